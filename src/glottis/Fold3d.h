// Copyright (C) 2026 fsai developers
//
// The 3D vocal fold in the 3D glottal channel (fsai_fold3d): the fold of
// fsai_modal (mesh::VocalFoldGeometry; St.Venant–Kirchhoff, docs/model.md
// E4–E7, Newmark with Rayleigh damping) held at its lateral, anterior and
// posterior faces, in the half-channel whose face x = depth + half_gap is
// the mid-sagittal symmetry plane (mesh::glottal_channel_3d); stabilised
// P1/P1 ALE Navier–Stokes (E8–E10, E19, E20) with the penalised inlet at
// p_sub (E11a) and the directional do-nothing outlet (E11c); the
// partitioned loop with IQN-ILS (E12, E13; coupling::PartitionedFsi). An
// open glottis: no closure model (the run stops with the ALE's "cell
// inverted" if the fold reaches the plane).
#pragma once

#include <ale/MeshMotion.h>
#include <coupling/FixedPointCoupling.h>
#include <fluid/FluidSolver.h>
#include <io/Checkpointer.h>
#include <memory>
#include <mesh/glottal_channel_3d.h>
#include <mpi.h>
#include <nlohmann/json.hpp>
#include <optional>
#include <structure/ElasticSolver.h>

namespace fsai::common
{
class Parameters;
}
namespace fsai::coupling
{
class InterfaceMap;
class PartitionedFsi;
} // namespace fsai::coupling
namespace fsai::structure
{
class ModalProjection;
}
namespace fsai::io
{
class PointProbes;
class RunSummary;
} // namespace fsai::io

namespace fsai::glottis
{
/// The scene's own options
struct Fold3dParameters
{
  std::string output = "results/fsai_fold3d";
  double p_sub = 800.0; ///< subglottal pressure [Pa]
  double ramp = 2e-3;   ///< p_sub ramps up over this time [s]
  /// [s]: jet CFL ≈ 6 at √(2 p_sub/ρ) ≈ 37 m/s on the 0.3 mm gap cells
  /// (the 2D closing cycle runs at 11–24 on its 0.035 mm cells)
  double dt = 5e-5;
  double duration = 0.03;   ///< [s]
  double stats_from = -1.0; ///< cycle statistics from t [s] (< 0: half-way)
  int write_every = 100;    ///< steps between XDMF outputs (0: none)
  /// Rayleigh damping: ratio ζ, stiffness-proportional at f_zeta (the 3D
  /// fold's f1 100 Hz), as the 2D elastic fold's (ElasticFold)
  double zeta = 0.01;
  double f_zeta = 100.0; ///< [Hz]
  int layers = 1;        ///< 1 (homogeneous) or 2 (body and cover)
  /// In-vacuo modes the fold's motion is projected on (0: none)
  int modes = 6;
  structure::Material cover{2e3, 0.4, 1000.0};
  bool quick = false;
  io::RestartOptions run;

  void bind(fsai::common::Parameters& p);
  void validate() const;
};

/// Every option of fsai_fold3d: the scene's and its solvers'
struct Fold3dSetup
{
  Fold3dParameters scene;
  mesh::VocalFoldGeometry fold;
  mesh::GlottalChannel3dGeometry channel;
  fluid::FluidParameters fluid;
  structure::SolidParameters solid;
  ale::MeshMotionParameters ale;
  coupling::CouplingParameters coupling;

  /// The scene's defaults for the solvers (see Fold3d.cpp for why)
  Fold3dSetup();
  void bind(fsai::common::Parameters& p);
  /// --quick's coarse settings for the options not given, then the checks
  void configure(const fsai::common::Parameters& p);
};

/// One step's record
struct Fold3dSample
{
  double t = 0;
  double Q = 0; ///< volume flow out of the channel, both halves [m³/s]
  /// Smallest half-gap, fold surface to the plane, in the middle fifth
  /// of the fold's length [m]
  double gap = 0;
  double ux = 0; ///< medial displacement at the medial surface's centre
  double uy = 0; ///< its inferior–superior displacement [m]
  int iterations = 0;
  bool converged = true;
  /// The fold's modal coordinates q_1..q_n [m], then the share of its
  /// displacement's M-norm² they leave out (structure::ModalProjection)
  std::vector<double> modal;
};

class Fold3dPhonation
{
public:
  /// @param[in] rows_kept Rows of the series kept by a restart
  ///   (io::RunLoop::rows_kept(); npos: a new run)
  Fold3dPhonation(MPI_Comm comm, const Fold3dSetup& setup,
                  std::size_t rows_kept = std::string::npos);
  ~Fold3dPhonation();

  /// Advance one step
  Fold3dSample step();

  /// Checkpoint / restart (io::RunLoop hooks)
  void checkpoint(nlohmann::json& scalars,
                  std::optional<io::RankState>& fields);
  void restore(const nlohmann::json& scalars,
               const std::vector<io::RankState>& ranks);

  /// Sizes, materials and solvers into the summary
  void describe(io::RunSummary& summary) const;
  /// Mean Krylov iterations of the flow's solves (0: direct)
  double krylov_iterations_mean() const;

  std::vector<std::shared_ptr<const dolfinx::fem::Function<double>>>
  flow_fields() const;
  std::vector<std::shared_ptr<const dolfinx::fem::Function<double>>>
  fold_fields() const;
  double time() const { return _t; }
  /// The modal projection (nullptr with --modes 0)
  const structure::ModalProjection* modes() const { return _modes.get(); }

private:
  MPI_Comm _comm;
  Fold3dSetup _setup;
  mesh::FluidSolidMeshes _meshes;
  std::vector<std::int32_t> _interface, _outlet;
  std::unique_ptr<fluid::FluidSolver> _flow;
  std::unique_ptr<structure::ElasticSolver> _solid;
  std::unique_ptr<ale::MeshMotion> _motion;
  std::unique_ptr<coupling::InterfaceMap> _map;
  std::unique_ptr<coupling::PartitionedFsi> _fsi;
  std::unique_ptr<io::PointProbes> _medial;
  std::unique_ptr<structure::ModalProjection> _modes;
  // Interface dofs in the middle fifth of the length, their reference x
  std::vector<std::int32_t> _gap_dofs;
  std::vector<double> _gap_X;
  double _t = 0;

  double smallest_gap() const;
  std::int64_t solid_dofs() const;
};
} // namespace fsai::glottis
