// Copyright (C) 2026 fsai developers
#pragma once

#include <chrono>
#include <mpi.h>
#include <nlohmann/json.hpp>
#include <string>

namespace fsai::io
{
/// The run's summary.json (docs/model.md §6): program, parameters in
/// effect, MPI size, `wall_s`, each rank's peak resident memory
/// (`peak_memory_mib_per_rank`), fsai timings and the scene's key results
/// under fixed names. Written by rank 0 atomically (temporary file +
/// rename), so readers never see a half-written file; write() may be called
/// repeatedly (e.g. at checkpoints) and at the end.
class RunSummary
{
public:
  /// Starts the wall clock
  RunSummary(MPI_Comm comm, std::string program);

  /// Parameters in effect (Parameters::to_json())
  void set_parameters(nlohmann::json parameters);

  /// Key result, e.g. set("f0_hz", 118.2)
  template <typename T>
  void set(const std::string& key, const T& value)
  {
    _results[key] = value;
  }

  /// Seconds since construction
  double wall_s() const;

  /// Write `path` (rank 0) with the current wall time and timings
  /// (collective)
  void write(const std::string& path) const;

  /// The JSON that write() would write (collective)
  nlohmann::json json() const;

private:
  MPI_Comm _comm;
  std::string _program;
  nlohmann::json _parameters = nlohmann::json::object();
  nlohmann::json _results = nlohmann::json::object();
  std::chrono::steady_clock::time_point _start;
};
} // namespace fsai::io
