// Copyright (C) 2026 fsai developers
//
// One time step of the strongly coupled partitioned FSI scheme (docs/model.md
// §3, loop O–V; docs/model.md §3, E12, E13). The interface variable x is the
// interface displacement at the fluid's interface vertices (owned entries,
// distributed); one evaluation of the fixed-point map H(x) is
//   1. ALE: the fluid mesh follows x (MeshMotion), mesh velocity w (BDF);
//   2. flow: the interface is a wall moving with w; one BDF step from the
//      step's saved state;
//   3. load: nodal forces of the fluid on the interface (the weak-form
//      residual, E12) divided by the lumped reference interface mass give
//      the nominal traction, handed to the solid's P2 trace (InterfaceMap);
//   4. structure: one Newmark step from the step's saved state;
//   5. H(x) = the solid's interface displacement at the fluid vertices.
// FixedPointCoupling iterates H with the chosen accelerator; the predictor
// is the linear extrapolation of the last two accepted interface
// displacements.
#pragma once

#include "FixedPointCoupling.h"
#include "InterfaceMap.h"
#include <ale/MeshMotion.h>
#include <fluid/FluidSolver.h>
#include <structure/ElasticSolver.h>

namespace fsai::coupling
{
class PartitionedFsi
{
public:
  /// @param[in] fluid_interface Fluid facets of the interface (local)
  /// @param[in] csv_path Per-step coupling log (empty: none)
  /// @param[in] csv_rows_kept Rows of an existing log kept (a restart:
  ///   io::RunLoop::rows_kept()); npos: a new log
  PartitionedFsi(fluid::FluidSolver& flow, structure::ElasticSolver& solid,
                 ale::MeshMotion& motion, const InterfaceMap& map,
                 std::span<const std::int32_t> fluid_interface,
                 const CouplingParameters& p, const std::string& csv_path,
                 std::size_t csv_rows_kept = std::string::npos);

  /// Advance flow, structure and mesh from t − Δt to t (the flow's and the
  /// solid's Δt must agree)
  StepReport step(double t);

  /// The accepted interface displacements of the last two steps (the
  /// predictor's) into / from a checkpoint (any partition); the
  /// accelerator's reused columns are not kept (a restarted step starts
  /// without them, as after clear_history())
  void save(io::RankState& state, const std::string& prefix) const;
  void load(const std::vector<io::RankState>& ranks, const std::string& prefix);
  /// Forget the accelerator's columns of earlier steps (at a checkpoint,
  /// so that a restarted run continues as the uninterrupted one)
  void clear_history() { _loop.clear_history(); }

private:
  fluid::FluidSolver& _flow;
  structure::ElasticSolver& _solid;
  ale::MeshMotion& _motion;
  const InterfaceMap& _map;
  FixedPointCoupling _loop;
  std::vector<std::int32_t> _facets; // fluid interface facets
  std::vector<std::int32_t> _owned;  // owned fluid interface dof blocks
  std::vector<double> _inv_mass;     // 1 / lumped mass at _owned (× bs)
  std::vector<double> _x_n, _x_nn;   // accepted interface displacements
  int _accepted = 0;
  std::shared_ptr<dolfinx::fem::Function<double>> _d, _F;

  void evaluate(double t, std::span<const double> x, std::span<double> Hx);
  std::vector<std::int64_t> owned_keys() const;
};
} // namespace fsai::coupling
