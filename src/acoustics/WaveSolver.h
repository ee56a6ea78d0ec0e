// Copyright (C) 2026 fsai developers
//
// Acoustic wave equation with Lighthill's source, docs/model.md E14, E15,
// E21; forms in forms/acoustics.py:
//   M P̈ + C Ṗ + K P = b(t)
// integrated by Newmark's method (β = 1/4, γ = 1/2: average acceleration,
// second order, unconditionally stable, energy-conserving when C = 0 and
// b = 0). M, C, K and the effective matrix A = M + γΔt C + βΔt² K are
// assembled once; A's factorisation (or preconditioner) is reused every
// step while Δt is fixed. PETSc options prefix "acoustic_" (default: LU
// with MUMPS).
#pragma once

#include "SlitLaw.h"
#include <array>
#include <dolfinx/fem/Constant.h>
#include <dolfinx/fem/Form.h>
#include <dolfinx/fem/Function.h>
#include <dolfinx/la/petsc.h>
#include <functional>
#include <io/run_state.h>
#include <map>
#include <memory>
#include <span>
#include <utility>
#include <vector>

namespace fsai::common
{
class Parameters;
}

namespace fsai::acoustics
{
/// Physical and time-integration parameters ([acoustics] section)
struct WaveParameters
{
  double c0 = 343.0; ///< Speed of sound [m/s] (air, 20 °C)
  double rho0 = 1.2; ///< Air density [kg/m³]
  double newmark_beta = 0.25;
  double newmark_gamma = 0.5;
  /// Yielding walls (WaveBoundaries::yielding), a locally reacting
  /// mass–resistance–spring per unit area, m ü + r u̇ + k u = p' (u the
  /// outward wall displacement): the soft-tissue values of Ishizaka,
  /// French & Flanagan (1975) as used by Maeda (1982), 1.5 g/cm²,
  /// 1600 dyn s/cm³, 3·10⁵ dyn/cm³, in SI
  double wall_mass = 15.0;        ///< [kg/m²]
  double wall_resistance = 1.6e4; ///< [Pa s/m]
  double wall_stiffness = 3.0e6;  ///< [Pa/m]

  void bind(fsai::common::Parameters& p);
  void validate() const;
};

/// How the boundary is treated, by role: local facet indices (owned and
/// ghost facets may both appear). Facets in no list are sound-hard walls.
struct WaveBoundaries
{
  /// Radiation condition (1/c0) ṗ + ∂p/∂n + β p = 0
  std::vector<std::int32_t> radiation;
  /// β [1/m]: 0 (Sommerfeld) or the curvature term of Bayliss–Turkel
  double radiation_beta = 0.0;
  /// Plane-wave absorbing end (1/c0) ṗ + ∂p/∂n = 0 (β = 0 whatever
  /// radiation_beta is): a duct continued by an anechoic termination
  std::vector<std::int32_t> absorbing;
  /// Volume-velocity source ∂p/∂n = ρ0 du/dt (set_inlet_acceleration)
  std::vector<std::int32_t> inlet;
  /// Vibrating wall ∂p/∂n = −ρ0 a·n (wall_acceleration())
  std::vector<std::int32_t> vibrating;
  /// Pressure release p' = 0
  std::vector<std::int32_t> pressure_release;
  /// Lip opening loaded by a flanged piston of area `piston_area` (A11):
  /// the outward normal velocity v obeys ρ0 v̇ = ṗ/(r/ρ0) + p/(m/ρ0),
  /// r, m of flanged_piston, so ∂p/∂n = −ρ0 v̇ on these facets. The domain
  /// ends at the lips; the radiated field is the caller's (a monopole of
  /// the lip flow, radiated_flow_rate)
  std::vector<std::int32_t> piston;
  double piston_area = 0.0; ///< physical area of the opening [m²]
  /// Yielding (locally reacting) wall ∂p/∂n = −ρ0 ü with
  /// m ü + r u̇ + k u = p' (WaveParameters::wall_*): the wall losses that
  /// give the tract's resonances their bandwidths
  std::vector<std::int32_t> yielding;
};

/// Newmark solver for E21 on a fixed mesh. Usage per step: set the source
/// data for the new time (set_inlet_acceleration, flow_velocity/taper,
/// wall_acceleration), then step().
class WaveSolver
{
public:
  /// @param[in] mesh Acoustic mesh (fixed)
  /// @param[in] degree Lagrange degree of p' (1 or 2)
  /// @param[in] axisymmetric Weight by r = x[1] (2D meshes only)
  /// @param[in] params Physical constants and Newmark parameters
  /// @param[in] boundaries Boundary roles
  /// @param[in] dt Time step [s]
  /// @param[in] sigma Absorbing-layer damping σ (DG0 on `mesh`, zero
  ///   outside the layer; nullptr: no layer)
  /// @param[in] lighthill Assemble the Lighthill source every step
  WaveSolver(std::shared_ptr<const dolfinx::mesh::Mesh> mesh, int degree,
             bool axisymmetric, const WaveParameters& params,
             const WaveBoundaries& boundaries, double dt,
             std::shared_ptr<const dolfinx::fem::Function<double>> sigma
             = nullptr,
             bool lighthill = false);

  /// Initial state p(0), ṗ(0) (defaults: zero); computes p̈(0) from the
  /// equation with the current source data
  void set_initial_state(const dolfinx::fem::Function<double>& p0,
                         const dolfinx::fem::Function<double>* v0 = nullptr);

  /// du/dt [m/s²] of the normal velocity into the domain on the inlet, at
  /// the time of the next step
  void set_inlet_acceleration(double dudt) { _inlet_dudt = dudt; }

  /// A compact volume source, E14's right-hand side ρ0 ∂q/∂t with
  /// q(x, t) = Q(t) ψ(x), ψ = shape/∫shape (so ∫q = Q: Q is the source's
  /// volume rate per unit depth [m²/s] on a 2D mesh, [m³/s] in 3D). `shape`
  /// ≥ 0 is sampled at the cell midpoints (one-point rule per cell); only
  /// the total matters while the region is small against a wavelength.
  /// Returns its index for set_volume_source_rate(). Throws InputError
  /// when the shape vanishes on the whole mesh. Degree 1, planar or 3D
  /// only (no r weight).
  std::size_t
  add_volume_source(const std::function<double(double, double)>& shape);
  /// dQ/dt [m²/s² per unit depth] of source `i` at the time of the next step
  void set_volume_source_rate(std::size_t i, double dQdt);

  /// Flow velocity v (P1 vector) of the Lighthill source at the next step
  dolfinx::fem::Function<double>& flow_velocity();
  /// Taper χ (P1) of the Lighthill source; 1 by default
  dolfinx::fem::Function<double>& taper();
  /// Wall acceleration a (P1 vector) on the vibrating boundary
  dolfinx::fem::Function<double>& wall_acceleration();
  /// A slit whose momentum law the caller sets (SlitLaw, docs/model.md
  /// A5), applied from the next step on; before set_initial_state()
  void set_slit(std::shared_ptr<SlitLaw> slit);

  /// Advance by one time step (t → t + Δt)
  void step();

  /// The state after the last step (p', ṗ', p̈', the yielding walls'
  /// displacement, velocity and acceleration, t) into a checkpoint (by mesh
  /// node, io/field_state.h) and back from all the checkpoint's ranks
  void save(io::RankState& state, const std::string& prefix) const;
  void load(const std::vector<io::RankState>& ranks, const std::string& prefix);

  /// Current time [s]
  double time() const { return _t; }
  /// Time step [s]
  double dt() const { return _dt; }
  /// Discrete energy ½ ṖᵀMṖ + ½ PᵀKP (collective). Conserved exactly (to
  /// round-off) by the trapezoidal Newmark scheme when C = 0, b = 0 and
  /// there are no yielding walls.
  double energy() const;
  /// Acoustic pressure p' (ghosts up to date)
  std::shared_ptr<dolfinx::fem::Function<double>> pressure() const
  {
    return _p;
  }
  /// ∫_inlet w ds: inlet width (planar), area/2π (axisymmetric), area (3D)
  double inlet_measure() const { return _inlet_measure; }
  /// Global number of unknowns
  std::int64_t dofs() const;
  /// U̇ out of the piston facets after the last step, ∫ v̇ w ds (per unit
  /// depth planar, per radian axisymmetric; collective) [m²/s² or m³/s²]
  double radiated_flow_rate() const;
  /// The load vector b of E21 for the current source data (inlet,
  /// Lighthill, vibrating wall): owned entries, for tests and diagnostics
  std::vector<double> source_vector();

private:
  using Form = dolfinx::fem::Form<double>;
  void assemble_source(Vec b);

  double _dt, _t = 0.0, _beta, _gamma, _inlet_dudt = 0.0, _inlet_measure = 0.0;
  bool _axisymmetric;
  // Volume sources: ∫ψ φ_i per source, and ρ0 dQ/dt of the next step
  std::vector<dolfinx::la::petsc::Vector> _b_volume;
  std::vector<double> _volume_dQdt;
  bool _lighthill, _vibrating = false, _yielding = false;
  double _wall_m, _wall_r, _wall_k; // per unit area
  double _wall_m_eff = 1.0;         // m + γΔt r + βΔt² k
  /// out = (p − r ṽ − k ũ)/m_eff: the walls' ü_{n+1} for the pressure p
  /// (predictors ũ, ṽ in _wu_pred, _wv_pred), on every dof
  void wall_acceleration_for(Vec p, Vec out) const;
  /// Assemble a boundary linear form into the PETSc vector `out`
  void assemble_into(const Form& L, Vec out);
  std::shared_ptr<const dolfinx::fem::FunctionSpace> _V, _Vv, _Vs;
  std::shared_ptr<dolfinx::fem::Function<double>> _p, _v_flow, _taper, _a_wall;
  std::vector<std::shared_ptr<dolfinx::fem::Constant<double>>> _constants;
  std::vector<std::shared_ptr<dolfinx::mesh::MeshTags<std::int32_t>>> _tags;
  std::shared_ptr<Form> _L_source, _L_wall;
  std::vector<std::int32_t> _bc_rows;    // owned Dirichlet rows (local)
  std::vector<PetscInt> _bc_rows_global; // the same, global
  dolfinx::la::petsc::Matrix _M{nullptr, false}, _C{nullptr, false},
      _K{nullptr, false}, _A{nullptr, false};
  dolfinx::la::petsc::Vector _p_vec{nullptr, false}; // wraps _p->x()
  dolfinx::la::petsc::Vector _v{nullptr, false}, _a{nullptr, false},
      _b_inlet{nullptr, false}, _rhs{nullptr, false}, _work_p{nullptr, false},
      _work_v{nullptr, false};
  // Yielding walls: lumped boundary mass ρ0 ∫ φ_i w ds, its 0/1 mask and
  // the wall's nodal state (displacement, velocity, acceleration) with
  // its Newmark predictors
  dolfinx::la::petsc::Vector _wall_b{nullptr, false},
      _wall_mask{nullptr, false}, _wu{nullptr, false}, _wv{nullptr, false},
      _wa{nullptr, false}, _wu_pred{nullptr, false}, _wv_pred{nullptr, false},
      _wall_work{nullptr, false};
  // Piston load (A11): ∫ φ_i w ds on its facets and the coefficients of
  // ṗ and p in ρ0 v̇ (1/(r/ρ0) [s/m], 1/(m/ρ0) [1/m])
  bool _piston = false;
  dolfinx::la::petsc::Vector _piston_b{nullptr, false};
  double _piston_damping = 0.0, _piston_stiffness = 0.0;
  std::unique_ptr<dolfinx::la::Vector<double>> _b_assembly;
  // A slit (set_slit): its operator, the effective matrix without it (A0)
  // and Lighthill's source scale, which it sets in its cells
  std::shared_ptr<SlitLaw> _slit;
  dolfinx::la::petsc::Matrix _A0{nullptr, false};
  std::shared_ptr<dolfinx::fem::Function<double>> _source_scale;
  double _rho0 = 1.2;
  int _degree = 1;
  std::map<std::string, std::shared_ptr<const dolfinx::fem::Constant<double>>>
      _constant_map;

  // Set-up steps of the constructor
  struct Forms
  {
    std::shared_ptr<Form> m, c, k, b_inlet, b_yield, b_piston, inlet_measure;
  };
  /// Spaces of p', the flow velocity, the taper and the source scale
  void create_spaces(std::shared_ptr<dolfinx::mesh::Mesh> mesh);
  /// The forms of E21 with each boundary role bound to its facets (A2–A4)
  Forms
  create_forms(const WaveParameters& params, const WaveBoundaries& boundaries,
               std::shared_ptr<const dolfinx::fem::Function<double>> sigma);
  /// M, C, K and the effective matrix A
  void assemble_matrices(const Forms& f);
  /// p' = 0 rows of A (pressure release)
  void fix_pressure_release(const std::vector<std::int32_t>& facets);
  /// State vectors, the inlet's source vector, the yielding walls' mass,
  /// the piston load
  void create_state(const Forms& f);
  dolfinx::la::petsc::KrylovSolver _solver;
};

/// Damping σ (DG0, cell midpoints) of an absorbing layer in the given
/// cells (zero elsewhere), between the spheres/circles of radius r0 and
/// r0 + d around `centre`:
/// σ = σ_max ((r − r0)/d)² with σ_max = 3 c0 ln(1/R0) / (2 d), so that a
/// normally incident wave crossing the layer twice is reduced by R0.
std::shared_ptr<dolfinx::fem::Function<double>>
absorbing_layer(std::shared_ptr<const dolfinx::mesh::Mesh> mesh,
                std::span<const std::int32_t> cells,
                std::array<double, 3> centre, double r0, double d, double c0,
                double R0);
} // namespace fsai::acoustics
