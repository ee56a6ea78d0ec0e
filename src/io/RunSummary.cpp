// Copyright (C) 2026 fsai developers
#include "RunSummary.h"
#include "../common/timer.h"
#include "output_dir.h"
#include <filesystem>
#include <fstream>
#include <sys/resource.h>
#include <vector>

namespace
{
/// Each rank's peak resident memory so far [MiB] (getrusage; Linux reports
/// ru_maxrss in KiB), on every rank
std::vector<double> peak_memory_mib(MPI_Comm comm)
{
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  const double mine = static_cast<double>(usage.ru_maxrss) / 1024.0;
  int size = 1;
  MPI_Comm_size(comm, &size);
  std::vector<double> all(size);
  MPI_Allgather(&mine, 1, MPI_DOUBLE, all.data(), 1, MPI_DOUBLE, comm);
  return all;
}
} // namespace

//-----------------------------------------------------------------------------
fsai::io::RunSummary::RunSummary(MPI_Comm comm, std::string program)
    : _comm(comm), _program(std::move(program)),
      _start(std::chrono::steady_clock::now())
{
}
//-----------------------------------------------------------------------------
void fsai::io::RunSummary::set_parameters(nlohmann::json parameters)
{
  _parameters = std::move(parameters);
}
//-----------------------------------------------------------------------------
double fsai::io::RunSummary::wall_s() const
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now()
                                       - _start)
      .count();
}
//-----------------------------------------------------------------------------
nlohmann::json fsai::io::RunSummary::json() const
{
  int size = 1;
  MPI_Comm_size(_comm, &size);
  nlohmann::json j = _results;
  j["program"] = _program;
  j["parameters"] = _parameters;
  j["mpi_size"] = size;
  j["wall_s"] = wall_s();
  j["peak_memory_mib_per_rank"] = peak_memory_mib(_comm);
  j["timings"] = common::timings_json();
  return j;
}
//-----------------------------------------------------------------------------
void fsai::io::RunSummary::write(const std::string& path) const
{
  const nlohmann::json j = json();
  int rank = 0;
  MPI_Comm_rank(_comm, &rank);
  if (rank != 0)
    return;
  ensure_parent_dir(path);
  const std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp);
    out << j.dump(2) << '\n';
    if (!out)
      throw std::runtime_error("cannot write '" + tmp + "' (disk full?)");
  }
  std::filesystem::rename(tmp, path);
}
//-----------------------------------------------------------------------------
