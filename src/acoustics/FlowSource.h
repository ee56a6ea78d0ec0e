// Copyright (C) 2026 fsai developers
//
// Transfer of the flow velocity to the acoustic mesh for Lighthill's source
// T_ij = χ ρ0 v_i v_j (docs/model.md E14, E15). The acoustic
// domain contains the flow domain in its reference configuration Ω^f_0, and
// the source is evaluated there (the flow mesh moves by ALE, the acoustic
// mesh does not): a node of the acoustic mesh at X takes the flow velocity
// of the flow-mesh point whose reference position is X, by linear
// interpolation in the reference flow triangle containing X. The two meshes
// need not match.
//
// Parallel: the flow mesh's reference triangles and, each step, its P1
// velocity (16k dofs in the glottis scene) are gathered to every rank, so
// every rank interpolates its own acoustic nodes (owned and ghost) from the
// same data; the result does not depend on the partition.
#pragma once
#include <array>
#include <cstdint>
#include <dolfinx/fem/Function.h>
#include <dolfinx/fem/FunctionSpace.h>
#include <mpi.h>
#include <span>
#include <vector>

namespace fsai::acoustics
{
class FlowSource
{
public:
  /// @param[in] comm Communicator of both meshes
  /// @param[in] Vf Flow velocity space (P1 vector, 2D)
  /// @param[in] X_ref Reference coordinates of Vf's dof blocks (owned and
  ///   ghost, 3 per block, as tabulate_dof_coordinates before any motion)
  /// @param[in] Va Acoustic P1 vector space (WaveSolver::flow_velocity)
  FlowSource(MPI_Comm comm, const dolfinx::fem::FunctionSpace& Vf,
             std::span<const double> X_ref,
             const dolfinx::fem::FunctionSpace& Va);

  /// v_a ← the flow velocity v_f at the acoustic nodes inside Ω^f_0, zero
  /// elsewhere (collective)
  void transfer(const dolfinx::fem::Function<double>& v_f,
                dolfinx::fem::Function<double>& v_a);

  /// Local acoustic dof blocks that lie in the flow domain
  std::size_t covered() const { return _nodes.size(); }

private:
  MPI_Comm _comm;
  std::vector<int> _counts, _offsets; // velocity values per rank (2 per block)
  std::vector<double> _v_global;      // gathered flow velocity
  /// Acoustic dof block, the three global flow blocks and their weights
  struct Node
  {
    std::int32_t block;
    std::array<std::int64_t, 3> flow;
    std::array<double, 3> weight;
  };
  std::vector<Node> _nodes;
};
} // namespace fsai::acoustics
