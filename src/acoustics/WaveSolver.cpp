// Copyright (C) 2026 fsai developers
#include "WaveSolver.h"
#include "../common/Parameters.h"
#include "../common/Runtime.h"
#include "../common/errors.h"
#include "../common/petsc_solver.h"
#include "../common/timer.h"
#include "piston_load.h"
#include <cmath>
#include <dolfinx/fem/DirichletBC.h>
#include <dolfinx/fem/assembler.h>
#include <dolfinx/fem/petsc.h>
#include <dolfinx/fem/utils.h>
#include <dolfinx/mesh/utils.h>
#include <fsai_forms/acoustics.h>
#include <io/field_state.h>
#include <numeric>

using namespace dolfinx;
namespace acoustic_forms = fsai::forms::acoustics;

namespace
{
using Coefficients
    = std::map<std::string, std::shared_ptr<const fem::Function<double>>>;
using Constants
    = std::map<std::string, std::shared_ptr<const fem::Constant<double>>>;

/// Tag the given boundary facets with 1 (the `ds(1)` of forms/acoustics.py).
/// Only owned exterior facets are kept; an interior facet is an input error.
std::shared_ptr<mesh::MeshTags<std::int32_t>>
role_tags(std::shared_ptr<const mesh::Mesh> mesh,
          std::vector<std::int32_t> facets, const std::string& role)
{
  const int fdim = mesh->topology().dim() - 1;
  auto f_to_c = mesh->topology().connectivity(fdim, fdim + 1);
  const std::int32_t num_owned = mesh->topology().index_map(fdim)->size_local();
  std::sort(facets.begin(), facets.end());
  facets.erase(std::unique(facets.begin(), facets.end()), facets.end());
  std::vector<std::int32_t> kept;
  for (std::int32_t f : facets)
  {
    if (f >= num_owned)
      continue;
    if (f_to_c->num_links(f) != 1)
    {
      throw fsai::InputError("acoustics: a facet given as '" + role
                             + "' boundary is not on the boundary");
    }
    kept.push_back(f);
  }
  std::vector<std::int32_t> values(kept.size(), 1);
  return std::make_shared<mesh::MeshTags<std::int32_t>>(
      mesh, fdim, std::move(kept), std::move(values));
}

/// Assemble a bilinear form into a new PETSc matrix (no boundary rows
/// modified)
la::petsc::Matrix assemble(const fem::Form<double>& a)
{
  la::petsc::Matrix A(fem::petsc::create_matrix(a), false);
  MatZeroEntries(A.mat());
  fem::assemble_matrix(la::petsc::Matrix::set_block_fn(A.mat(), ADD_VALUES), a,
                       {});
  MatAssemblyBegin(A.mat(), MAT_FINAL_ASSEMBLY);
  MatAssemblyEnd(A.mat(), MAT_FINAL_ASSEMBLY);
  return A;
}
} // namespace

//-----------------------------------------------------------------------------
void fsai::acoustics::WaveParameters::bind(fsai::common::Parameters& p)
{
  p.add("wave.c0", c0, "speed of sound [m/s]");
  p.add("wave.rho0", rho0, "air density [kg/m^3]");
  p.add("wave.newmark_beta", newmark_beta, "Newmark beta (1/4: trapezoidal)");
  p.add("wave.newmark_gamma", newmark_gamma,
        "Newmark gamma (1/2: no numerical damping)");
  p.add("wave.wall_mass", wall_mass,
        "yielding wall: mass per unit area [kg/m^2]");
  p.add("wave.wall_resistance", wall_resistance,
        "yielding wall: resistance per unit area [Pa s/m]");
  p.add("wave.wall_stiffness", wall_stiffness,
        "yielding wall: stiffness per unit area [Pa/m]");
}
//-----------------------------------------------------------------------------
void fsai::acoustics::WaveParameters::validate() const
{
  fsai::require_positive("--wave.c0", c0);
  fsai::require_positive("--wave.rho0", rho0);
  fsai::require_range("--wave.newmark_gamma", newmark_gamma, 0.5, 1.0);
  // Unconditional stability needs 2β >= γ >= 1/2
  fsai::require(2 * newmark_beta >= newmark_gamma and newmark_beta <= 0.5,
                "--wave.newmark_beta",
                "in [gamma/2, 1/2] (unconditionally stable)", newmark_beta);
  fsai::require_positive("--wave.wall_mass", wall_mass);
  fsai::require(wall_resistance >= 0, "--wave.wall_resistance", ">= 0",
                wall_resistance);
  fsai::require(wall_stiffness >= 0, "--wave.wall_stiffness", ">= 0",
                wall_stiffness);
}
//-----------------------------------------------------------------------------
//-----------------------------------------------------------------------------
fsai::acoustics::WaveSolver::WaveSolver(
    std::shared_ptr<const mesh::Mesh> mesh, int degree, bool axisymmetric,
    const WaveParameters& params, const WaveBoundaries& boundaries, double dt,
    std::shared_ptr<const fem::Function<double>> sigma, bool lighthill)
    : _dt(dt), _beta(params.newmark_beta), _gamma(params.newmark_gamma),
      _axisymmetric(axisymmetric), _lighthill(lighthill),
      _wall_m(params.wall_mass), _wall_r(params.wall_resistance),
      _wall_k(params.wall_stiffness), _solver(mesh->comm())
{
  _rho0 = params.rho0;
  common::ScopedTimer timer("acoustics: setup");
  params.validate();
  fsai::require_positive("acoustics: time step", dt);
  const int tdim = mesh->topology().dim();
  fsai::require(!axisymmetric or tdim == 2, "acoustics: axisymmetric model",
                "a 2D mesh (x along the axis, y = r >= 0)", tdim);
  fsai::require(degree == 1 or degree == 2, "acoustics: degree", "1 or 2",
                degree);
  _degree = degree;
  create_spaces(std::const_pointer_cast<mesh::Mesh>(mesh));
  const Forms forms = create_forms(params, boundaries, sigma);
  common::ScopedTimer t_assemble("acoustics: assemble matrices");
  assemble_matrices(forms);
  fix_pressure_release(boundaries.pressure_release);
  create_state(forms);
  t_assemble.stop();
  // The factorisation is computed at the first solve and reused while the
  // operator does not change (with a slit it changes every step)
  common::configure_direct_solver(_solver.ksp(), mesh->comm(), tdim);
  _solver.set_options_prefix("acoustic_");
  _solver.set_from_options();
  _solver.set_operator(_A.mat());
}
//-----------------------------------------------------------------------------
void fsai::acoustics::WaveSolver::create_spaces(
    std::shared_ptr<mesh::Mesh> mesh)
{
  const int tdim = mesh->topology().dim();
  auto space = [&](auto factory, const char* name)
  {
    return std::make_shared<fem::FunctionSpace>(
        fem::create_functionspace(factory, name, mesh));
  };
  _V = space(acoustic_forms::functionspace_m(tdim, _degree), "p");
  _Vv = space(acoustic_forms::functionspace_L_source(tdim, _degree), "v");
  _Vs = space(acoustic_forms::functionspace_L_source(tdim, _degree), "taper");
  _p = std::make_shared<fem::Function<double>>(_V);
  _p->name = "p_acoustic";
  _v_flow = std::make_shared<fem::Function<double>>(_Vv);
  _v_flow->name = "v_flow";
  _taper = std::make_shared<fem::Function<double>>(_Vs);
  _taper->name = "taper";
  _taper->x()->set(1.0);
  _a_wall = std::make_shared<fem::Function<double>>(_Vv);
  _a_wall->name = "wall_acceleration";
  // Lighthill's source scale: 1, except in a slit (SlitLaw)
  _source_scale = std::make_shared<fem::Function<double>>(space(
      acoustic_forms::functionspace_L_source(tdim, _degree), "source_scale"));
  _source_scale->x()->set(1.0);
}
//-----------------------------------------------------------------------------
fsai::acoustics::WaveSolver::Forms fsai::acoustics::WaveSolver::create_forms(
    const WaveParameters& params, const WaveBoundaries& boundaries,
    std::shared_ptr<const fem::Function<double>> sigma)
{
  auto mesh = std::const_pointer_cast<mesh::Mesh>(_V->mesh());
  const int tdim = mesh->topology().dim();
  auto constant = [&](double value)
  {
    _constants.push_back(std::make_shared<fem::Constant<double>>(value));
    return _constants.back();
  };
  _constant_map = {{"c0", constant(params.c0)},
                   {"rho0", constant(params.rho0)},
                   {"axisymmetric", constant(_axisymmetric ? 1.0 : 0.0)},
                   {"beta", constant(boundaries.radiation_beta)},
                   {"one", constant(1.0)}};
  std::shared_ptr<const fem::Function<double>> s = sigma;
  if (!s)
  {
    auto zero = std::make_shared<fem::Function<double>>(
        std::make_shared<fem::FunctionSpace>(fem::create_functionspace(
            acoustic_forms::functionspace_c(tdim, _degree), "sigma", mesh)));
    zero->x()->set(0.0);
    s = zero;
  }

  // Boundary roles (A2–A4): each form's ds(1) bound to one set of facets
  mesh->topology_mutable().create_connectivity(tdim - 1, tdim);
  auto tags_rad = role_tags(mesh, boundaries.radiation, "radiation");
  // The damping (1/c0) ṗ acts on radiation and absorbing facets alike, the
  // curvature term β p on the radiation facets only
  std::vector<std::int32_t> damped = boundaries.radiation;
  damped.insert(damped.end(), boundaries.absorbing.begin(),
                boundaries.absorbing.end());
  auto tags_damped = role_tags(mesh, damped, "absorbing");
  auto tags_in = role_tags(mesh, boundaries.inlet, "inlet");
  auto tags_wall = role_tags(mesh, boundaries.vibrating, "vibrating");
  auto tags_yield = role_tags(mesh, boundaries.yielding, "yielding");
  auto tags_piston = role_tags(mesh, boundaries.piston, "piston");
  _tags = {tags_rad, tags_damped, tags_in, tags_wall, tags_yield, tags_piston};
  // A role is active if any rank has facets of it (collective)
  auto on_any_rank = [&](const std::vector<std::int32_t>& facets)
  {
    int here = facets.empty() ? 0 : 1, any = 0;
    MPI_Allreduce(&here, &any, 1, MPI_INT, MPI_MAX, mesh->comm());
    return any != 0;
  };
  _yielding = on_any_rank(boundaries.yielding);
  _vibrating = on_any_rank(boundaries.vibrating);
  _piston = on_any_rank(boundaries.piston);
  if (_piston)
  {
    const PistonLoad load
        = flanged_piston(boundaries.piston_area, params.c0, params.rho0);
    _piston_damping = params.rho0 / load.resistance;
    _piston_stiffness = params.rho0 / load.inertance;
  }
  using fem::IntegralType;
  auto on = [](const std::shared_ptr<mesh::MeshTags<std::int32_t>>& t)
  {
    return std::map<IntegralType, const mesh::MeshTags<int>*>{
        {IntegralType::exterior_facet, t.get()}};
  };
  auto form = [&](ufcx_form& f,
                  std::vector<std::shared_ptr<const fem::FunctionSpace>> spaces,
                  const Coefficients& coeffs,
                  const std::map<IntegralType, const mesh::MeshTags<int>*>& sd)
  {
    return std::make_shared<fem::Form<double>>(
        fem::create_form<double>(f, spaces, coeffs, _constant_map, sd, mesh));
  };
  Forms f;
  f.m = form(acoustic_forms::m(tdim, _degree), {_V, _V}, {}, {});
  f.c = form(acoustic_forms::c(tdim, _degree), {_V, _V}, {{"sigma", s}},
             on(tags_damped));
  f.k = form(acoustic_forms::k(tdim, _degree), {_V, _V}, {{"sigma", s}},
             on(tags_rad));
  _L_source = form(
      acoustic_forms::L_source(tdim, _degree), {_V},
      {{"v", _v_flow}, {"taper", _taper}, {"source_scale", _source_scale}}, {});
  _L_wall = form(acoustic_forms::L_wall(tdim, _degree), {_V},
                 {{"a_wall", _a_wall}}, on(tags_wall));
  f.b_inlet
      = form(acoustic_forms::b_inlet(tdim, _degree), {_V}, {}, on(tags_in));
  f.inlet_measure = form(acoustic_forms::boundary_measure(tdim, _degree), {},
                         {}, on(tags_in));
  f.b_yield
      = form(acoustic_forms::b_inlet(tdim, _degree), {_V}, {}, on(tags_yield));
  f.b_piston
      = form(acoustic_forms::b_inlet(tdim, _degree), {_V}, {}, on(tags_piston));
  return f;
}
//-----------------------------------------------------------------------------
void fsai::acoustics::WaveSolver::assemble_matrices(const Forms& f)
{
  // E21 matrices, assembled once, and the effective matrix of the
  // acceleration form of Newmark's method, A = M + γΔt C + βΔt² K
  _M = assemble(*f.m);
  _C = assemble(*f.c);
  _K = assemble(*f.k);
  Mat A;
  MatDuplicate(_M.mat(), MAT_COPY_VALUES, &A);
  MatAXPY(A, _gamma * _dt, _C.mat(), DIFFERENT_NONZERO_PATTERN);
  MatAXPY(A, _beta * _dt * _dt, _K.mat(), DIFFERENT_NONZERO_PATTERN);
  _A = la::petsc::Matrix(A, false);
}
//-----------------------------------------------------------------------------
void fsai::acoustics::WaveSolver::fix_pressure_release(
    const std::vector<std::int32_t>& facets)
{
  // p'' = 0 on those rows, hence p' stays 0 (collective: every rank calls
  // it, with or without facets)
  const int tdim = _V->mesh()->topology().dim();
  auto map = _V->dofmap()->index_map;
  for (std::int32_t d : fem::locate_dofs_topological(*_V, tdim - 1, facets))
    if (d < map->size_local())
      _bc_rows.push_back(d);
  std::vector<std::int64_t> global(_bc_rows.size());
  map->local_to_global(_bc_rows, global);
  _bc_rows_global.assign(global.begin(), global.end());
  MatZeroRowsColumns(_A.mat(), PetscInt(_bc_rows_global.size()),
                     _bc_rows_global.data(), 1.0, nullptr, nullptr);
}
//-----------------------------------------------------------------------------
void fsai::acoustics::WaveSolver::create_state(const Forms& f)
{
  // State vectors: p wraps the Function's array; v, a plain PETSc vectors
  _p_vec = la::petsc::Vector(la::petsc::create_vector_wrap(*_p->x()), false);
  auto like = [&]()
  {
    Vec x;
    VecDuplicate(_p_vec.vec(), &x);
    VecSet(x, 0.0);
    return la::petsc::Vector(x, false);
  };
  for (auto* v :
       {&_v, &_a, &_rhs, &_work_p, &_work_v, &_b_inlet, &_wall_b, &_wall_mask,
        &_wu, &_wv, &_wa, &_wu_pred, &_wv_pred, &_wall_work})
    *v = like();
  _b_assembly = std::make_unique<la::Vector<double>>(
      _V->dofmap()->index_map, _V->dofmap()->index_map_bs());

  // Fixed source vector of the volume-velocity inlet
  assemble_into(*f.b_inlet, _b_inlet.vec());
  // Yielding walls (A3, ∂p/∂n = −ρ0 ü on them): the lumped boundary mass
  // B = ρ0 ∫ φ_i w ds. The wall's Newmark step, solved node by node, makes
  // ü_{n+1} = (p_{n+1} − r ṽ − k ũ)/m_eff, m_eff = m + γΔt r + βΔt² k, and
  // p_{n+1} = p~ + βΔt² p̈_{n+1}: A gains the diagonal B βΔt²/m_eff, the
  // right-hand side −B (p~ − r ṽ − k ũ)/m_eff (step)
  _wall_m_eff = _wall_m + _gamma * _dt * _wall_r + _beta * _dt * _dt * _wall_k;
  if (_yielding)
  {
    assemble_into(*f.b_yield, _wall_b.vec());
    PetscInt n;
    VecGetLocalSize(_wall_b.vec(), &n);
    const PetscScalar* b;
    PetscScalar* mask;
    VecGetArrayRead(_wall_b.vec(), &b);
    VecGetArray(_wall_mask.vec(), &mask);
    for (PetscInt i = 0; i < n; ++i)
      mask[i] = b[i] != 0.0 ? 1.0 : 0.0;
    VecRestoreArray(_wall_mask.vec(), &mask);
    VecRestoreArrayRead(_wall_b.vec(), &b);
    VecCopy(_wall_b.vec(), _work_p.vec());
    VecScale(_work_p.vec(), _beta * _dt * _dt / _wall_m_eff);
    MatDiagonalSet(_A.mat(), _work_p.vec(), ADD_VALUES);
  }
  // Piston load (A11): ρ0 v̇ = c_p ṗ + k_p p on its facets adds the lumped
  // boundary mass b = ∫ φ_i w ds times c_p to C and times k_p to K (and
  // to A, γΔt C + βΔt² K)
  if (_piston)
  {
    _piston_b = like();
    assemble_into(*f.b_piston, _piston_b.vec());
    VecScale(_piston_b.vec(), 1.0 / _rho0); // b_inlet's form is ρ0 ∫ φ w ds
    auto add_diagonal = [&](Mat A, double scale)
    {
      VecCopy(_piston_b.vec(), _work_p.vec());
      VecScale(_work_p.vec(), scale);
      MatDiagonalSet(A, _work_p.vec(), ADD_VALUES);
    };
    add_diagonal(_C.mat(), _piston_damping);
    add_diagonal(_K.mat(), _piston_stiffness);
    add_diagonal(_A.mat(), _gamma * _dt * _piston_damping
                               + _beta * _dt * _dt * _piston_stiffness);
  }
  double local = fem::assemble_scalar(*f.inlet_measure);
  MPI_Allreduce(&local, &_inlet_measure, 1, MPI_DOUBLE, MPI_SUM,
                _V->mesh()->comm());
}
//-----------------------------------------------------------------------------
void fsai::acoustics::WaveSolver::set_slit(std::shared_ptr<SlitLaw> slit)
{
  // A0: the effective matrix without the slit; the slit adds βΔt² D_k(κ)
  // every step
  SlitContext ctx{_V,    _degree, _source_scale,  _constant_map,
                  _rho0, _dt,     _bc_rows_global};
  slit->attach(ctx);
  Mat A0;
  MatDuplicate(_A.mat(), MAT_COPY_VALUES, &A0);
  _A0 = la::petsc::Matrix(A0, false);
  _slit = std::move(slit);
}
//-----------------------------------------------------------------------------
fem::Function<double>& fsai::acoustics::WaveSolver::flow_velocity()
{
  return *_v_flow;
}
//-----------------------------------------------------------------------------
fem::Function<double>& fsai::acoustics::WaveSolver::taper() { return *_taper; }
//-----------------------------------------------------------------------------
fem::Function<double>& fsai::acoustics::WaveSolver::wall_acceleration()
{
  return *_a_wall;
}
//-----------------------------------------------------------------------------
std::int64_t fsai::acoustics::WaveSolver::dofs() const
{
  return _V->dofmap()->index_map->size_global();
}
//-----------------------------------------------------------------------------
std::vector<double> fsai::acoustics::WaveSolver::source_vector()
{
  assemble_source(_rhs.vec());
  const PetscScalar* r;
  PetscInt n;
  VecGetLocalSize(_rhs.vec(), &n);
  VecGetArrayRead(_rhs.vec(), &r);
  std::vector<double> out(r, r + n);
  VecRestoreArrayRead(_rhs.vec(), &r);
  return out;
}
//-----------------------------------------------------------------------------
std::size_t fsai::acoustics::WaveSolver::add_volume_source(
    const std::function<double(double, double)>& shape)
{
  const mesh::Mesh& mesh = *_V->mesh();
  const int tdim = mesh.topology().dim();
  const auto dofmap = _V->dofmap();
  if (dofmap->cell_dofs(0).size() != std::size_t(tdim + 1))
    throw fsai::InputError("volume source: P1 pressure only");
  // The weights below are plain cell measures, without the r of an
  // axisymmetric model's forms
  if (_axisymmetric)
    throw fsai::InputError("volume source: planar or 3D models only");
  // ∫ψ φ_i by the one-point rule: |K| ψ(centre)/(tdim + 1) to each vertex
  la::Vector<double> w(dofmap->index_map, 1);
  auto wa = w.mutable_array();
  const auto& gdofs = mesh.geometry().dofmap();
  const auto x = mesh.geometry().x();
  const std::int32_t n_owned = mesh.topology().index_map(tdim)->size_local();
  double local = 0.0;
  for (std::int32_t c = 0; c < n_owned; ++c)
  {
    const auto g = gdofs.links(c);
    std::array<std::array<double, 3>, 4> v{};
    std::array<double, 3> centre{};
    for (int i = 0; i <= tdim; ++i)
      for (int d = 0; d < 3; ++d)
      {
        v[i][d] = x[3 * g[i] + d];
        centre[d] += v[i][d] / (tdim + 1);
      }
    // |K| = |det[v1 − v0, v2 − v0 (, v3 − v0)]| / tdim!; the z rows of a 2D
    // mesh are zero, so its edge vectors' cross product has only a z part
    std::array<std::array<double, 3>, 3> e{};
    for (int i = 0; i < tdim; ++i)
      for (int d = 0; d < 3; ++d)
        e[i][d] = v[i + 1][d] - v[0][d];
    const double cross_z = e[0][0] * e[1][1] - e[0][1] * e[1][0];
    const double measure
        = tdim == 2
              ? 0.5 * std::abs(cross_z)
              : std::abs(e[2][0] * (e[0][1] * e[1][2] - e[0][2] * e[1][1])
                         - e[2][1] * (e[0][0] * e[1][2] - e[0][2] * e[1][0])
                         + e[2][2] * cross_z)
                    / 6.0;
    const double s = shape(centre[0], centre[1]);
    if (!(s >= 0.0) or !std::isfinite(s))
      throw fsai::InputError("volume source: shape must be finite and >= 0");
    local += s * measure;
    for (auto d : dofmap->cell_dofs(c))
      wa[d] += s * measure / (tdim + 1);
  }
  w.scatter_rev(std::plus<double>());
  double total = 0.0;
  MPI_Allreduce(&local, &total, 1, MPI_DOUBLE, MPI_SUM, mesh.comm());
  if (!(total > 0.0))
    throw fsai::InputError("volume source: its shape is zero on the mesh");
  Vec b;
  VecDuplicate(_p_vec.vec(), &b);
  PetscScalar* r;
  PetscInt n;
  VecGetLocalSize(b, &n);
  VecGetArray(b, &r);
  for (PetscInt i = 0; i < n; ++i)
    r[i] = wa[i] / total;
  VecRestoreArray(b, &r);
  _b_volume.emplace_back(b, false);
  _volume_dQdt.push_back(0.0);
  return _b_volume.size() - 1;
}
//-----------------------------------------------------------------------------
void fsai::acoustics::WaveSolver::set_volume_source_rate(std::size_t i,
                                                         double dQdt)
{
  if (i >= _volume_dQdt.size())
    throw std::out_of_range("volume source index");
  _volume_dQdt[i] = dQdt;
}
//-----------------------------------------------------------------------------
void fsai::acoustics::WaveSolver::assemble_source(Vec b)
{
  // b = du/dt b_inlet + ρ0 dQ/dt b_volume + b_Lighthill + b_wall + b_slit
  VecSet(b, 0.0);
  if (_inlet_dudt != 0.0)
    VecAXPY(b, _inlet_dudt, _b_inlet.vec());
  for (std::size_t i = 0; i < _b_volume.size(); ++i)
    if (_volume_dQdt[i] != 0.0)
      VecAXPY(b, _rho0 * _volume_dQdt[i], _b_volume[i].vec());
  if (_lighthill or _vibrating or _slit)
  {
    _b_assembly->set(0.0);
    auto arr = _b_assembly->mutable_array();
    if (_lighthill)
      fem::assemble_vector(arr, *_L_source);
    if (_vibrating)
      fem::assemble_vector(arr, *_L_wall);
    if (_slit)
      _slit->add_load(arr);
    _b_assembly->scatter_rev(std::plus<double>());
    la::petsc::Vector w(la::petsc::create_vector_wrap(*_b_assembly), false);
    VecAXPY(b, 1.0, w.vec());
  }
}
//-----------------------------------------------------------------------------
void fsai::acoustics::WaveSolver::set_initial_state(
    const fem::Function<double>& p0, const fem::Function<double>* v0)
{
  // p, v given; M a = b(0) − C v − K p
  {
    auto src = p0.x()->array();
    std::copy(src.begin(), src.end(), _p->x()->mutable_array().begin());
  }
  if (v0)
  {
    la::petsc::Vector w(la::petsc::create_vector_wrap(*v0->x()), false);
    VecCopy(w.vec(), _v.vec());
  }
  else
    VecSet(_v.vec(), 0.0);
  assemble_source(_rhs.vec());
  MatMult(_C.mat(), _v.vec(), _work_v.vec());
  VecAXPY(_rhs.vec(), -1.0, _work_v.vec());
  MatMult(_K.mat(), _p_vec.vec(), _work_p.vec());
  VecAXPY(_rhs.vec(), -1.0, _work_p.vec());
  // Walls at rest: ü(0) = p(0)/m, and its load −B ü(0)
  VecSet(_wu.vec(), 0.0);
  VecSet(_wv.vec(), 0.0);
  VecSet(_wa.vec(), 0.0);
  if (_yielding)
  {
    VecPointwiseMult(_wa.vec(), _p_vec.vec(), _wall_mask.vec());
    VecScale(_wa.vec(), 1.0 / _wall_m);
    VecPointwiseMult(_wall_work.vec(), _wa.vec(), _wall_b.vec());
    VecAXPY(_rhs.vec(), -1.0, _wall_work.vec());
  }

  Mat M;
  MatDuplicate(_M.mat(), MAT_COPY_VALUES, &M);
  la::petsc::Matrix Mbc(M, false);
  std::vector<std::int64_t> global(_bc_rows.size());
  _V->dofmap()->index_map->local_to_global(_bc_rows, global);
  std::vector<PetscInt> rows(global.begin(), global.end());
  MatZeroRowsColumns(Mbc.mat(), PetscInt(rows.size()), rows.data(), 1.0,
                     nullptr, nullptr);
  PetscScalar* r;
  VecGetArray(_rhs.vec(), &r);
  for (std::int32_t i : _bc_rows)
    r[i] = 0.0;
  VecRestoreArray(_rhs.vec(), &r);

  la::petsc::KrylovSolver mass_solver(_V->mesh()->comm());
  common::configure_direct_solver(mass_solver.ksp(), _V->mesh()->comm(),
                                  _V->mesh()->topology().dim());
  mass_solver.set_options_prefix("acoustic_mass_");
  mass_solver.set_from_options();
  mass_solver.set_operator(Mbc.mat());
  mass_solver.solve(_a.vec(), _rhs.vec());
  _p->x()->scatter_fwd();
}
//-----------------------------------------------------------------------------
void fsai::acoustics::WaveSolver::step()
{
  const double dt = _dt;
  _t += dt;

  // Newmark predictors (E21): p~ = p + Δt v + (½ − β)Δt² a,
  // v~ = v + (1 − γ)Δt a
  VecWAXPY(_work_p.vec(), dt, _v.vec(), _p_vec.vec());
  VecAXPY(_work_p.vec(), (0.5 - _beta) * dt * dt, _a.vec());
  VecWAXPY(_work_v.vec(), (1.0 - _gamma) * dt, _a.vec(), _v.vec());

  // The slit's κ and load at the new time (before the right-hand side)
  if (_slit)
  {
    _slit->update_operator(_A0.mat(), _A.mat(), _beta);
    _solver.set_operator(_A.mat());
  }

  // Right-hand side b(t + Δt) − C v~ − K p~, zero on pressure-release rows
  {
    common::ScopedTimer t("acoustics: source assembly");
    assemble_source(_rhs.vec());
  }
  Vec tmp = _a.vec(); // a is overwritten by the solve: use it as scratch
  MatMult(_C.mat(), _work_v.vec(), tmp);
  VecAXPY(_rhs.vec(), -1.0, tmp);
  MatMult(_K.mat(), _work_p.vec(), tmp);
  VecAXPY(_rhs.vec(), -1.0, tmp);
  if (_slit)
  {
    // κ of the new time: K(κ) p~ = (K + D_k) p~, A = A0 + βΔt² D_k
    MatMult(_slit->stiffness_change(), _work_p.vec(), tmp);
    VecAXPY(_rhs.vec(), -1.0, tmp);
  }
  if (_yielding)
  {
    // Wall predictors ũ = u + Δt u̇ + (½ − β)Δt² ü, ṽ = u̇ + (1 − γ)Δt ü
    VecWAXPY(_wu_pred.vec(), dt, _wv.vec(), _wu.vec());
    VecAXPY(_wu_pred.vec(), (0.5 - _beta) * dt * dt, _wa.vec());
    VecWAXPY(_wv_pred.vec(), (1.0 - _gamma) * dt, _wa.vec(), _wv.vec());
    // rhs −= B (p~ − r ṽ − k ũ)/m_eff
    wall_acceleration_for(_work_p.vec(), _wall_work.vec());
    VecPointwiseMult(_wall_work.vec(), _wall_work.vec(), _wall_b.vec());
    VecAXPY(_rhs.vec(), -1.0, _wall_work.vec());
  }
  if (!_bc_rows.empty())
  {
    PetscScalar* r;
    VecGetArray(_rhs.vec(), &r);
    for (std::int32_t i : _bc_rows)
      r[i] = 0.0;
    VecRestoreArray(_rhs.vec(), &r);
  }

  {
    common::ScopedTimer t("acoustics: solve");
    _solver.solve(_a.vec(), _rhs.vec());
    KSPConvergedReason reason;
    KSPGetConvergedReason(_solver.ksp(), &reason);
    if (reason < 0)
    {
      throw std::runtime_error("acoustics: linear solve failed at t = "
                               + std::to_string(_t) + " s (KSPConvergedReason "
                               + std::to_string(reason) + ")");
    }
  }

  // Correctors: p = p~ + βΔt² a, v = v~ + γΔt a
  VecWAXPY(_p_vec.vec(), _beta * dt * dt, _a.vec(), _work_p.vec());
  VecWAXPY(_v.vec(), _gamma * dt, _a.vec(), _work_v.vec());
  _p->x()->scatter_fwd();
  if (_slit)
    _slit->update_velocity(_p->x()->array());
  if (_yielding)
  {
    // ü = (p − r ṽ − k ũ)/m_eff on the wall nodes, then the correctors
    wall_acceleration_for(_p_vec.vec(), _wa.vec());
    VecPointwiseMult(_wa.vec(), _wa.vec(), _wall_mask.vec());
    VecWAXPY(_wu.vec(), _beta * dt * dt, _wa.vec(), _wu_pred.vec());
    VecWAXPY(_wv.vec(), _gamma * dt, _wa.vec(), _wv_pred.vec());
  }
}
//-----------------------------------------------------------------------------
void fsai::acoustics::WaveSolver::wall_acceleration_for(Vec p, Vec out) const
{
  VecCopy(p, out);
  VecAXPY(out, -_wall_r, _wv_pred.vec());
  VecAXPY(out, -_wall_k, _wu_pred.vec());
  VecScale(out, 1.0 / _wall_m_eff);
}
//-----------------------------------------------------------------------------
void fsai::acoustics::WaveSolver::assemble_into(const Form& L, Vec out)
{
  _b_assembly->set(0.0);
  fem::assemble_vector(_b_assembly->mutable_array(), L);
  _b_assembly->scatter_rev(std::plus<double>());
  la::petsc::Vector w(la::petsc::create_vector_wrap(*_b_assembly), false);
  VecCopy(w.vec(), out);
}
//-----------------------------------------------------------------------------
double fsai::acoustics::WaveSolver::radiated_flow_rate() const
{
  if (!_piston)
    return 0.0;
  // ∫ v̇ w ds = (1/ρ0) ∫ (c_p ṗ + k_p p) w ds, exact for P1/P2 through b
  PetscScalar bv, bp;
  VecDot(_piston_b.vec(), _v.vec(), &bv);
  VecDot(_piston_b.vec(), _p_vec.vec(), &bp);
  return (_piston_damping * bv + _piston_stiffness * bp) / _rho0;
}
//-----------------------------------------------------------------------------
double fsai::acoustics::WaveSolver::energy() const
{
  PetscScalar ev, ep;
  MatMult(_M.mat(), _v.vec(), _work_v.vec());
  VecDot(_v.vec(), _work_v.vec(), &ev);
  MatMult(_K.mat(), _p_vec.vec(), _work_p.vec());
  VecDot(_p_vec.vec(), _work_p.vec(), &ep);
  return 0.5 * (ev + ep);
}
//-----------------------------------------------------------------------------
std::shared_ptr<fem::Function<double>> fsai::acoustics::absorbing_layer(
    std::shared_ptr<const mesh::Mesh> mesh, std::span<const std::int32_t> cells,
    std::array<double, 3> centre, double r0, double d, double c0, double R0)
{
  fsai::require_positive("absorbing layer: thickness", d);
  fsai::require(R0 > 0 and R0 < 1, "absorbing layer: target reflection",
                "in (0, 1)", R0);
  const int tdim = mesh->topology().dim();
  auto mesh_nc = std::const_pointer_cast<mesh::Mesh>(mesh);
  auto V = std::make_shared<fem::FunctionSpace>(fem::create_functionspace(
      acoustic_forms::functionspace_c(tdim, 1), "sigma", mesh_nc));
  auto sigma = std::make_shared<fem::Function<double>>(V);
  sigma->name = "sigma_layer";
  sigma->x()->set(0.0);
  const double sigma_max = 3.0 * c0 * std::log(1.0 / R0) / (2.0 * d);
  sigma->interpolate(
      [&](auto& x) -> xt::xarray<double>
      {
        xt::xarray<double> s = xt::zeros<double>({x.shape(1)});
        for (std::size_t i = 0; i < x.shape(1); ++i)
        {
          double r2 = 0.0;
          for (std::size_t j = 0; j < 3; ++j)
            r2 += (x(j, i) - centre[j]) * (x(j, i) - centre[j]);
          const double xi = std::clamp((std::sqrt(r2) - r0) / d, 0.0, 1.0);
          s(i) = sigma_max * xi * xi;
        }
        return s;
      },
      cells);
  sigma->x()->scatter_fwd();
  return sigma;
}
//-----------------------------------------------------------------------------
void fsai::acoustics::WaveSolver::save(io::RankState& state,
                                       const std::string& prefix) const
{
  const auto keys = io::node_keys(*_V);
  const std::int32_t owned = _V->dofmap()->index_map->size_local();
  io::put_blocks(state, prefix + "p", _p->x()->array(), 1, keys, owned);
  auto put = [&](const char* name, const la::petsc::Vector& v)
  {
    const PetscScalar* a = nullptr;
    VecGetArrayRead(v.vec(), &a);
    io::put_blocks(state, prefix + name, std::span<const double>(a, owned), 1,
                   keys, owned);
    VecRestoreArrayRead(v.vec(), &a);
  };
  put("p_dot", _v);
  put("p_ddot", _a);
  if (_yielding)
  {
    put("wall_u", _wu);
    put("wall_v", _wv);
    put("wall_a", _wa);
  }
  if (_slit)
    _slit->save(state, prefix);
  state[prefix + "t"] = {_t};
}
//-----------------------------------------------------------------------------
void fsai::acoustics::WaveSolver::load(const std::vector<io::RankState>& ranks,
                                       const std::string& prefix)
{
  const auto keys = io::node_keys(*_V);
  const std::int32_t owned = _V->dofmap()->index_map->size_local();
  io::get_blocks(ranks, prefix + "p", _p->x()->mutable_array(), 1, keys);
  auto get = [&](const char* name, la::petsc::Vector& v)
  {
    PetscScalar* a = nullptr;
    VecGetArray(v.vec(), &a);
    io::get_blocks(ranks, prefix + name, std::span<double>(a, owned), 1,
                   std::span(keys.data(), owned));
    VecRestoreArray(v.vec(), &a);
    VecGhostUpdateBegin(v.vec(), INSERT_VALUES, SCATTER_FORWARD);
    VecGhostUpdateEnd(v.vec(), INSERT_VALUES, SCATTER_FORWARD);
  };
  get("p_dot", _v);
  get("p_ddot", _a);
  if (_yielding)
  {
    get("wall_u", _wu);
    get("wall_v", _wv);
    get("wall_a", _wa);
  }
  if (_slit)
    _slit->load(ranks, prefix);
  _t = io::state_entry(ranks.at(0), prefix + "t", 1)[0];
}
