// Copyright (C) 2026 fsai developers
//
// The flow side of the FE glottis scene (docs/model.md §5), whatever moves the
// fold: the half-channel mesh (mesh::glottis_channel), the stabilised ALE
// Navier–Stokes flow (FluidSolver: E11a total-pressure inlet, directional
// do-nothing outlet, symmetry axis, fold and wall as moving / fixed walls), the
// mesh motion (MeshMotion) that follows a displacement of the fold surface, and
// the porous region Ω^P_t (cells whose current midpoint lies inside the moved
// fold). FlowGlottis drives it with the rigid 2-DOF fold,
// ElasticFlowGlottis with the elastic fold.
//
// The fluid boundary must stay above g_min (the caller lifts it, see
// boundary_lift); between it and the axis, under the medial surface, the
// "algebraic" gap motion moves columns of nodes with the boundary above
// them (set_interface), so the thin gap never inverts.
#pragma once
#include "FoldProfile.h"
#include <ale/MeshMotion.h>
#include <array>
#include <fluid/FluidSolver.h>
#include <functional>
#include <io/TimeSeriesWriter.h>
#include <memory>
#include <mesh/MeshData.h>
#include <mpi.h>
#include <span>
#include <vector>

namespace fsai::glottis
{
struct FlowGlottisParameters;

/// Vertical lift of the fluid boundary that keeps its lowest point g (the
/// fold's half-gap) above g_min: 0 for g ≥ 2 g_min, below it g_b − g with
/// g_b = g_min + b exp((g − g_min − b)/b), b = g_min (C¹), so the boundary
/// stays above g_min however far the fold crosses the axis
double boundary_lift(double g, double g_min);

class FlowChannel
{
public:
  /// Displacement of the fluid boundary at a reference point of the fold
  /// surface
  using SurfaceDisplacement
      = std::function<std::array<double, 2>(const std::array<double, 2>&)>;
  /// Map of a current point to the coordinates of the fold's outline
  using ToOutline
      = std::function<std::array<double, 2>(const std::array<double, 2>&)>;

  /// `curve`: empty for the channel around the profile at rest, else the
  /// fold surface's points (inferior to superior, without the attachments)
  /// of a channel meshed again around a moved fold, whose reference
  /// configuration is then that moved one (docs/model.md E13a)
  FlowChannel(MPI_Comm comm, const FoldProfile& profile,
              const FlowGlottisParameters& p, fluid::FluidParameters fp,
              const ale::MeshMotionParameters& ap,
              const std::vector<std::array<double, 2>>& curve = {});

  /// The accepted state of `old` (another mesh of the same channel, its
  /// mesh where the flow left it) onto this channel's reference mesh: the
  /// velocity, its BDF history and the pressure interpolated linearly at
  /// this mesh's nodes, the nodes' previous positions (for the BDF2 mesh
  /// velocity) likewise; the time and step count carried over. Returns
  /// the glottal and inlet flow rates before and after (the transfer's
  /// mass balance; collective)
  std::array<double, 4> transfer_from(FlowChannel& old);
  /// Reference and current positions of this rank's owned fold nodes
  std::vector<std::array<std::array<double, 2>, 2>> fold_nodes() const;

  /// Interface values of the mesh motion (fold nodes and gap columns) for
  /// the fluid boundary displacement u(X) of the fold's reference points
  void set_interface(const SurfaceDisplacement& u);
  /// Move the mesh by the extension of the set interface values (throws
  /// MeshInvertedError)
  ale::MeshQuality move(double t) { return _motion->move(t); }
  /// The extension of the set interface values, without moving
  std::vector<double> extension() { return _motion->extension(); }
  /// Move the mesh to X + d (d: an extension or combination of extensions)
  ale::MeshQuality move_to(std::span<const double> d, double t)
  {
    return _motion->move_to(d, t);
  }
  /// After a move: the mesh velocity of the step and the fold wall's
  /// velocity (the moving-wall condition) from it
  void set_wall_velocity();
  /// The porous indicator (G4) of the cells that may turn porous, by
  /// where their current midpoint lies against the moved fold, the closed
  /// polygon `outline` (to_outline maps a current point to its
  /// coordinates). δ = --closure.porous_ramp = 0: χ = 1 inside, 0 outside;
  /// δ > 0: by the depth d inside it, s = 1/2 + d/δ clamped to [0, 1],
  /// χ = χ_0^(1 − s) for s > 0 and 0 for s = 0, χ_0 = 0.01 ρ/(σ_P Δt_χ),
  /// Δt_χ = --closure.porous_floor_dt or the run's Δt.
  /// χ = 0 in the other cells
  void mark_porous(const std::vector<std::array<double, 2>>& outline,
                   const ToOutline& to_outline);
  /// The flow step to the current mesh, from the state saved at the start
  /// of the time step (repeated by every coupling iteration)
  void solve_flow();

  /// Fluid force on an owned fold node, times the depth L_g [N]
  struct NodalForce
  {
    std::array<double, 2> X; ///< reference position
    std::array<double, 2> f;
  };
  /// Consistent nodal forces of the flow on this rank's owned fold nodes
  /// (E12)
  std::vector<NodalForce> fold_forces();
  /// Pressure at this rank's owned fold nodes, by reference position
  /// (x, y, p per node)
  std::vector<double> fold_pressure() const;
  /// Current positions of this rank's owned fold nodes of the fluid
  /// boundary
  std::vector<std::array<double, 2>> fold_boundary() const;
  /// Inlet flux and glottal flow through the section x = medial_x, both
  /// folds, times L_g [m³/s] (collective)
  std::array<double, 2> flow_rates();

  /// The mesh motion's accepted state becomes the history (end of a step)
  void advance() { _motion->advance(); }
  /// Flow and mesh back at the last accepted step
  void rewind();
  /// Adds the accepted flow ("flow.") and mesh motion ("ale.") of this rank
  /// to a checkpoint's state
  void save(io::RankState& state) const;
  /// Restores what save() wrote, from the states of all ranks of the
  /// checkpoint (throws on a mismatch; callers wrap it in io::on_every_rank)
  void load(const std::vector<io::RankState>& ranks);

  fluid::FluidSolver& flow() { return *_flow; }
  const fluid::FluidSolver& flow() const { return *_flow; }
  const ale::MeshMotion& motion() const { return *_motion; }
  ale::MeshMotion& motion() { return *_motion; }
  bool linear_motion() const { return _motion->linear(); }
  std::int64_t cells() const;
  /// Fewest and most cells owned by one rank (collective)
  std::array<std::int64_t, 2> cells_per_rank() const;
  /// Reference coordinates of the velocity dof blocks (3 per block)
  const std::vector<double>& reference_coordinates() const { return _X_ref; }
  /// The fields of the flow's XDMF output: velocity, pressure, porous
  /// indicator, mesh displacement
  std::vector<io::TimeSeriesWriter::Field> fields() const;
  /// Logs the mesh size (cells, per rank, flow dofs) and returns the flow
  /// dofs (collective)
  std::int64_t describe() const;

private:
  MPI_Comm _comm;
  const FoldProfile& _profile;
  double _porous_ramp; // δ of mark_porous [m]
  double _chi_floor;   // χ_0 of mark_porous
  mesh::MeshData _mesh;
  std::vector<std::int32_t> _fold_facets, _inlet_facets;
  /// Fold facets upstream of the glottal section x = medial_x (reference
  /// midpoint): the flow through that section is the inlet flux minus the
  /// volume these moving walls displace
  std::vector<std::int32_t> _upstream_fold_facets;
  std::unique_ptr<fluid::FluidSolver> _flow;
  std::unique_ptr<ale::MeshMotion> _motion;
  std::shared_ptr<dolfinx::fem::Function<double>> _F; // nodal forces
  std::vector<std::int32_t> _fold_dofs; // velocity-space blocks on the fold
  std::vector<std::array<double, 2>> _fold_X; // their reference coordinates
  std::vector<double> _X_ref;                 // all velocity blocks, reference
  /// Owned pressure dofs on the fold and their reference coordinates
  std::vector<std::int32_t> _fold_p_dofs;
  std::vector<std::array<double, 2>> _fold_p_X;
  /// Algebraic gap motion: dof blocks under the medial region
  std::vector<std::int32_t> _gap_dofs;
  /// the two boundary nodes (reference) above each, the position t between
  /// them and the height fraction under their chord
  std::vector<std::array<std::array<double, 2>, 2>> _gap_nodes;
  std::vector<double> _gap_t, _gap_fraction;
  std::vector<std::int32_t> _candidates; // cells that may turn porous
};
} // namespace fsai::glottis
