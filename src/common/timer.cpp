// Copyright (C) 2026 fsai developers
#include "timer.h"
#include <cstdio>
#include <dolfinx/common/timing.h>
#include <set>
#include <tuple>
#include <vector>

namespace
{
std::set<std::string>& task_names()
{
  static std::set<std::string> names;
  return names;
}
} // namespace

//-----------------------------------------------------------------------------
fsai::common::ScopedTimer::ScopedTimer(const std::string& task)
    : _timer("fsai " + task)
{
  task_names().insert(task);
}
//-----------------------------------------------------------------------------
nlohmann::json fsai::common::timings_json()
{
  nlohmann::json out = nlohmann::json::object();
  for (const std::string& task : task_names())
  {
    try
    {
      auto [count, wall, user, sys] = dolfinx::timing("fsai " + task);
      out[task] = {{"count", count}, {"wall_s", wall}};
    }
    catch (const std::runtime_error&)
    {
      // Timer still running (no record yet): nothing to report
    }
  }
  return out;
}
//-----------------------------------------------------------------------------
void fsai::common::print_timings(MPI_Comm comm)
{
  // fsai's own tasks only (DOLFINx's full table: dolfinx::list_timings),
  // max over ranks; every rank must have timed the same tasks
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  std::vector<double> wall;
  std::vector<std::size_t> count;
  for (const std::string& task : task_names())
  {
    double w = 0.0;
    std::size_t c = 0;
    try
    {
      std::tie(c, w, std::ignore, std::ignore)
          = dolfinx::timing("fsai " + task);
    }
    catch (const std::runtime_error&)
    {
    }
    wall.push_back(w);
    count.push_back(c);
  }
  std::vector<double> wall_max(wall.size());
  MPI_Reduce(wall.data(), wall_max.data(), static_cast<int>(wall.size()),
             MPI_DOUBLE, MPI_MAX, 0, comm);
  if (rank != 0 or wall.empty())
    return;
  std::printf("\n%-36s %8s %12s %12s\n", "timer (max over ranks)", "count",
              "total [s]", "mean [s]");
  std::size_t i = 0;
  for (const std::string& task : task_names())
  {
    std::printf("%-36s %8zu %12.4f %12.6f\n", task.c_str(), count[i],
                wall_max[i], count[i] ? wall_max[i] / count[i] : 0.0);
    ++i;
  }
  std::fflush(stdout);
}
//-----------------------------------------------------------------------------
