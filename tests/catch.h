// Copyright (C) 2026 fsai developers
// Include this instead of <catch2/catch.hpp> in every test file.
//
// NOTE(DOLFINx 0.5.2): dolfinx/common/log.h (loguru, glog mode) defines a
// CHECK macro that aborts the process. Including it first, then dropping
// its CHECK, lets Catch2's CHECK win in every test file whatever the order
// of the includes that follow (log.h has an include guard).
#pragma once

#include <dolfinx/common/log.h>
#undef CHECK
#include <catch2/catch.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <filesystem>
#include <mpi.h>
#include <string>
#include <unistd.h>
#include <vector>

namespace fsai::test
{
/// A scratch folder with the same path on every rank of MPI_COMM_WORLD,
/// removed (by rank 0, after a barrier) when it goes out of scope
class TempDir
{
public:
  TempDir()
  {
    std::string pid = std::to_string(getpid());
    pid.resize(16, ' ');
    MPI_Bcast(pid.data(), 16, MPI_CHAR, 0, MPI_COMM_WORLD);
    pid.erase(pid.find(' '));
    _path = std::filesystem::temp_directory_path()
            / ("fsai_test_" + pid + "_" + std::to_string(_counter++));
    std::filesystem::create_directories(_path);
  }
  ~TempDir()
  {
    MPI_Barrier(MPI_COMM_WORLD);
    int rank = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    std::error_code ec;
    if (rank == 0)
      std::filesystem::remove_all(_path, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  /// Path of `name` inside the folder
  std::string operator/(const std::string& name) const
  {
    return (_path / name).string();
  }

private:
  std::filesystem::path _path;
  static inline int _counter = 0;
};

/// {max |a − b|, max |a|} over all ranks of MPI_COMM_WORLD (a, b: the same
/// local dofs of two runs)
inline std::array<double, 2> max_difference(const std::vector<double>& a,
                                            const std::vector<double>& b)
{
  std::array<double, 2> l{0, 0}, g;
  for (std::size_t i = 0; i < a.size(); ++i)
    l[0] = std::max(l[0], std::abs(a[i] - b[i])),
    l[1] = std::max(l[1], std::abs(a[i]));
  MPI_Allreduce(l.data(), g.data(), 2, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  return g;
}
} // namespace fsai::test
