// Copyright (C) 2026 fsai developers
//
// The glottis scene with the FE flow (docs/model.md §5): stabilised P1/P1 ALE
// Navier–Stokes (FluidSolver) in the symmetric half-channel
// (mesh::glottis_channel), driven by the subglottal pressure through the E11a
// inlet (ε large: total pressure p_sub), directional do-nothing outlet,
// symmetry axis y = 0; the 2-DOF fold (TwoDofFold) moves the fold boundary;
// Hertz impact (HertzContact).
//
// Closure model: the fluid boundary follows the fold but never comes closer
// to the axis than g_min (below 2 g_min its height is compressed smoothly
// towards g_min, keeping the boundary nodes in order), so the fluid mesh
// never collapses; the cells the fold would occupy (inside the
// moved rigid profile) form the porous region Ω^P_t, marked cell-wise
// (χ = 1) each coupling iteration, where the term σ_P χ (v − w) stops the
// flow. Too small σ_P leaks, too large σ_P or g_min → 0 ruins the
// conditioning (--fluid.sigma_p, --closure.g_min sweeps in bench/).
//
// Each time step is a strongly coupled fixed point on (h, ℓφ) (ℓ = 1 mm
// scales the rotation to a displacement): move the fold boundary and the
// mesh (MeshMotion), update χ, one flow step, generalised forces from the
// fluid's nodal forces on the fold (consistent, E12) with the tapered
// virtual displacements, plus Hertz, one Newmark step of the fold
// (FixedPointCoupling: Aitken or IQN-ILS, as for Turek–Hron).
#pragma once
#include "FlowChannel.h"
#include "FoldProfile.h"
#include "GlottisModel.h"
#include "HertzContact.h"
#include "Sample.h"
#include "TwoDofFold.h"
#include <ale/MeshMotion.h>
#include <coupling/FixedPointCoupling.h>
#include <fluid/FluidSolver.h>
#include <memory>
#include <mesh/MeshData.h>
#include <mesh/glottis_channel.h>
#include <mpi.h>

namespace fsai::common
{
class Parameters;
}

namespace fsai::glottis
{
/// [fe] and [closure] sections
struct FlowGlottisParameters
{
  double p_sub = 800; ///< subglottal pressure [Pa]
  double ramp = 5e-3; ///< p_sub ramps up smoothly over this time [s]
  double dt = 2e-5;   ///< time step [s]
  /// Mesh sizes of the channel (--fe.h_far, --fe.h_gap, ...), passed
  /// whole to mesh::glottis_channel
  mesh::ChannelSizes sizes;
  double g_min = 0.02e-3; ///< closest approach of the fluid boundary [m]
  /// Width δ over which the porous indicator χ of a cell rises from 0 to 1
  /// with the depth of its midpoint inside the moved fold (G4; 0: χ
  /// switches from 0 to 1 as the midpoint enters the fold) [m]
  double porous_ramp = 0.0;
  /// The step Δt_χ of the ramp's floor χ_0 = 0.01 ρ/(σ_P Δt_χ) (G4) [s];
  /// 0: the run's Δt (the porous model then changes with Δt; a Δt study
  /// holds it fixed with this)
  double porous_floor_dt = 0.0;
  /// Mesh motion of the gap between the medial surface and the axis:
  /// "algebraic" (each node keeps its height fraction y/y_s under the
  /// surface point above it; the rest of the mesh by the elastic
  /// extension) or "elastic" (all by the extension)
  std::string gap_motion = "algebraic";
  /// "algebraic": the columns moved algebraically are those whose top (the
  /// fold boundary above them) is at most g0 + gap_columns·R from the axis
  /// (R the edge radius); the rest follows the elastic extension. Not R:
  /// where the columns reach the steep superior surface the column band
  /// shifted horizontally with the fold meets the extension at a kink, and
  /// a rotation of 0.09 rad inverted a cell there on the 0.035 mm mesh
  /// (replays of computed fold trajectories, --replay: min scaled Jacobian
  /// 7.7e-4 with R, 0.227 with 0.75 R or 0.5 R at that state; 0.75 R kept
  /// 0.074 vs 0.043 for 0.5 R through a 1600 Pa start-up)
  double gap_columns = 0.75;
  /// First guess of (h, φ) each step: "load" (a Newmark step of the fold
  /// under the fluid load extrapolated linearly from the last two steps,
  /// plus the Hertz force at the extrapolated state: its error is
  /// O(Δt⁴ F''/m), so a heavy fold's first coupling residual is already
  /// below the tolerance) or "displacement" (linear extrapolation of
  /// (h, φ), error O(Δt² q''): every step needs a second flow solve)
  std::string predictor = "load";
  /// Move the mesh by superposition: the fluid boundary's displacement
  /// (tapered rigid motion plus lift, and the algebraic gap columns that
  /// follow it) is (cos φ − 1) B₁ + sin φ B₂ + (lift − h) B₃ for three
  /// fixed fields B, so a linear extension of it is the same combination
  /// of their three extensions, computed once (no solve per move). Off:
  /// solve the extension at every move (the same mesh to round-off)
  bool superpose_motion = true;
  /// Elastic fold: after a step whose mesh has a cell below this scaled
  /// Jacobian while the half-gap exceeds 2 h_gap (or when a move inverts a
  /// cell), the channel is meshed again on the fold surface as it is and
  /// the flow state moved onto the new mesh (docs/model.md E13a); 0: never
  double remesh_quality = 0.0;
  /// Elastic fold: a step whose coupling does not converge, or whose move
  /// inverts a fluid cell, is discarded and taken as two of half the
  /// length, at most this many times in a row (Δt/2^n; docs/model.md
  /// E13b); 0: never (an inverted cell remeshes, an unconverged step is
  /// accepted with a warning, as at the last level)
  int step_cuts = 0;
  /// Elastic fold, step cuts: "clear": the halves of a discarded attempt
  /// start IQN-ILS afresh (no reused columns, like a first step), since
  /// the secant columns that led the attempt astray (a reopening after the
  /// closed phase) would mislead them too; "keep": they reuse them (at
  /// 1200 Pa, 50 steps unconverged at Δt/4 instead of 5: docs/glottis.md)
  std::string cut_history = "clear";
  /// Elastic fold: how the fluid boundary is kept above g_min (G3).
  /// "uniform": the whole surface lifted by boundary_lift of its lowest
  /// point (tapered to the wall); "local": each surface point's own
  /// boundary_lift spread along the surface by a Gaussian of width R/2
  /// (the largest of the points' spread lifts), so that in the closed
  /// phase the contact point's motion does not move the whole fluid
  /// boundary
  std::string lift = "uniform";
  /// Elastic fold: the smallest angle [°] of the fluid's corner between
  /// the fold surface and the wall at each attachment (0: none). A soft
  /// fold's superior surface can roll onto the wall at its attachment
  /// (the linear fold does not feel the wall), which closes the fluid's
  /// corner there; the fluid boundary is kept out of the narrower wedge
  /// (G3a), as the lift keeps it off the axis
  double wedge_angle = 30;
  void bind(fsai::common::Parameters& p);
  void validate() const;
};

/// Everything the FE glottis scene is built from ([glottis], [vf],
/// [contact], [fe], [closure], [fluid], [ale], [coupling] sections), with
/// the scene's defaults: fsai_glottis and fsai_demo both start from it (the
/// command line may override any of it)
struct FlowGlottisSetup
{
  GlottisGeometry geometry;
  TwoDofParameters fold;
  ContactParameters contact;
  FlowGlottisParameters fe;
  fluid::FluidParameters fluid;
  ale::MeshMotionParameters ale;
  coupling::CouplingParameters coupling;

  FlowGlottisSetup();
  void bind(fsai::common::Parameters& p);
  /// Validate every part, with the scene's subglottal pressure and step
  void validate(double p_sub, double dt);
};

class FlowGlottis : public GlottisModel
{
public:
  FlowGlottis(MPI_Comm comm, const FoldProfile& profile,
              const TwoDofParameters& vf, const ContactParameters& contact,
              const FlowGlottisParameters& p, fluid::FluidParameters fp,
              const ale::MeshMotionParameters& ap,
              const coupling::CouplingParameters& cp,
              const std::string& coupling_csv,
              std::size_t coupling_rows_kept = std::string::npos);
  /// One coupled time step
  Sample step() override;
  /// The accepted state after the last step (flow, mesh motion, fold,
  /// coupling history) for a checkpoint (this rank's part); load()
  /// continues from the parts of all the checkpoint's ranks (the scene
  /// must be built with the same parameters, on any number of ranks;
  /// coupling_rows_kept = the checkpoint's step keeps coupling.csv's rows)
  io::RankState save() const;
  void load(const std::vector<io::RankState>& ranks);
  /// After a failed step: flow, mesh and fold back at the last accepted
  /// step, whose fields (velocity, pressure, porous indicator, mesh
  /// displacement) are written to the XDMF file `path` for inspection
  std::optional<double> write_last_good(const std::string& path) override;
  /// Move the fluid boundary and mesh to the fold state q = (h, φ) at time
  /// t, nothing else (no flow solve, no step accepted): for replaying a
  /// fold trajectory through the mesh motion. Throws MeshInvertedError like
  /// a step's move
  ale::MeshQuality move_mesh(double t, const std::array<double, 2>& q);
  /// Time of the last accepted step
  double time() const override { return _t; }
  void checkpoint(nlohmann::json& scalars,
                  std::optional<io::RankState>& fields) override;
  void restore(const nlohmann::json& checkpoint,
               const std::vector<io::RankState>& fields) override;
  std::vector<io::TimeSeriesWriter::Field> flow_fields() const override;
  void describe(io::RunSummary& summary) override;
  void report(io::RunSummary& summary) const override;
  const TwoDofFold& fold() const { return _fold; }
  /// The flow side: mesh, flow, mesh motion, output fields
  const FlowChannel& channel() const { return _channel; }
  const TwoDofFold* two_dof_fold() const override { return &_fold; }
  const FlowChannel* flow_channel() const override { return &_channel; }

private:
  /// The coupling map: fold state guess → new fold state
  std::array<double, 2> evaluate(double t, const std::array<double, 2>& q,
                                 Sample& s);
  void set_boundary(const RigidMotion& m);
  /// Extensions of the three fields B of superpose_motion (empty: off)
  std::array<std::vector<double>, 3> _extension_basis;
  std::vector<double> _d_move; // their combination, for move_to()

  MPI_Comm _comm;
  const FoldProfile& _profile;
  ContactParameters _contact;
  FlowGlottisParameters _par;
  TwoDofFold _fold;
  FlowChannel _channel;
  std::unique_ptr<coupling::FixedPointCoupling> _loop;
  /// Displacement of the fluid boundary at reference surface point X:
  /// tapered rigid motion plus the vertical lift
  std::array<double, 2> boundary_displacement(const RigidMotion& m,
                                              const std::array<double, 2>& X,
                                              double lift) const;
  /// Vertical lift of the whole fluid boundary that keeps it above g_min
  double boundary_lift(const RigidMotion& m) const;
  std::array<double, 2> _q_n{}, _q_nn{};
  /// Generalised fluid load (Q_h, Q_φ) of the last evaluation and of the
  /// last two accepted steps (the "load" predictor)
  std::array<double, 2> _load{}, _load_n{}, _load_nn{};
  /// The predictor's guess of (h, φ) for the step to time t
  std::array<double, 2> predict();
  int _steps = 0;
  double _t = 0;
};
} // namespace fsai::glottis
