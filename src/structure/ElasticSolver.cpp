// Copyright (C) 2026 fsai developers
#include "ElasticSolver.h"
#include "../common/Parameters.h"
#include "../common/Runtime.h"
#include "../common/errors.h"
#include "../common/petsc_solver.h"
#include "../common/timer.h"
#include "../io/field_state.h"
#include <cmath>
#include <dolfinx/fem/DirichletBC.h>
#include <dolfinx/fem/assembler.h>
#include <dolfinx/fem/petsc.h>
#include <dolfinx/fem/utils.h>
#include <fmt/format.h>
#include <fsai_forms/structure.h>

using namespace dolfinx;
namespace structure_forms = fsai::forms::structure;

namespace
{
double global_norm(const la::Vector<double>& x)
{
  return la::norm(x, la::Norm::l2);
}
} // namespace

//-----------------------------------------------------------------------------
void fsai::structure::Material::validate(const std::string& what) const
{
  fsai::require_positive(what + ".E", E);
  fsai::require(nu > -1.0 and nu < 0.5, what + ".nu", "in (-1, 0.5)", nu);
  fsai::require_positive(what + ".rho", rho);
}
//-----------------------------------------------------------------------------
void fsai::structure::SolidParameters::bind(fsai::common::Parameters& p)
{
  p.add_choice("solid.model", model, {"linear", "svk"},
               "linear elasticity or St.Venant-Kirchhoff");
  p.add("solid.degree", degree, "Lagrange degree of the displacement (1, 2)");
  p.add("solid.E", material.E, "Young's modulus [Pa]");
  p.add("solid.nu", material.nu, "Poisson's ratio");
  p.add("solid.rho", material.rho, "density [kg/m^3]");
  p.add("solid.newmark_beta", newmark_beta, "Newmark beta");
  p.add("solid.newmark_gamma", newmark_gamma, "Newmark gamma");
  p.add("solid.rho_inf", rho_inf,
        "generalised-alpha: spectral radius at infinite frequency in [0, 1] "
        "(sets beta, gamma, alpha_m, alpha_f); < 0: Newmark with "
        "solid.newmark_beta and _gamma");
  p.add("solid.rayleigh_mass", rayleigh_mass,
        "Rayleigh eps1 (D = eps1 M + eps2 K) [1/s]");
  p.add("solid.rayleigh_stiffness", rayleigh_stiffness, "Rayleigh eps2 [s]");
  p.add("solid.newton_rtol", newton_rtol, "Newton tolerance on |du|/|u|");
  p.add("solid.newton_max_it", newton_max_it, "Newton iteration limit");
  p.add("solid.newton_reuse", newton_reuse,
        "modified Newton: reuse the factorised Jacobian while it converges");
  p.add("solid.newton_reuse_rate", newton_reuse_rate,
        "modified Newton: refactorise when |du| shrinks by less than this");
  p.add("solid.newton_warm_start", newton_warm_start,
        "a repeated step (coupling iteration) starts Newton from the last "
        "iteration's solution");
  p.add_choice("solid.assembly", assembly, {"coo", "dolfinx"},
               "Newton tangent insertion: PETSc COO on a recorded pattern, or "
               "DOLFINx's per-cell MatSetValuesBlockedLocal (the same matrix "
               "to rounding)");
  p.add("solid.clamped_length", clamped_length,
        "2D: length of the body clamped at both ends along z (its first "
        "harmonic, a foundation mu (pi/L)^2 u); 0: plane strain [m]");
}
//-----------------------------------------------------------------------------
void fsai::structure::SolidParameters::set_damping_ratio(double zeta,
                                                         double f_low,
                                                         double f_high)
{
  const double wl = 2 * M_PI * f_low, wh = 2 * M_PI * f_high;
  rayleigh_mass = 2 * zeta * wl * wh / (wl + wh);
  rayleigh_stiffness = 2 * zeta / (wl + wh);
}
//-----------------------------------------------------------------------------
void fsai::structure::SolidParameters::validate() const
{
  fsai::require(model == "linear" or model == "svk", "--solid.model",
                "linear or svk", model);
  fsai::require(degree == 1 or degree == 2, "--solid.degree", "1 or 2", degree);
  material.validate("--solid");
  fsai::require_range("--solid.newmark_gamma", newmark_gamma, 0.5, 1.0);
  fsai::require(2 * newmark_beta >= newmark_gamma and newmark_beta <= 0.5,
                "--solid.newmark_beta",
                "in [gamma/2, 1/2] (unconditionally stable)", newmark_beta);
  fsai::require(rho_inf < 0 or rho_inf <= 1, "--solid.rho_inf",
                "in [0, 1] (generalised-alpha) or < 0 (Newmark)", rho_inf);
  fsai::require(rayleigh_mass >= 0, "--solid.rayleigh_mass", ">= 0",
                rayleigh_mass);
  fsai::require(rayleigh_stiffness >= 0, "--solid.rayleigh_stiffness", ">= 0",
                rayleigh_stiffness);
  fsai::require(clamped_length >= 0, "--solid.clamped_length",
                ">= 0 (0: plane strain)", clamped_length);
  fsai::require_positive("--solid.newton_rtol", newton_rtol);
  fsai::require(newton_max_it >= 1, "--solid.newton_max_it", ">= 1",
                newton_max_it);
  fsai::require(newton_reuse_rate > 0 and newton_reuse_rate < 1,
                "--solid.newton_reuse_rate", "in (0, 1)", newton_reuse_rate);
}
//-----------------------------------------------------------------------------
fsai::structure::TimeScheme
fsai::structure::TimeScheme::from(const SolidParameters& p)
{
  if (p.rho_inf < 0)
    return {p.newmark_beta, p.newmark_gamma, 0.0, 0.0};
  // Chung & Hulbert (1993): second order, unconditionally stable, the
  // least low-frequency damping for the given ρ∞ (docs/model.md E18a)
  const double r = p.rho_inf;
  const double am = (2 * r - 1) / (r + 1), af = r / (r + 1);
  const double g = 0.5 - am + af;
  return {0.25 * (1 - am + af) * (1 - am + af), g, am, af};
}
//-----------------------------------------------------------------------------
fsai::structure::ElasticSolver::ElasticSolver(
    std::shared_ptr<const mesh::Mesh> mesh, std::span<const std::int32_t> fixed,
    std::span<const std::int32_t> loaded, const SolidParameters& params,
    double dt)
    : _p(params), _scheme(TimeScheme::from(params)), _dt(dt),
      _Jmat(nullptr, false), _solver(mesh->comm())
{
  common::ScopedTimer timer("solid: setup");
  params.validate();
  fsai::require_positive("solid: time step", dt);
  const int tdim = mesh->topology().dim();
  fsai::require(tdim == 2 or params.clamped_length == 0,
                "--solid.clamped_length", "0 on a 3D mesh (2D sections only)",
                params.clamped_length);
  const int deg = params.degree;
  auto mesh_nc = std::const_pointer_cast<mesh::Mesh>(mesh);
  _V = std::make_shared<fem::FunctionSpace>(fem::create_functionspace(
      structure_forms::functionspace_R(tdim, deg), "u", mesh_nc));
  auto Q = std::make_shared<fem::FunctionSpace>(fem::create_functionspace(
      structure_forms::functionspace_R(tdim, deg), "mu", mesh_nc));
  auto vec = [&](const std::string& name)
  {
    auto f = std::make_shared<fem::Function<double>>(_V);
    f->name = name;
    f->x()->set(0.0);
    return f;
  };
  _u = vec("displacement");
  _u_n = vec("u_n");
  _v_n = vec("v_n");
  _a_n = vec("a_n");
  _v = vec("velocity");
  _a = vec("acceleration");
  _traction = vec("traction");
  _traction_n = vec("traction_n");
  _T_last.assign(_traction->x()->array().size(), 0.0);
  _T_last_t = _t;
  auto scalar = [&](const std::string& name, double value)
  {
    auto f = std::make_shared<fem::Function<double>>(Q);
    f->name = name;
    f->x()->set(value);
    return f;
  };
  _lambda = scalar("lambda", params.material.lambda());
  _mu = scalar("mu", params.material.mu());
  _rho = scalar("density", params.material.rho);

  auto constant = [&](double value)
  {
    _constants.push_back(std::make_shared<fem::Constant<double>>(value));
    return _constants.back();
  };
  _dt_c = constant(dt);
  _dynamic = constant(1.0);
  _load = constant(1.0);
  _k_c = constant(0.0);
  _b_c = constant(0.0);
  _y_c = constant(0.0);
  std::vector<double> g0(tdim, 0.0);
  _g = std::make_shared<fem::Constant<double>>(std::span<const double>(g0));
  std::map<std::string, std::shared_ptr<const fem::Constant<double>>> c
      = {{"dt", _dt_c},
         {"beta", constant(_scheme.beta)},
         {"gamma", constant(_scheme.gamma)},
         {"alpha_m", constant(_scheme.alpha_m)},
         {"alpha_f", constant(_scheme.alpha_f)},
         {"eps1", constant(params.rayleigh_mass)},
         {"eps2", constant(params.rayleigh_stiffness)},
         {"dynamic", _dynamic},
         {"nonlinear", constant(params.model == "svk" ? 1.0 : 0.0)},
         {"load", _load},
         {"g", _g},
         {"k_c", _k_c},
         {"b_c", _b_c},
         {"y_c", _y_c},
         {"kz2", constant(params.clamped_length > 0
                              ? std::pow(M_PI / params.clamped_length, 2)
                              : 0.0)}};
  std::map<std::string, std::shared_ptr<const fem::Function<double>>> coeffs
      = {{"u", _u},
         {"u_n", _u_n},
         {"v_n", _v_n},
         {"a_n", _a_n},
         {"traction", _traction},
         {"traction_n", _traction_n},
         {"lmbda", _lambda},
         {"mu", _mu},
         {"rho", _rho}};

  // Dirichlet u = 0 and the loaded boundary (ds(1))
  const int fdim = tdim - 1;
  mesh_nc->topology_mutable().create_connectivity(fdim, tdim);
  std::vector<std::int32_t> dofs
      = fem::locate_dofs_topological(*_V, fdim, fixed);
  auto zero = vec("zero");
  _bcs = {std::make_shared<const fem::DirichletBC<double>>(zero, dofs)};
  std::vector<std::int32_t> lf(loaded.begin(), loaded.end());
  std::sort(lf.begin(), lf.end());
  lf.erase(std::unique(lf.begin(), lf.end()), lf.end());
  std::vector<std::int32_t> ones(lf.size(), 1);
  _loaded_tags = std::make_shared<mesh::MeshTags<std::int32_t>>(
      mesh, fdim, std::move(lf), std::move(ones));
  std::map<fem::IntegralType, const mesh::MeshTags<int>*> sd
      = {{fem::IntegralType::exterior_facet, _loaded_tags.get()}};

  _R = std::make_shared<fem::Form<double>>(fem::create_form<double>(
      structure_forms::R(tdim, deg), {_V}, coeffs, c, sd));
  _J = std::make_shared<fem::Form<double>>(fem::create_form<double>(
      structure_forms::J(tdim, deg), {_V, _V}, coeffs, c, sd));
  _K = std::make_shared<fem::Form<double>>(fem::create_form<double>(
      structure_forms::k(tdim, deg), {_V, _V}, coeffs, c, {}));
  _M = std::make_shared<fem::Form<double>>(fem::create_form<double>(
      structure_forms::m(tdim, deg), {_V, _V}, coeffs, c, {}));
  _F_c = std::make_shared<fem::Form<double>>(fem::create_form<double>(
      structure_forms::contact_force(tdim, deg), {}, coeffs, c, sd, mesh));
  _Jmat = la::petsc::Matrix(fem::petsc::create_matrix(*_J), false);

  _solver.set_options_prefix("solid_");
  common::configure_direct_solver(_solver.ksp(), mesh->comm(), tdim, false,
                                  _V->dofmap()->index_map->size_global()
                                      * _V->dofmap()->index_map_bs());
  _solver.set_from_options();
  _solver.set_operator(_Jmat.mat());
}
//-----------------------------------------------------------------------------
void fsai::structure::ElasticSolver::fix_where(
    const std::function<bool(std::span<const double, 3>)>& where)
{
  auto zero = std::make_shared<fem::Function<double>>(_V);
  zero->x()->set(0.0);
  const auto d = fem::locate_dofs_geometrical(
      *_V,
      [&](const xt::xtensor<double, 2>& x) -> xt::xtensor<bool, 1>
      {
        xt::xtensor<bool, 1> on = xt::zeros<bool>({x.shape(1)});
        for (std::size_t i = 0; i < x.shape(1); ++i)
        {
          const std::array<double, 3> p{x(0, i), x(1, i), x(2, i)};
          on(i) = where(p);
        }
        return on;
      });
  _bcs.push_back(std::make_shared<const fem::DirichletBC<double>>(zero, d));
  _J_current = false;
}
//-----------------------------------------------------------------------------
void fsai::structure::ElasticSolver::set_material(
    std::span<const std::int32_t> cells, const Material& m)
{
  m.validate("material");
  auto dofmap = _mu->function_space()->dofmap();
  auto set = [&](fem::Function<double>& f, double value)
  {
    auto x = f.x()->mutable_array();
    for (std::int32_t c : cells)
      x[dofmap->cell_dofs(c)[0]] = value; // DG0: one dof per cell
    f.x()->scatter_fwd();
  };
  set(*_lambda, m.lambda());
  set(*_mu, m.mu());
  set(*_rho, m.rho);
  _J_current = false;
}
//-----------------------------------------------------------------------------
void fsai::structure::ElasticSolver::set_contact(double k, double b, double y_c)
{
  fsai::require(k >= 0, "solid: contact stiffness", ">= 0", k);
  fsai::require(b >= 0, "solid: contact damping", ">= 0", b);
  _k_c->value[0] = k;
  _b_c->value[0] = b;
  _y_c->value[0] = y_c;
  _J_current = false;
}
//-----------------------------------------------------------------------------
double fsai::structure::ElasticSolver::contact_force() const
{
  // The form holds the Newmark velocity of the unknown u from u_n, v_n, a_n:
  // after a step these are the step's start, so the damping part is the
  // step's own (with generalised-α, the force at t_{n+1−α_f}, E18a)
  const double local = fem::assemble_scalar(*_F_c);
  double global = 0;
  MPI_Allreduce(&local, &global, 1, MPI_DOUBLE, MPI_SUM, _V->mesh()->comm());
  return global;
}
//-----------------------------------------------------------------------------
double fsai::structure::ElasticSolver::contact_overlap() const
{
  // The contact form with k = 1 and no damping
  const double k = _k_c->value[0], b = _b_c->value[0];
  _k_c->value[0] = 1.0;
  _b_c->value[0] = 0.0;
  const double overlap = contact_force();
  _k_c->value[0] = k;
  _b_c->value[0] = b;
  return overlap;
}
//-----------------------------------------------------------------------------
void fsai::structure::ElasticSolver::set_body_acceleration(
    std::array<double, 3> g)
{
  for (std::size_t i = 0; i < _g->value.size(); ++i)
    _g->value[i] = g[i];
}
//-----------------------------------------------------------------------------
int fsai::structure::ElasticSolver::newton(const std::string& what)
{
  la::Vector<double> b(_V->dofmap()->index_map, _V->dofmap()->index_map_bs());
  la::Vector<double> du(_V->dofmap()->index_map, _V->dofmap()->index_map_bs());
  la::petsc::Vector _b(la::petsc::create_vector_wrap(b), false);
  la::petsc::Vector _du(la::petsc::create_vector_wrap(du), false);
  // Linear elasticity without contact: one Newton iteration is exact and
  // the Jacobian constant
  const bool linear
      = _p.model == "linear" and _k_c->value[0] == 0.0 and !_contact_update;
  double r0 = -1.0;
  double dnorm_prev = -1.0;
  // Modified Newton in dynamic steps only: there the mass term dominates
  // the tangent and a step moves little; a static solve from rest is too
  // nonlinear for an old tangent (CSM1's first load step diverges with it)
  const bool reuse = _p.newton_reuse and _dynamic->value[0] > 0;
  if (!reuse)
    _J_stale = true;
  for (int it = 1; it <= _p.newton_max_it; ++it)
  {
    if (_contact_update)
      _contact_update(it);
    // Residual, zero on the Dirichlet rows (u stays 0 there)
    {
      common::ScopedTimer t("solid: assemble residual");
      b.set(0.0);
      fem::assemble_vector(b.mutable_array(), *_R);
      b.scatter_rev(std::plus<double>());
      fem::set_bc<double>(b.mutable_array(), _bcs);
    }
    const double rnorm = global_norm(b);
    if (!std::isfinite(rnorm))
    {
      throw std::runtime_error(fmt::format(
          "solid: residual is not finite at t = {:.6g} s ({})", _t, what));
    }
    if (r0 < 0.0)
      r0 = rnorm;
    if (rnorm <= _p.newton_atol)
      return it - 1;

    // Jacobian: constant for the linear model while Δt is fixed; with
    // newton_reuse the last factorised one while it still contracts
    if (!_J_current or (!linear and (!reuse or _J_stale)))
    {
      common::ScopedTimer t("solid: assemble jacobian");
      // The tangent's domains, dofmap and fixed dofs never change (what the
      // COO pattern needs; u = 0 there, so no lifting), only its values. The
      // pattern is recorded at the first assembly, not in the constructor:
      // the modal analysis only uses K and M
      if (_p.assembly == "coo" and !_coo)
        _coo = std::make_unique<common::CooMatrixAssembler>(_Jmat.mat(), *_J,
                                                            _bcs);
      if (_coo)
        _coo->assemble(_Jmat.mat(), *_J);
      else
        common::assemble_matrix_per_cell(_Jmat.mat(), *_J, _bcs);
      _solver.set_operator(_Jmat.mat());
      _J_current = true;
      _J_stale = false;
      dnorm_prev = -1.0; // a fresh tangent: no contraction test yet
    }
    {
      common::ScopedTimer t("solid: solve");
      VecScale(_b.vec(), -1.0);
      _solver.solve(_du.vec(), _b.vec());
      KSPConvergedReason reason;
      KSPGetConvergedReason(_solver.ksp(), &reason);
      if (reason < 0)
      {
        throw std::runtime_error(fmt::format(
            "solid: linear solve failed at t = {:.6g} s, Newton iteration {} "
            "(KSPConvergedReason {})",
            _t, it, int(reason)));
      }
    }
    du.scatter_fwd();
    auto u = _u->x()->mutable_array();
    auto d = du.array();
    for (std::size_t i = 0; i < u.size(); ++i)
      u[i] += d[i];
    if (linear)
      return it; // exact in one iteration (J is the exact tangent)
    const double dnorm = global_norm(du), unorm = global_norm(*_u->x());
    // An old tangent that no longer contracts fast is refreshed
    if (dnorm_prev > 0 and dnorm > _p.newton_reuse_rate * dnorm_prev)
      _J_stale = true;
    dnorm_prev = dnorm;
    if (dnorm <= _p.newton_rtol * std::max(unorm, 1e-300))
      return it;
  }
  throw std::runtime_error(fmt::format(
      "solid: Newton did not converge in {} iterations at t = {:.6g} s ({}); "
      "reduce the time step or the load increments",
      _p.newton_max_it, _t, what));
}
//-----------------------------------------------------------------------------
int fsai::structure::ElasticSolver::step()
{
  common::ScopedTimer timer("solid: step");
  // Start from the old state: u_n, v_n, a_n; predictor u = u_n
  auto cp = [](const fem::Function<double>& s, fem::Function<double>& d)
  {
    std::copy(s.x()->array().begin(), s.x()->array().end(),
              d.x()->mutable_array().begin());
  };
  cp(*_u, *_u_n);
  cp(*_v, *_v_n);
  cp(*_a, *_a_n);
  if (!_guess.empty())
  {
    // Warm start: the solution of the previous coupling iteration
    std::copy(_guess.begin(), _guess.end(), _u->x()->mutable_array().begin());
    _guess.clear();
  }
  // T_n (E18a): the traction under which the state at this step's start
  // was computed (the last step's, or the static solve's; 0 at rest, as
  // a_0 = 0 assumes); a step repeated from its start (restore_state) keeps
  // its T_n
  if (_T_last_t == _t)
    std::copy(_T_last.begin(), _T_last.end(),
              _traction_n->x()->mutable_array().begin());
  _dynamic->value[0] = 1.0;
  _load->value[0] = 1.0;
  _t += _dt;
  const int its = newton("dynamic step");
  _stepped = true;
  remember_traction();

  // Newmark update (E18): a = (u − ũ)/(βΔt²), v = v_n + Δt((1−γ)a_n + γa)
  const double b = _scheme.beta, g = _scheme.gamma, dt = _dt;
  auto u = _u->x()->array(), un = _u_n->x()->array(), vn = _v_n->x()->array(),
       an = _a_n->x()->array();
  auto v = _v->x()->mutable_array(), a = _a->x()->mutable_array();
  for (std::size_t i = 0; i < u.size(); ++i)
  {
    const double ut = un[i] + dt * vn[i] + (0.5 - b) * dt * dt * an[i];
    a[i] = (u[i] - ut) / (b * dt * dt);
    v[i] = vn[i] + dt * ((1 - g) * an[i] + g * a[i]);
  }
  return its;
}
//-----------------------------------------------------------------------------
void fsai::structure::ElasticSolver::remember_traction()
{
  // The next step's T_n (E18a)
  _T_last.assign(_traction->x()->array().begin(),
                 _traction->x()->array().end());
  _T_last_t = _t;
}
//-----------------------------------------------------------------------------
void fsai::structure::ElasticSolver::set_dt(double dt)
{
  fsai::require_positive("solid: time step", dt);
  if (dt == _dt)
    return;
  _dt = dt;
  _dt_c->value[0] = dt;
  _J_current = false; // the inertia term M/(βΔt²) changed
}
//-----------------------------------------------------------------------------
int fsai::structure::ElasticSolver::solve_static(int load_steps)
{
  fsai::require(load_steps >= 1, "solid: load steps", ">= 1", load_steps);
  common::ScopedTimer timer("solid: static solve");
  _dynamic->value[0] = 0.0;
  _J_current = false;
  int its = 0;
  for (int k = 1; k <= load_steps; ++k)
  {
    _load->value[0] = double(k) / load_steps;
    its += newton(fmt::format("load step {}/{}", k, load_steps));
  }
  _dynamic->value[0] = 1.0;
  _load->value[0] = 1.0;
  _J_current = false;
  remember_traction();
  return its;
}
//-----------------------------------------------------------------------------
void fsai::structure::ElasticSolver::save_state()
{
  _saved.clear();
  for (auto& f : {_u, _v, _a})
    _saved.insert(_saved.end(), f->x()->array().begin(), f->x()->array().end());
  _saved.push_back(_t);
  _guess.clear();
  _stepped = false;
}
//-----------------------------------------------------------------------------
void fsai::structure::ElasticSolver::save(io::RankState& state,
                                          const std::string& prefix) const
{
  _J_stale = true;
  const auto keys = io::node_keys(*_V);
  const int bs = _V->dofmap()->index_map_bs();
  const std::int32_t owned = _V->dofmap()->index_map->size_local();
  for (const auto& [name, f] : {std::pair{"u", _u}, {"v", _v}, {"a", _a}})
    io::put_blocks(state, prefix + name, f->x()->array(), bs, keys, owned);
  state[prefix + "t"] = {_t};
  // The next step's T_n (E18a), so that a restart continues identically
  if (_T_last_t == _t)
    io::put_blocks(state, prefix + "T_last", _T_last, bs, keys, owned);
}
//-----------------------------------------------------------------------------
void fsai::structure::ElasticSolver::load(
    const std::vector<io::RankState>& ranks, const std::string& prefix)
{
  const auto keys = io::node_keys(*_V);
  const int bs = _V->dofmap()->index_map_bs();
  for (const auto& [name, f] : {std::pair{"u", _u}, {"v", _v}, {"a", _a}})
    io::get_blocks(ranks, prefix + name, f->x()->mutable_array(), bs, keys);
  _t = io::state_entry(ranks.at(0), prefix + "t", 1)[0];
  _T_last.assign(_traction->x()->array().size(), 0.0);
  if (ranks.at(0).count(prefix + "T_last"))
    io::get_blocks(ranks, prefix + "T_last", std::span<double>(_T_last), bs,
                   keys);
  _T_last_t = _t;
  _saved.clear();
  _guess.clear();
  _J_stale = true;
}
//-----------------------------------------------------------------------------
void fsai::structure::ElasticSolver::restore_state()
{
  if (_saved.empty())
    throw std::runtime_error("solid: restore_state without save_state");
  if (_p.newton_warm_start and _stepped)
    _guess.assign(_u->x()->array().begin(), _u->x()->array().end());
  std::size_t off = 0;
  for (auto& f : {_u, _v, _a})
  {
    auto x = f->x()->mutable_array();
    std::copy_n(_saved.begin() + off, x.size(), x.begin());
    off += x.size();
  }
  _t = _saved.back();
}
//-----------------------------------------------------------------------------
namespace
{
double quadratic_form(const fem::Form<double>& a,
                      const fem::Function<double>& x)
{
  la::petsc::Matrix A(fem::petsc::create_matrix(a), false);
  MatZeroEntries(A.mat());
  fem::assemble_matrix(la::petsc::Matrix::set_block_fn(A.mat(), ADD_VALUES), a,
                       {});
  MatAssemblyBegin(A.mat(), MAT_FINAL_ASSEMBLY);
  MatAssemblyEnd(A.mat(), MAT_FINAL_ASSEMBLY);
  la::petsc::Vector xv(la::petsc::create_vector_wrap(*x.x()), false);
  Vec y;
  VecDuplicate(xv.vec(), &y);
  MatMult(A.mat(), xv.vec(), y);
  PetscScalar r;
  VecDot(xv.vec(), y, &r);
  VecDestroy(&y);
  return r;
}
} // namespace
double fsai::structure::ElasticSolver::kinetic_energy()
{
  return 0.5 * quadratic_form(*_M, *_v);
}
//-----------------------------------------------------------------------------
double fsai::structure::ElasticSolver::strain_energy()
{
  return 0.5 * quadratic_form(*_K, *_u);
}
//-----------------------------------------------------------------------------
la::petsc::Matrix
fsai::structure::ElasticSolver::stiffness_matrix(double diagonal) const
{
  la::petsc::Matrix A(fem::petsc::create_matrix(*_K), false);
  MatZeroEntries(A.mat());
  fem::assemble_matrix(la::petsc::Matrix::set_block_fn(A.mat(), ADD_VALUES),
                       *_K, _bcs);
  MatAssemblyBegin(A.mat(), MAT_FLUSH_ASSEMBLY);
  MatAssemblyEnd(A.mat(), MAT_FLUSH_ASSEMBLY);
  fem::set_diagonal<double>(la::petsc::Matrix::set_fn(A.mat(), INSERT_VALUES),
                            *_V, _bcs, diagonal);
  MatAssemblyBegin(A.mat(), MAT_FINAL_ASSEMBLY);
  MatAssemblyEnd(A.mat(), MAT_FINAL_ASSEMBLY);
  return A;
}
//-----------------------------------------------------------------------------
la::petsc::Matrix fsai::structure::ElasticSolver::mass_matrix() const
{
  la::petsc::Matrix A(fem::petsc::create_matrix(*_M), false);
  MatZeroEntries(A.mat());
  fem::assemble_matrix(la::petsc::Matrix::set_block_fn(A.mat(), ADD_VALUES),
                       *_M, _bcs);
  MatAssemblyBegin(A.mat(), MAT_FINAL_ASSEMBLY);
  MatAssemblyEnd(A.mat(), MAT_FINAL_ASSEMBLY);
  return A;
}
//-----------------------------------------------------------------------------
