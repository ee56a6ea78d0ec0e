// Copyright (C) 2026 fsai developers
// Rank-0 logging: progress and results go to stdout on rank 0 only, warnings
// to stderr on rank 0. Per-rank debugging output goes through DOLFINx's LOG.
#pragma once

#include <fmt/core.h>
#include <mpi.h>

namespace fsai::log
{
/// Rank of this process in MPI_COMM_WORLD (0 before MPI is initialised)
int rank();

/// Print a line on rank 0 (stdout, flushed)
template <typename... Args>
void info(fmt::format_string<Args...> f, Args&&... args)
{
  if (rank() == 0)
  {
    fmt::print(stdout, f, std::forward<Args>(args)...);
    std::fputc('\n', stdout);
    std::fflush(stdout);
  }
}

/// Print "warning: ..." on rank 0 (stderr)
template <typename... Args>
void warn(fmt::format_string<Args...> f, Args&&... args)
{
  if (rank() == 0)
  {
    fmt::print(stderr, "warning: ");
    fmt::print(stderr, f, std::forward<Args>(args)...);
    std::fputc('\n', stderr);
  }
}
} // namespace fsai::log
