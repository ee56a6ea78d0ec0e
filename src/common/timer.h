// Copyright (C) 2026 fsai developers
// Scoped wall-clock timers. They feed DOLFINx's timing registry (so
// dolfinx::list_timings shows them next to DOLFINx's own tasks) and remember
// the task names so the run summary can report fsai's own timings.
#pragma once

#include <dolfinx/common/Timer.h>
#include <mpi.h>
#include <nlohmann/json.hpp>
#include <string>

namespace fsai::common
{
/// Timer that records under `task` when it goes out of scope. Name tasks
/// "<module>: <what>", e.g. "fluid: assemble".
class ScopedTimer
{
public:
  explicit ScopedTimer(const std::string& task);
  /// Stop early (before scope exit)
  void stop() { _timer.stop(); }

private:
  dolfinx::common::Timer _timer;
};

/// {task: {"count": n, "wall_s": total}} for every task timed by ScopedTimer
/// on this rank
nlohmann::json timings_json();

/// Print the table of all timings (max over ranks) on rank 0
void print_timings(MPI_Comm comm);
} // namespace fsai::common
