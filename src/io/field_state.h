// Copyright (C) 2026 fsai developers
//
// FE fields in checkpoints, independent of the partition: each rank stores
// its owned dof blocks with partition-independent keys (the input index of
// the mesh node of a P1 dof block, the input index of a cell), and a restart
// fills every local block (owned and ghost) from all the checkpoint's
// ranks. The mesh partitioner (PT-SCOTCH) does not give the same partition
// twice, so rank-local arrays cannot be read back as they are; the number
// of ranks may also differ between a run and its restart.
#pragma once
#include "run_state.h"
#include <cstdint>
#include <dolfinx/fem/FunctionSpace.h>
#include <dolfinx/mesh/Mesh.h>
#include <span>
#include <string>
#include <vector>

namespace fsai::io
{
/// Keys of the local dof blocks (owned, then ghost) of a P1 or P2 space on
/// a P1 mesh: the input index of the mesh node at each vertex block; an
/// edge block (P2) has −2 − (b(b+1)/2 + a) for the input indices a < b of
/// its vertices
std::vector<std::int64_t> node_keys(const dolfinx::fem::FunctionSpace& V);

/// Keys of the local cells (owned, then ghost): their input index
std::vector<std::int64_t> cell_keys(const dolfinx::mesh::Mesh& mesh);

/// Store the first `owned` blocks of `values` (block size bs) under `name`,
/// with their keys under name + "#keys"
void put_blocks(RankState& state, const std::string& name,
                std::span<const double> values, int bs,
                std::span<const std::int64_t> keys, std::int32_t owned);

/// Fill every block of `values` (one per key) from the blocks stored under
/// `name` by any of the checkpoint's ranks; InputError if a block is not
/// found (another mesh)
void get_blocks(const std::vector<RankState>& ranks, const std::string& name,
                std::span<double> values, int bs,
                std::span<const std::int64_t> keys);

/// The rank states `<stem>.r<k>.bin`, k < nranks, written by a run on
/// `nranks` ranks, all read on every rank
std::vector<RankState>
read_all_rank_states(MPI_Comm comm, const std::string& stem, int nranks);
} // namespace fsai::io
