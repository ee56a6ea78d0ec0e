// Copyright (C) 2026 fsai developers
//
// Incompressible Navier–Stokes, stabilised P1/P1, BDF1/BDF2 on a (possibly
// moving) mesh: docs/model.md E8–E11, E19, E20; forms/fluid.py. Each
// solve is linear (Oseen: the convecting velocity is extrapolated, or
// Picard: iterated). PETSc options prefix "fluid_" (default: MUMPS LU).
// The matrix is reassembled at every solve (mesh, convecting velocity and
// τ change) through PETSc's COO interface on the pattern recorded at setup,
// with the Dirichlet lifting from the same element matrices
// (common::CooMatrixAssembler; --fluid.assembly dolfinx for DOLFINx's own).
#pragma once

#include "PressureConvectionDiffusion.h"
#include <array>
#include <common/CooMatrixAssembler.h>
#include <dolfinx/fem/Constant.h>
#include <dolfinx/fem/DirichletBC.h>
#include <dolfinx/fem/Form.h>
#include <dolfinx/fem/Function.h>
#include <dolfinx/la/petsc.h>
#include <io/run_state.h>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace fsai::common
{
class Parameters;
}

namespace fsai::fluid
{
/// Flow parameters ([fluid] section)
struct FluidParameters
{
  double rho = 1.2;   ///< density [kg/m³]
  double mu = 1.8e-5; ///< dynamic viscosity [Pa s]
  bool supg = true;
  bool pspg = true;
  bool graddiv = true;
  /// τ_m of SUPG/PSPG with its transient term (2/Δt)² (E20, Tezduyar
  /// 1992). false drops it, as for steady problems: then τ_m does not
  /// vanish as Δt → 0, so the stabilised solution does not depend on Δt
  /// through τ (Hsu, Bazilevs, Calo, Tezduyar & Hughes 2010, CMAME 199,
  /// 828–840, on the small-time-step degradation of SUPG/PSPG)
  bool tau_dt = true;
  /// The step Δt_τ in τ_m's transient term (2/Δt_τ)² [s]; 0: the run's Δt.
  /// Held fixed, τ_m (and with it the stabilised spatial discretisation)
  /// stays the same when Δt is halved or a step is cut, so that a Δt
  /// study measures the time discretisation alone
  double tau_step = 0.0;
  /// τ_m also holds the porous reaction (σ_P χ/ρ)² (E20), as in stabilised
  /// Brinkman–Darcy flow. Without it, in Ω^P the PSPG coupling τ_m σ_P/ρ is
  /// about 40 and PSPG nearly cancels the exact Schur complement there;
  /// the selfp approximation (diag(A_uu)⁻¹, twice the lumped mass's
  /// inverse) is then negative in Ω^P, and the "iterative" solver's
  /// FGMRES stalls once the porous region closes the channel (the
  /// glottis at closure). Off by default: the validated runs were made
  /// without it
  bool tau_porous = false;
  int picard = 1;           ///< linear solves per time step (1: Oseen)
  double picard_tol = 1e-6; ///< on |Δv|/|v| when picard > 1 or steady
  double sigma_p = 0.0;     ///< porous inverse permeability [kg/(m³ s)]
  double inlet_eps = 0.0;   ///< inlet penalty ε [s/m] (0: not used)
  double p_in = 0.0;        ///< inlet reference pressure [Pa]
  double p_out = 0.0;       ///< outlet reference pressure [Pa]
  /// "direct" (MUMPS LU) or "iterative" (FGMRES, Schur fieldsplit with
  /// BoomerAMG on the velocity block and the Schur approximation `schur`:
  /// for 3D; through a closed porous region with tau_porous, E20b)
  std::string solver = "direct";
  /// Velocity-block preconditioner of "iterative": "amg" (BoomerAMG, works
  /// for steady and transient flow) or "ilu" (block-Jacobi ILU(0): cheaper
  /// when the mass term ρ a0 M dominates the block, i.e. transient runs at
  /// moderate CFL; poor for steady problems)
  std::string velocity_pc = "amg";
  /// Schur-complement approximation of "iterative" (docs/model.md E20b):
  /// "selfp" (AMG on C + D diag(A)⁻¹ Dᵀ) or "pcd" (pressure
  /// convection–diffusion, fluid::PressureConvectionDiffusion: only a
  /// pressure Laplacian meets AMG, so it holds in the glottal jet, where
  /// AMG on selfp diverges; needs a penalty inlet or an outlet)
  std::string schur = "selfp";
  double ksp_rtol = 1e-8; ///< "iterative": relative to |b|
  /// "iterative": the preconditioner is rebuilt for every pc_lag-th solve
  /// and kept in between (1: every solve). The Krylov solve still
  /// converges to ksp_rtol on the current operator, so only its cost
  /// depends on the lag; a solve that fails with a kept preconditioner is
  /// repeated with a fresh one, and a checkpoint makes the next solve
  /// rebuild it (restarts continue identically). (Keeping a "direct" LU
  /// as FGMRES's preconditioner was tried on the FE glottis scene: 5
  /// iterations per solve, 48 ms against 35 ms for a fresh MUMPS LU.)
  int pc_lag = 1;
  /// "direct" (docs/model.md E20a): a step solved again from its saved
  /// state (the coupling's next iterate: restore_state() between two
  /// step() calls) refines the factorisation of the step's first solve
  /// (KSPRICHARDSON from the last iterate's solution) until |b − A x| ≤
  /// refine_rtol |b|, instead of factorising anew; after refine_max_its
  /// refinements it factorises afresh. 0: factorise every solve. On the
  /// elastic fold's FE glottis a refined solve took 16 ms against 45 ms
  /// (bench/glottis_elastic_refine.py). A refinement (triangular solves
  /// and a product, about 7 ms) costs a sixth of a fresh factorisation and
  /// its solve (45 ms), so six are no dearer than one; at the elastic
  /// fold's closures the iterates' operators differ more and refinements
  /// take up to 5 (with a cap of 3, 21 % of the elastic voice's repeated
  /// solves factorised afresh after 3 wasted refinements)
  double refine_rtol = 1e-14;
  int refine_max_its = 6;
  /// Matrix insertion: "coo" (PETSc's COO interface on the pattern recorded
  /// at setup: the element matrices are written in order and handed over
  /// in one call) or "dolfinx" (MatSetValuesLocal per cell). The same
  /// matrix to rounding; with "coo" the flow's assembly (matrix and
  /// vector) took 0.63 of its time on the FE glottis scene
  std::string assembly = "coo";
  /// Quadrature degree of the cell integrals (forms/fluid.py): 4 or 2. Both
  /// integrate the Galerkin terms exactly on P1; 2 samples the τ-weighted
  /// stabilisation terms at 3 points per triangle instead of 6 (4 instead
  /// of 14 per tetrahedron), so the discretisation differs slightly
  int quadrature_degree = 4;

  void bind(fsai::common::Parameters& p);
  void validate() const;
};

/// Boundary facets by role (local indices)
struct FluidBoundaries
{
  std::vector<std::int32_t> inlet_dirichlet; ///< v = inlet_velocity()
  std::vector<std::int32_t> inlet_penalty;   ///< E11a (needs inlet_eps > 0)
  std::vector<std::int32_t> outlet;          ///< E11c directional do-nothing
  std::vector<std::int32_t> walls;           ///< v = wall_velocity() (0 or w_D)
  std::vector<std::int32_t> symmetry; ///< v_c = 0 (plane normal to axis c)
  int symmetry_component = 1;         ///< c: 1 for the 2D axis y = const
};

/// The boundaries of fsai::mesh::dfg_channel by its facet tags (m: its
/// MeshData; a template so that this header need not name the fsai::mesh
/// namespace, which would hide dolfinx::mesh in the solvers' sources):
/// Dirichlet inflow, do-nothing outlet, no-slip walls and cylinder
template <typename TaggedMesh>
FluidBoundaries dfg_boundaries(const TaggedMesh& m)
{
  FluidBoundaries b;
  b.inlet_dirichlet = m.facet_tags->find(m.facet_tag("inlet"));
  b.outlet = m.facet_tags->find(m.facet_tag("outlet"));
  b.walls = m.facet_tags->find(m.facet_tag("walls"));
  auto cyl = m.facet_tags->find(m.facet_tag("cylinder"));
  b.walls.insert(b.walls.end(), cyl.begin(), cyl.end());
  return b;
}

class FluidSolver
{
public:
  FluidSolver(std::shared_ptr<const dolfinx::mesh::Mesh> mesh,
              const FluidBoundaries& boundaries, const FluidParameters& p,
              double dt);

  /// Inlet velocity profile (Dirichlet or penalty target), set before a
  /// step for the new time
  dolfinx::fem::Function<double>& inlet_velocity() { return *_v_in; }
  /// Velocity imposed on the walls (zero; the mesh velocity on moving walls)
  dolfinx::fem::Function<double>& wall_velocity() { return *_v_wall; }
  /// Mesh velocity w (ALE)
  dolfinx::fem::Function<double>& mesh_velocity() { return *_w; }
  /// Body force per unit mass f (gravity, manufactured solutions)
  dolfinx::fem::Function<double>& body_force() { return *_f; }
  /// Inlet reference pressure p_in of E11a (ramps, driving pressures)
  void set_inlet_pressure(double p) { _p_in->value = {p}; }
  /// Porous indicator χ (DG0)
  dolfinx::fem::Function<double>& porous_indicator() { return *_chi; }
  /// The same, shared (for output)
  std::shared_ptr<const dolfinx::fem::Function<double>> porous_field() const
  {
    return _chi;
  }

  /// Initial condition: the current velocity() becomes v_n = v_nn, and the
  /// next step is a BDF1 start
  void reset_history();
  /// One BDF step t → t + Δt (BDF1 for the first); returns linear solves
  int step();
  /// Steady state by Picard iteration from the current velocity; returns
  /// the iterations
  int solve_steady(int max_iterations = 50);

  /// Force exerted by the fluid on the boundary `facets` (consistent:
  /// residual of the weak form at the velocity dofs there) [N per unit
  /// depth in 2D]
  std::array<double, 3> force(std::span<const std::int32_t> facets);
  /// The same per velocity dof: F (velocity space) is set to the nodal
  /// forces on the dofs of `facets` and zero elsewhere (FSI load transfer)
  void nodal_forces(std::span<const std::int32_t> facets,
                    dolfinx::fem::Function<double>& F);
  /// Keep / go back to the state at the start of the step (coupling
  /// iterations repeat a step)
  void save_state();
  void restore_state();
  /// Repeated steps solved by refining the step's factorisation, and
  /// those that fell back to a fresh one (FluidParameters::refine_rtol)
  int refined_solves() const { return _refined; }
  int refine_fallbacks() const { return _refine_fallbacks; }
  /// "iterative": the solves, and their mean Krylov iterations (0 before
  /// the first)
  int krylov_solves() const { return _krylov_solves; }
  double krylov_iterations_mean() const
  {
    return _krylov_solves > 0 ? double(_krylov_its) / double(_krylov_solves)
                              : 0.0;
  }
  /// The accepted state (velocity and pressure, the BDF history, time and
  /// step count) into a checkpoint (entries prefix + "..."; fields by mesh
  /// node, io/field_state.h) and back from all the checkpoint's ranks
  void save(io::RankState& state, const std::string& prefix) const;
  void load(const std::vector<io::RankState>& ranks, const std::string& prefix);
  /// The accepted step's state from elsewhere (a flow transferred from
  /// another mesh): v^n (also the current velocity), v^{n−1}, p^n (local
  /// arrays of the velocity and pressure spaces, ghosts included), the time,
  /// the steps taken (≥ 1: the next step is BDF2) and the last step's
  /// length; saved as the start of the next step
  void set_state(std::span<const double> v_n, std::span<const double> v_nn,
                 std::span<const double> p, double t, int steps, double dt_n);
  /// v^{n−1} of the BDF history
  std::shared_ptr<const dolfinx::fem::Function<double>> velocity_nn() const
  {
    return _v_nn;
  }
  /// Flow rate ∫ v·n ds over `facets` (outward n)
  double flow_rate(std::span<const std::int32_t> facets);

  /// The velocity space (collapsed, P1 vector)
  std::shared_ptr<const dolfinx::fem::FunctionSpace> velocity_space() const
  {
    return _V;
  }
  std::shared_ptr<dolfinx::fem::Function<double>> velocity() const
  {
    return _v;
  }
  std::shared_ptr<dolfinx::fem::Function<double>> pressure() const
  {
    return _p;
  }
  double time() const { return _t; }
  void set_time(double t) { _t = t; }
  double dt() const { return _dt; }
  /// Length of the next steps (a variable step: the BDF2 weights and the
  /// convection's extrapolation follow the ratio to the last step, E19)
  void set_dt(double dt);
  /// Length of the last step taken (t_n − t_{n−1})
  double dt_previous() const { return _dt_n; }
  /// Steps taken (0: the next is a BDF1 start)
  int steps() const { return _steps; }
  std::int64_t dofs() const;
  /// ||∇p||_L2: a measure of spurious pressure oscillations
  double pressure_gradient_norm();
  /// Largest nodal speed |v|
  double max_speed() const;
  /// Largest CFL number |v − w| Δt / h and cell Reynolds number |v| h / ν
  std::array<double, 2> cfl_and_cell_reynolds() const;

private:
  /// Assemble and solve once with the current b; updates _up. `repeat`:
  /// the step's operator differs from its first solve's by one coupling
  /// iterate (refine_rtol)
  int solve(bool repeat = false);
  /// The repeated step's solve by iterative refinement with the kept
  /// factorisation (false: it did not converge; _up is then undefined)
  bool refine(Vec x, Vec b);
  /// Whether the saved step has been solved (with refinement on), whether
  /// restore_state() came since the last step(), and the last solution of
  /// the saved step (the refinement's initial guess)
  bool _saved_step_solved = false;
  bool _restored = false;
  std::vector<double> _up_iterate;
  /// Repeated-step solves refined / that fell back to a factorisation
  int _refined = 0, _refine_fallbacks = 0;
  std::int64_t _krylov_its = 0;
  int _krylov_solves = 0;
  // Set-up steps of the constructor
  void create_spaces(std::shared_ptr<dolfinx::mesh::Mesh> mesh);
  void create_forms(std::shared_ptr<dolfinx::mesh::Mesh> mesh,
                    const FluidBoundaries& bnd);
  void create_dirichlet_conditions(const FluidBoundaries& bnd);
  void create_matrix();    // the system's sparsity (and the COO assembler)
  void configure_solver(); // MUMPS, or the Schur fieldsplit
  void configure_blocks(); // fieldsplit block solvers, at the first solve
  bool _configure_blocks = false;
  mutable int _solves_since_setup = 0; // solves with this preconditioner
  void split();
  void merge(); // the mixed vector up from v and p (local entries)
  struct State
  {
    std::vector<double> up, v, p, v_n, v_nn;
    double t = 0, dt_n = 0;
    int steps = 0;
  } _saved;

  FluidParameters _par;
  double _dt, _dt_n, _t = 0.0;
  int _steps = 0;
  std::shared_ptr<const dolfinx::fem::FunctionSpace> _W, _V, _Q, _DG0;
  std::vector<std::int32_t> _map_v, _map_p; // collapsed → mixed dofs
  std::shared_ptr<dolfinx::fem::Function<double>> _up, _v, _p, _v_n, _v_nn,
      _v_star, _w, _v_in, _v_wall, _chi, _f;
  std::shared_ptr<dolfinx::fem::Constant<double>> _a0, _a1, _a2, _inv_dt, _p_in;
  std::vector<std::shared_ptr<dolfinx::fem::Constant<double>>> _constants;
  std::vector<std::shared_ptr<const dolfinx::fem::DirichletBC<double>>> _bcs;
  std::vector<std::shared_ptr<dolfinx::mesh::MeshTags<std::int32_t>>> _tags;
  std::shared_ptr<dolfinx::fem::Form<double>> _a, _L, _F;
  /// --fluid.schur pcd: the Schur block's preconditioner
  std::unique_ptr<PressureConvectionDiffusion> _pcd;
  dolfinx::la::petsc::Matrix _A;
  std::unique_ptr<common::CooMatrixAssembler> _coo; // assembly "coo"
  dolfinx::la::petsc::KrylovSolver _solver;
  /// A boundary on which forces are asked for: its owned velocity-space dof
  /// blocks and the residual form restricted to the cells that hold a dof
  /// of it (on any rank); cached per facet list
  struct Boundary
  {
    std::vector<std::int32_t> blocks;
    std::shared_ptr<dolfinx::mesh::MeshTags<std::int32_t>> cells;
    std::shared_ptr<dolfinx::fem::Form<double>> residual;
  };
  std::map<std::vector<std::int32_t>, Boundary> _boundaries;
  const Boundary& boundary(std::span<const std::int32_t> facets);
  /// Weak-form residual of the current solution at the boundary's blocks
  /// (bs entries each, owned entries summed over ranks)
  std::vector<double> boundary_residual(const Boundary& bnd);
};
} // namespace fsai::fluid
