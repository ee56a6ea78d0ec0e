// Copyright (C) 2026 fsai developers
//
// Elastic solid (docs/model.md E1, E4, E6, E7, E16–E18; forms in
// forms/structure.py): linear elasticity or St.Venant–Kirchhoff, P1/P2,
// plane strain (2D) or 3D, Newmark (β, γ) with Rayleigh damping
// D = ε1 M + ε2 K, Newton's method on R(u) = 0 every step, static solves
// with load stepping, and save/restore of the state for the sub-iterations
// of a partitioned coupling. PETSc options prefix "solid_" (default LU).
#pragma once
#include <functional>

#include <array>
#include <common/CooMatrixAssembler.h>
#include <dolfinx/fem/Constant.h>
#include <dolfinx/fem/DirichletBC.h>
#include <dolfinx/fem/Form.h>
#include <dolfinx/fem/Function.h>
#include <dolfinx/la/petsc.h>
#include <io/run_state.h>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace fsai::common
{
class Parameters;
}

namespace fsai::structure
{
/// Isotropic material: Young's modulus E [Pa], Poisson's ratio ν, density
/// ρ [kg/m³]
struct Material
{
  double E = 8e3;
  double nu = 0.4;
  double rho = 1000.0;
  void validate(const std::string& what) const;
  double lambda() const { return E * nu / ((1 + nu) * (1 - 2 * nu)); }
  double mu() const { return E / (2 * (1 + nu)); }
};

/// Solver parameters ([solid] section)
struct SolidParameters
{
  std::string model = "linear"; ///< "linear" or "svk"
  int degree = 1;
  Material material; ///< default material of every cell
  double newmark_beta = 0.25;
  double newmark_gamma = 0.5;
  /// Generalised-α (Chung–Hulbert, E18a): the spectral radius ρ∞ ∈ [0, 1]
  /// of the step at Δt ω → ∞ sets α_m, α_f, β and γ (second order, damping
  /// only the motion near the step's Nyquist frequency); < 0: Newmark with
  /// newmark_beta and newmark_gamma
  double rho_inf = -1.0;
  double rayleigh_mass = 0.0;      ///< ε1 [1/s]
  double rayleigh_stiffness = 0.0; ///< ε2 [s]
  double newton_rtol = 1e-9;       ///< on the update, relative to u
  double newton_atol = 1e-12;      ///< on the residual norm
  int newton_max_it = 30;
  /// Modified Newton (dynamic steps): keep the factorised Jacobian across
  /// Newton iterations, coupling iterations and steps while each update shrinks
  /// by at least `newton_reuse_rate` (else refactorise); the converged
  /// state is the same to the Newton tolerance
  bool newton_reuse = false;
  double newton_reuse_rate = 0.25;
  /// A step repeated after restore_state() (coupling iterations) starts
  /// Newton from the previous iteration's solution instead of u_n: the
  /// loads differ by the coupling residual only, so about one Newton
  /// iteration fewer (FSI3, Δt 0.0025: 3.5 → 2.7 per solid step, 15 % less
  /// wall time, the same figures). Off by default: the solid's response
  /// then depends on the iteration history at the Newton tolerance, as
  /// with newton_reuse, and on FSI3 at Δt 0.005 the drag developed a
  /// step-to-step oscillation after t = 6 s that the default run does not
  /// show (docs/benchmarks.md, Turek–Hron)
  bool newton_warm_start = false;
  /// Insertion of the Newton tangent: "coo" (common::CooMatrixAssembler:
  /// PETSc's COO interface on the pattern recorded at the first assembly;
  /// on FSI3 the tangent's assembly took 0.35–0.55 of its time)
  /// or "dolfinx" (MatSetValuesBlockedLocal per cell); the same matrix to
  /// rounding
  std::string assembly = "coo";
  /// 2D only: the section is that of a body of this length clamped at its
  /// two ends along the third axis (a vocal fold's anterior and posterior
  /// ends), reduced to the first harmonic along it: an elastic foundation
  /// μ (π/L)² u (forms/structure.py, "Clamped section"). 0: plane strain
  double clamped_length = 0.0; ///< L [m]

  void bind(fsai::common::Parameters& p);
  void validate() const;
  /// Rayleigh damping with ratio ζ at f_low and f_high [Hz] (ε1 = 2ζ ω_l
  /// ω_h/(ω_l + ω_h), ε2 = 2ζ/(ω_l + ω_h)); f_low = 0: stiffness-
  /// proportional only, ζ at f_high
  void set_damping_ratio(double zeta, double f_low, double f_high);
};

/// The step's weights (E18, E18a): β, γ of Newmark's kinematics and the
/// generalised-α points t_{n+1−α_m} (inertia), t_{n+1−α_f} (other forces)
struct TimeScheme
{
  double beta, gamma, alpha_m, alpha_f;
  /// From rho_inf (generalised-α) or newmark_beta/gamma (α_m = α_f = 0)
  static TimeScheme from(const SolidParameters& p);
};

/// Elastic solid on a fixed reference mesh, displacement u = 0 on the
/// `fixed` facets, traction on the `loaded` facets.
class ElasticSolver
{
public:
  /// @param[in] mesh Reference configuration
  /// @param[in] fixed Facets (local indices) with u = 0
  /// @param[in] loaded Facets carrying the traction field traction()
  /// @param[in] params Model, degree, default material, Newmark, Newton
  /// @param[in] dt Time step [s] (any positive value for static use)
  ElasticSolver(std::shared_ptr<const dolfinx::mesh::Mesh> mesh,
                std::span<const std::int32_t> fixed,
                std::span<const std::int32_t> loaded,
                const SolidParameters& params, double dt);

  /// Hold every dof whose point x (x, y, z) satisfies `where(x)` at u = 0
  /// too (owned and ghost); call before solving
  void fix_where(const std::function<bool(std::span<const double, 3>)>& where);
  /// Material of the given cells (local indices); call before solving
  void set_material(std::span<const std::int32_t> cells, const Material& m);
  /// Body acceleration g [m/s²] (gravity), scaled by the load factor
  void set_body_acceleration(std::array<double, 3> g);
  /// Penalty contact of the loaded facets with the plane y = y_c
  /// (forms/structure.py): pressure k δ max(0, 1 + b δ̇) where the surface
  /// has crossed it by δ; k = 0 removes it. Part of the residual, so each
  /// step is solved with it (Newton), also for the linear model
  void set_contact(double k, double b, double y_c);
  /// Contact force along +y on the loaded facets at the current state [N]
  /// (per unit depth in 2D; collective)
  double contact_force() const;
  /// ∫ δ dS over the loaded facets at the current state [m²] (the contact
  /// force per unit stiffness, without damping; collective)
  double contact_overlap() const;
  /// A contact law whose stiffness depends on the state (the Hertz
  /// contact of glottis::ElasticFold) sets k, b, y_c (set_contact) from the
  /// current iterate in `update(iteration)`, called before every residual
  /// of a Newton solve (iteration 1, 2, …; collective)
  void set_contact_update(std::function<void(int)> update)
  {
    _contact_update = std::move(update);
  }
  /// Traction on the loaded facets [Pa] (P1/P2 vector field)
  dolfinx::fem::Function<double>& traction() { return *_traction; }

  /// One Newmark step t → t + Δt; returns the Newton iterations
  int step();
  /// Static equilibrium under the full loads, reached in `load_steps`
  /// equal increments of the load factor; returns total Newton iterations
  int solve_static(int load_steps = 1);

  /// Keep / go back to the state at the start of the step (coupling; with
  /// newton_warm_start the repeated step starts from the last solution)
  void save_state();
  void restore_state();
  /// The accepted state (u, v, a, t) for a checkpoint (this rank's owned
  /// blocks, by mesh node and edge); load() fills it from the parts of all
  /// the checkpoint's ranks (same mesh, any partition). Saving also marks
  /// the tangent stale, so the next step factorises a fresh one, as a run
  /// restarted from the checkpoint does: both continue identically
  void save(io::RankState& state, const std::string& prefix) const;
  void load(const std::vector<io::RankState>& ranks, const std::string& prefix);

  std::shared_ptr<dolfinx::fem::Function<double>> displacement() const
  {
    return _u;
  }
  std::shared_ptr<dolfinx::fem::Function<double>> velocity() const
  {
    return _v;
  }
  std::shared_ptr<dolfinx::fem::Function<double>> acceleration() const
  {
    return _a;
  }
  double time() const { return _t; }
  double dt() const { return _dt; }
  /// Length of the next steps (Newmark and generalised-α are one-step
  /// schemes: any step may differ from the last)
  void set_dt(double dt);

  /// ½ vᵀ M v
  double kinetic_energy();
  /// ½ uᵀ K u (linear stiffness at the reference state)
  double strain_energy();

  /// Stiffness (Dirichlet rows/columns zero, diagonal `diagonal`) and mass
  /// (diagonal 0) for modal analysis: no spurious modes near 0
  dolfinx::la::petsc::Matrix stiffness_matrix(double diagonal = 1.0) const;
  dolfinx::la::petsc::Matrix mass_matrix() const;

  std::shared_ptr<const dolfinx::fem::FunctionSpace> space() const
  {
    return _V;
  }
  /// Density field (DG0) for diagnostics
  std::shared_ptr<const dolfinx::fem::Function<double>> density() const
  {
    return _rho;
  }

private:
  int newton(const std::string& what);
  /// The traction the state now stands under, and its time (T_n, E18a)
  void remember_traction();

  const SolidParameters _p;
  const TimeScheme _scheme;
  double _dt, _t = 0.0;
  std::shared_ptr<const dolfinx::fem::FunctionSpace> _V;
  std::shared_ptr<dolfinx::fem::Function<double>> _u, _u_n, _v_n, _a_n, _v, _a,
      _traction, _traction_n, _lambda, _mu, _rho;
  // The traction of the last step taken (or static solve) and the time
  // it ended at: the next step's T_n (E18a); a repeated step
  // (restore_state) keeps its T_n
  std::vector<double> _T_last;
  double _T_last_t = -1.0;
  std::shared_ptr<dolfinx::fem::Constant<double>> _dt_c, _dynamic, _load, _g,
      _k_c, _b_c, _y_c;
  std::function<void(int)> _contact_update;
  std::vector<std::shared_ptr<dolfinx::fem::Constant<double>>> _constants;
  std::vector<std::shared_ptr<const dolfinx::fem::DirichletBC<double>>> _bcs;
  std::shared_ptr<dolfinx::mesh::MeshTags<std::int32_t>> _loaded_tags;
  std::shared_ptr<dolfinx::fem::Form<double>> _R, _J, _K, _M, _F_c;
  dolfinx::la::petsc::Matrix _Jmat;
  std::unique_ptr<common::CooMatrixAssembler> _coo; // assembly "coo"
  bool _J_current = false;      ///< J assembled and factorised for the current
                                ///< material, Δt and load mode
  mutable bool _J_stale = true; ///< modified Newton: refactorise before the
                                ///< next solve
  std::vector<double> _saved;
  std::vector<double> _guess; // warm start of a repeated step (Newton)
  bool _stepped = false;      // a step was taken since save_state()
  dolfinx::la::petsc::KrylovSolver _solver;
};
} // namespace fsai::structure
