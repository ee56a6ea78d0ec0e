// Copyright (C) 2026 fsai developers
//
// The glottis scene with the elastic fold (ElasticFold) in the FE flow
// (FlowChannel): `fsai_glottis --flow fe --fold elastic`. The
// closure model of the 2-DOF scene (docs/model.md §5) with a deforming surface
// instead of a rigid one:
//   - the fluid boundary is the fold surface, lifted as a whole (tapered
//     to the wall) by boundary_lift(g, g_min) when the fold's half-gap g
//     comes below 2 g_min, so the fluid mesh never collapses (or, with
//     --closure.lift local, around the points below 2 g_min only);
//   - Ω^P_t: the cells whose current midpoint lies inside the deformed
//     fold (its moved surface polyline closed along the wall) are porous;
//   - contact with the axis is the fold's own penalty contact (inside its
//     Newton solve), as with the Bernoulli flow.
// The two meshes (the channel at h_gap, the fold at elastic.h_surface)
// meet on the same profile curve but not at the same nodes: both
// directions of the transfer go by the arc length along the profile
// (FoldProfile::arc_length), the fold's surface displacement interpolated
// linearly between its P2 surface dofs onto the fluid nodes, the fluid
// pressure (P1, at the fold nodes of the fluid boundary) interpolated onto
// the fold's surface dofs as the traction −p n. The viscous traction is
// left out of the fold's load: it is the shear τ ~ μ U/g, of order
// μ·30 m/s / 0.1 mm ≈ 5 Pa against pressures of 1 kPa (the summary's
// lift/drag are the full consistent nodal forces, E12).
//
// Each time step: the interface variable is the fold's surface
// displacement (owned dofs of each rank); the map H moves the fluid
// boundary and mesh to it, marks Ω^P_t, solves one flow step, and solves
// the fold's Newmark step under the fluid pressure. The coupling is
// implicit by default: FixedPointCoupling (IQN-ILS) iterates H to the
// [coupling] tolerance. An explicit coupling (one H per step,
// --elastic.coupling explicit) diverges: although air is 1/800 of the
// fold's density, moving the surface moves the air of the whole channel,
// an added mass far above that of the fold's surface layer (lift grew
// ×3–4 per step from the first step; a cell inverted at step 13).
// First guess (coupling.predictor = "load", as for the 2-DOF fold): the
// fold's step under the surface pressure extrapolated linearly from the
// last two steps, error O(Δt² p''); "displacement": the Newmark predictor
// u + Δt v + ½Δt² a.
//
// Remeshing (--fe.remesh_quality q > 0, docs/model.md E13a): when
// an accepted step leaves a cell below the scaled Jacobian q, or a move
// inverts one (the step is then repeated once on the new mesh), the
// channel is meshed again with the fold surface where the fluid boundary
// is, and the flow state is transferred (FlowChannel::transfer_from). The
// new fluid boundary nodes take the arc length of their nearest point on
// the old boundary, and from then on move by the fold's displacement
// since the remeshing (u − u_r, and the lift's change).
//
// Step cuts (--fe.step_cuts n > 0, docs/model.md E13b): an attempt whose
// coupling does not converge, or whose move inverts a cell, is discarded
// and the step taken as two halves (each of which may be cut again, n
// levels); the flow's BDF2 and mesh velocity follow the variable grid
// (E19), and after a coupling failure the halves start IQN-ILS afresh
// (--fe.cut_history clear). Only the last level remeshes at an inverted
// cell or accepts an unconverged step. The caller sees one step of Δt.
#pragma once
#include "ElasticFold.h"
#include "FlowChannel.h"
#include "FlowGlottis.h"
#include "GlottisModel.h"
#include "Sample.h"
#include <array>
#include <coupling/FixedPointCoupling.h>
#include <map>
#include <memory>

namespace fsai::glottis
{
/// Moves the fold surface points x below the wall y = H and out of the
/// wedges narrower than `angle` [°] at the attachments (0, H) and (T, H)
/// on the fluid's side of each (G3a; angle 0: unchanged)
void keep_out_of_wedges(std::vector<std::array<double, 2>>& x,
                        const GlottisGeometry& g, double angle);

class ElasticFlowGlottis : public GlottisModel
{
public:
  ElasticFlowGlottis(MPI_Comm comm, const FoldProfile& profile,
                     const ElasticFoldParameters& ep,
                     const ContactParameters& contact,
                     const FlowGlottisParameters& p, fluid::FluidParameters fp,
                     const ale::MeshMotionParameters& ap,
                     const coupling::CouplingParameters& cp,
                     const std::string& coupling_csv,
                     std::size_t coupling_rows_kept = std::string::npos);
  /// One coupled time step
  Sample step() override;
  /// The accepted state (flow, mesh motion, fold, the surface pressures of
  /// the load predictor, time) for a checkpoint (this rank's part); load()
  /// continues from the parts of all the checkpoint's ranks
  /// (coupling_rows_kept = the checkpoint's step keeps coupling.csv's
  /// rows). As with the Bernoulli flow, the coupling's history of earlier
  /// steps is forgotten at a checkpoint, not saved.
  io::RankState save();
  void load(const std::vector<io::RankState>& ranks);
  double time() const override { return _t; }
  void checkpoint(nlohmann::json& scalars,
                  std::optional<io::RankState>& fields) override;
  void restore(const nlohmann::json& checkpoint,
               const std::vector<io::RankState>& fields) override;
  std::vector<io::TimeSeriesWriter::Field> flow_fields() const override;
  std::vector<io::TimeSeriesWriter::Field> fold_fields() override;
  void describe(io::RunSummary& summary) override;
  ElasticFold& fold() { return _fold; }
  ElasticFold* elastic_fold() override { return &_fold; }
  const ElasticFold* elastic_fold() const override { return &_fold; }
  /// Pressure at the fold's ordered surface points (the fold's load, traction
  /// −p n) of the last evaluation [Pa]
  const std::vector<double>& surface_load() const { return _p; }
  /// The flow side: mesh, flow, mesh motion, output fields
  const FlowChannel& channel() const { return *_channel; }
  const FlowChannel* flow_channel() const override { return _channel.get(); }
  int remeshes() const override { return _remesh.count; }
  void report(io::RunSummary& summary) const override;
  /// After a failed step: flow and mesh back at the last accepted step,
  /// whose fields (flow, porous indicator, mesh displacement) are written to
  /// the XDMF file `path`
  std::optional<double> write_last_good(const std::string& path) override;

private:
  /// Fluid boundary, mesh, mesh velocity and Ω^P_t for the moved fold
  /// surface x (all ordered points)
  void move_boundary(double t, std::vector<std::array<double, 2>> x);

  /// The fluid pressure at the fold's ordered surface points
  std::vector<double> surface_pressure();
  /// Arc length of a reference point of the fluid's fold boundary (cached:
  /// the same fluid nodes are asked at every move)
  double arc_length(const std::array<double, 2>& X);
  /// The channel meshed again around the fold as it is, with the accepted
  /// flow state (after an accepted step)
  void remesh();
  /// The channel of the remeshed boundary `_remesh.curve` (no state)
  std::unique_ptr<FlowChannel> make_channel() const;

  MPI_Comm _comm;
  const FoldProfile& _profile;
  FlowGlottisParameters _par;
  ElasticFold _fold;
  fluid::FluidParameters _fp;
  ale::MeshMotionParameters _ap;
  std::unique_ptr<FlowChannel> _channel;
  bool _explicit;
  /// The fluid boundary of the last remeshing: its points as meshed (by
  /// arc length s), the fold's surface displacement and lift then
  struct Remeshing
  {
    int count = 0;
    std::vector<std::array<double, 2>> curve;
    std::vector<double> s;
    std::vector<std::array<double, 2>> u;
    double lift = 0;
  } _remesh;
  double _quality = 1;     ///< min scaled Jacobian of the last move
  double _min_quality = 1; ///< over the accepted steps
  coupling::FixedPointCoupling _loop;
  std::vector<double> _s; ///< arc length of the fold's ordered points
  std::vector<double> _w; ///< their taper weights
  /// The lift of the fluid boundary above each fold point, --closure.lift
  /// local
  std::vector<double>
  local_lifts(const std::vector<std::array<double, 2>>& x) const;
  std::map<std::array<double, 2>, double> _arc_cache;
  /// Gathered fluid pressure nodes: their order by arc length and arc
  /// lengths (set at the first call)
  std::vector<std::size_t> _p_order;
  std::vector<double> _p_s;
  /// Surface pressure of the last evaluation and of the last two accepted
  /// steps (the "load" predictor)
  std::vector<double> _p, _p_n, _p_nn;
  /// The first guess of the step's surface displacement
  std::vector<double> predict();
  /// The accepted state advanced by dt, cut into halves where an attempt
  /// fails (`cuts` levels so far, E13b); its coupling reports summed into
  /// `total`
  void advance(double dt, int cuts, coupling::StepReport& total);
  /// One coupled step of length dt on the current mesh, its coupling
  /// report added to `total`; false: the coupling did not converge and
  /// `may_retry` (the state is back at the step's start)
  bool attempt(double dt, bool may_retry, coupling::StepReport& total);
  /// The sample of the accepted state (the step's coupling report `rep`)
  Sample sample(const coupling::StepReport& rep);
  int _step_cuts = 0; ///< attempts taken again as two halves
  /// The flow's refined solves and refinement fallbacks on the meshes
  /// before the current one (FluidParameters::refine_rtol)
  std::array<int, 2> _refines_before{0, 0};
  /// Refined solves and fallbacks over the run (all meshes)
  std::array<int, 2> refine_counts() const;
  /// The moved fold surface of the last move and of the accepted step
  std::vector<std::array<double, 2>> _x_moved, _x_accepted;
  int _steps = 0;
  double _t = 0;
};
} // namespace fsai::glottis
