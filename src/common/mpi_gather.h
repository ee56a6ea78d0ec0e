// Copyright (C) 2026 fsai developers
#pragma once
#include <dolfinx/common/MPI.h>
#include <mpi.h>
#include <vector>

namespace fsai::common
{
/// All ranks' `local` arrays (any length each), concatenated in rank order
/// on every rank (collective)
template <typename T>
std::vector<T> allgather(MPI_Comm comm, const std::vector<T>& local)
{
  int size = 1;
  MPI_Comm_size(comm, &size);
  int n = int(local.size());
  std::vector<int> counts(size), offsets(size + 1, 0);
  MPI_Allgather(&n, 1, MPI_INT, counts.data(), 1, MPI_INT, comm);
  for (int r = 0; r < size; ++r)
    offsets[r + 1] = offsets[r] + counts[r];
  std::vector<T> all(offsets[size]);
  MPI_Allgatherv(local.data(), n, dolfinx::MPI::mpi_type<T>(), all.data(),
                 counts.data(), offsets.data(), dolfinx::MPI::mpi_type<T>(),
                 comm);
  return all;
}
} // namespace fsai::common
