// Copyright (C) 2026 fsai developers
#include "FluidSolver.h"
#include "../common/Parameters.h"
#include "../common/Runtime.h"
#include "../common/bdf.h"
#include "../common/errors.h"
#include "../common/petsc_solver.h"
#include "../common/timer.h"
#include <cmath>
#include <dolfinx/fem/assembler.h>
#include <dolfinx/fem/petsc.h>
#include <dolfinx/fem/utils.h>
#include <dolfinx/mesh/utils.h>
#include <fmt/format.h>
#include <fsai_forms/fluid.h>
#include <io/field_state.h>
#include <numeric>
#include <petscpc.h>

using namespace dolfinx;
namespace fluid_forms = fsai::forms::fluid;

namespace
{
// Entries of a function's vector owned by this rank (ghosts excluded, so
// norms summed over ranks count each dof once, as in a serial run)
std::size_t owned_entries(const dolfinx::fem::Function<double>& f)
{
  const auto& map = *f.x()->map();
  return std::size_t(map.size_local()) * f.x()->bs();
}

// The owned dofs of a collapsed subspace (sub: its dof → the mixed space's
// local dof) in a fieldsplit's order, the mixed space's local numbering
std::vector<std::int32_t> split_order(const std::vector<std::int32_t>& sub,
                                      std::int32_t owned)
{
  std::vector<std::int32_t> order;
  for (std::size_t j = 0; j < sub.size(); ++j)
    if (sub[j] < owned)
      order.push_back(std::int32_t(j));
  std::sort(order.begin(), order.end(),
            [&](std::int32_t i, std::int32_t j) { return sub[i] < sub[j]; });
  return order;
}

// 1/Δt_τ of τ_m's transient term (E20): the run's step, a fixed one, or
// none (the steady τ_m)
double inverse_tau_step(const fsai::fluid::FluidParameters& p, double dt)
{
  if (!p.tau_dt)
    return 0.0;
  return 1.0 / (p.tau_step > 0 ? p.tau_step : dt);
}
} // namespace
//-----------------------------------------------------------------------------
void fsai::fluid::FluidParameters::bind(fsai::common::Parameters& p)
{
  p.add("fluid.rho", rho, "density [kg/m^3]");
  p.add("fluid.mu", mu, "dynamic viscosity [Pa s]");
  p.add("fluid.supg", supg, "SUPG stabilisation");
  p.add("fluid.pspg", pspg, "PSPG stabilisation");
  p.add("fluid.graddiv", graddiv, "div-div stabilisation");
  p.add("fluid.tau_dt", tau_dt,
        "SUPG/PSPG tau_m with its transient term (2/dt)^2 (false: tau of "
        "the steady problem)");
  p.add("fluid.tau_step", tau_step,
        "the step in tau_m's transient term (2/dt_tau)^2 [s] (0: the run's "
        "dt; fixed: tau_m does not change with dt or at a cut step)");
  p.add("fluid.tau_porous", tau_porous,
        "SUPG/PSPG tau_m with the porous term (sigma_p chi/rho)^2 (the "
        "iterative solver needs it where the porous region closes the "
        "channel)");
  p.add("fluid.picard", picard, "linear solves per time step (1: Oseen)");
  p.add("fluid.picard_tol", picard_tol, "Picard tolerance on |dv|/|v|");
  p.add("fluid.sigma_p", sigma_p, "porous inverse permeability [kg/(m^3 s)]");
  p.add("fluid.inlet_eps", inlet_eps, "inlet penalty epsilon [s/m]");
  p.add("fluid.p_in", p_in, "inlet reference pressure [Pa]");
  p.add("fluid.p_out", p_out, "outlet reference pressure [Pa]");
  p.add_choice("fluid.solver", solver, {"direct", "iterative"},
               "linear solver: MUMPS LU, or Schur fieldsplit + AMG (3D)");
  p.add_choice("fluid.velocity_pc", velocity_pc, {"amg", "ilu"},
               "iterative solver: velocity-block preconditioner");
  p.add_choice("fluid.schur", schur, {"selfp", "pcd"},
               "iterative solver: Schur-complement approximation (pcd: "
               "pressure convection-diffusion, holds in the glottal jet)");
  p.add("fluid.ksp_rtol", ksp_rtol,
        "iterative solver: relative tolerance (the previous step's solution "
        "is the initial guess)");
  p.add("fluid.pc_lag", pc_lag,
        "iterative solver: rebuild the preconditioner every pc_lag-th solve "
        "(1: every solve; the solve still meets ksp_rtol)");
  p.add("fluid.refine_rtol", refine_rtol,
        "direct solver: a step solved again (the coupling's next iterate) "
        "refines the step's first factorisation to this residual relative "
        "to |b| instead of factorising anew (0: factorise every solve)");
  p.add("fluid.refine_max_its", refine_max_its,
        "direct solver: refinement iterations before a fresh "
        "factorisation");
  p.add_choice("fluid.assembly", assembly, {"coo", "dolfinx"},
               "matrix insertion: PETSc COO on a recorded pattern, or "
               "DOLFINx's per-cell MatSetValuesLocal (the same matrix to "
               "rounding)");
  p.add("fluid.quadrature_degree", quadrature_degree,
        "quadrature degree of the cell integrals, 4 or 2 (both exact for the "
        "Galerkin terms; 2 samples the stabilisation at fewer points)");
}
//-----------------------------------------------------------------------------
void fsai::fluid::FluidParameters::validate() const
{
  fsai::require_positive("--fluid.rho", rho);
  fsai::require_positive("--fluid.mu", mu);
  fsai::require(tau_step >= 0, "--fluid.tau_step", ">= 0", tau_step);
  fsai::require(picard >= 1 and picard <= 100, "--fluid.picard", "in [1, 100]",
                picard);
  fsai::require_positive("--fluid.picard_tol", picard_tol);
  fsai::require(sigma_p >= 0, "--fluid.sigma_p", ">= 0", sigma_p);
  fsai::require(inlet_eps >= 0, "--fluid.inlet_eps", ">= 0", inlet_eps);
  fsai::require(ksp_rtol > 0 and ksp_rtol < 1, "--fluid.ksp_rtol", "in (0, 1)",
                ksp_rtol);
  fsai::require(pc_lag >= 1, "--fluid.pc_lag", ">= 1", pc_lag);
  fsai::require(refine_rtol >= 0 and refine_rtol < 1, "--fluid.refine_rtol",
                "in [0, 1)", refine_rtol);
  fsai::require(refine_max_its >= 1, "--fluid.refine_max_its", ">= 1",
                refine_max_its);
  fsai::require(quadrature_degree == 2 or quadrature_degree == 4,
                "--fluid.quadrature_degree", "2 or 4", quadrature_degree);
}
//-----------------------------------------------------------------------------
fsai::fluid::FluidSolver::FluidSolver(std::shared_ptr<const mesh::Mesh> mesh,
                                      const FluidBoundaries& bnd,
                                      const FluidParameters& p, double dt)
    : _par(p), _dt(dt), _dt_n(dt), _A(nullptr, false), _solver(mesh->comm())
{
  common::ScopedTimer timer("fluid: setup");
  p.validate();
  fsai::require_positive("fluid: time step", dt);
  fsai::require(bnd.inlet_penalty.empty() or p.inlet_eps > 0,
                "--fluid.inlet_eps", "> 0 for a penalty inlet", p.inlet_eps);
  auto mesh_nc = std::const_pointer_cast<mesh::Mesh>(mesh);
  create_spaces(mesh_nc);
  create_forms(mesh_nc, bnd);
  create_dirichlet_conditions(bnd);
  create_matrix();
  configure_solver();
}
//-----------------------------------------------------------------------------
void fsai::fluid::FluidSolver::create_spaces(std::shared_ptr<mesh::Mesh> mesh)
{
  // The mixed P1/P1 space, its collapsed velocity and pressure spaces, the
  // porous indicator's DG0 space, and every field of E8–E20
  const int tdim = mesh->topology().dim();
  _W = std::make_shared<fem::FunctionSpace>(fem::create_functionspace(
      fluid_forms::functionspace_a(tdim, 1), "v_0", mesh));
  {
    auto [V, map] = _W->sub({0})->collapse();
    _V = std::make_shared<fem::FunctionSpace>(std::move(V));
    _map_v = std::move(map);
    auto [Q, mapq] = _W->sub({1})->collapse();
    _Q = std::make_shared<fem::FunctionSpace>(std::move(Q));
    _map_p = std::move(mapq);
  }
  _DG0 = std::make_shared<fem::FunctionSpace>(fem::create_functionspace(
      fluid_forms::functionspace_a(tdim, 1), "chi", mesh));
  auto fn = [](auto V, const std::string& name)
  {
    auto f = std::make_shared<fem::Function<double>>(V);
    f->name = name;
    f->x()->set(0.0);
    return f;
  };
  _up = fn(_W, "up");
  _v = fn(_V, "velocity");
  _p = fn(_Q, "pressure");
  _v_n = fn(_V, "v_n");
  _v_nn = fn(_V, "v_nn");
  _v_star = fn(_V, "v_star");
  _w = fn(_V, "mesh_velocity");
  _v_in = fn(_V, "inlet_velocity");
  _v_wall = fn(_V, "wall_velocity");
  _chi = fn(_DG0, "porous");
  _f = fn(_V, "body_force");
}
//-----------------------------------------------------------------------------
void fsai::fluid::FluidSolver::create_forms(std::shared_ptr<mesh::Mesh> mesh,
                                            const FluidBoundaries& bnd)
{
  // forms/fluid.py's system, right-hand side and residual (E12) with the
  // parameters as constants; ds(1) the penalty inlet (E11a), ds(2) the
  // outlet (E11c)
  const auto& p = _par;
  const int tdim = mesh->topology().dim();
  auto constant = [&](double v)
  {
    _constants.push_back(std::make_shared<fem::Constant<double>>(v));
    return _constants.back();
  };
  _a0 = constant(0.0);
  _a1 = constant(0.0);
  _a2 = constant(0.0);
  _inv_dt = constant(inverse_tau_step(p, _dt));
  _p_in = constant(p.p_in);
  std::map<std::string, std::shared_ptr<const fem::Constant<double>>> c
      = {{"rho", constant(p.rho)},
         {"mu", constant(p.mu)},
         {"a0", _a0},
         {"a1", _a1},
         {"a2", _a2},
         {"inv_dt", _inv_dt},
         {"supg", constant(p.supg ? 1.0 : 0.0)},
         {"pspg", constant(p.pspg ? 1.0 : 0.0)},
         {"graddiv", constant(p.graddiv ? 1.0 : 0.0)},
         {"sigma_p", constant(p.sigma_p)},
         {"tau_porous", constant(p.tau_porous ? 1.0 : 0.0)},
         {"inv_eps", constant(p.inlet_eps > 0 ? 1.0 / p.inlet_eps : 0.0)},
         {"p_in", _p_in},
         {"p_out", constant(p.p_out)}};
  std::map<std::string, std::shared_ptr<const fem::Function<double>>> coeffs
      = {{"up", _up}, {"v_n", _v_n},   {"v_nn", _v_nn}, {"v_star", _v_star},
         {"w", _w},   {"v_in", _v_in}, {"chi", _chi},   {"f", _f}};

  // Natural boundaries: ds(1) penalty inlet, ds(2) outlet
  const int fdim = tdim - 1;
  mesh->topology_mutable().create_connectivity(fdim, tdim);
  const std::int32_t nf = mesh->topology().index_map(fdim)->size_local();
  std::vector<std::pair<std::int32_t, int>> tagged;
  for (std::int32_t f : bnd.inlet_penalty)
    if (f < nf)
      tagged.push_back({f, 1});
  for (std::int32_t f : bnd.outlet)
    if (f < nf)
      tagged.push_back({f, 2});
  std::sort(tagged.begin(), tagged.end());
  std::vector<std::int32_t> idx, val;
  for (auto [f, v] : tagged)
    idx.push_back(f), val.push_back(v);
  _tags.push_back(std::make_shared<mesh::MeshTags<std::int32_t>>(
      mesh, fdim, std::move(idx), std::move(val)));
  std::map<fem::IntegralType, const mesh::MeshTags<int>*> sd
      = {{fem::IntegralType::exterior_facet, _tags[0].get()}};

  // The system and the residual (forces) with the same quadrature
  const bool q2 = p.quadrature_degree == 2;
  _a = std::make_shared<fem::Form<double>>(fem::create_form<double>(
      q2 ? fluid_forms::a_q2(tdim, 1) : fluid_forms::a(tdim, 1), {_W, _W},
      coeffs, c, sd));
  _L = std::make_shared<fem::Form<double>>(fem::create_form<double>(
      q2 ? fluid_forms::L_q2(tdim, 1) : fluid_forms::L(tdim, 1), {_W}, coeffs,
      c, sd));
  _F = std::make_shared<fem::Form<double>>(fem::create_form<double>(
      q2 ? fluid_forms::F_res_q2(tdim, 1) : fluid_forms::F_res(tdim, 1), {_W},
      coeffs, c, sd));

  // The PCD Schur approximation (E20b) on the pressure dofs in the
  // fieldsplit's order, p = 0 where the pressure is natural
  if (p.solver == "iterative" and p.schur == "pcd")
  {
    auto form = [&](ufcx_form& f, bool bilinear)
    {
      return std::make_shared<const fem::Form<double>>(fem::create_form<double>(
          f, bilinear ? std::vector{_Q, _Q} : std::vector{_Q}, coeffs, c, {}));
    };
    std::vector<std::int32_t> natural = bnd.inlet_penalty;
    natural.insert(natural.end(), bnd.outlet.begin(), bnd.outlet.end());
    std::sort(natural.begin(), natural.end());
    natural.erase(std::unique(natural.begin(), natural.end()), natural.end());
    _pcd = std::make_unique<PressureConvectionDiffusion>(
        _Q, form(fluid_forms::K_p(tdim, 1), true),
        form(fluid_forms::F_p(tdim, 1), true),
        form(fluid_forms::m_p(tdim, 1), false),
        form(fluid_forms::g_p(tdim, 1), false),
        fem::locate_dofs_topological(*_Q, fdim, natural),
        split_order(_map_p, _W->dofmap()->index_map->size_local()));
  }
}
//-----------------------------------------------------------------------------
void fsai::fluid::FluidSolver::create_dirichlet_conditions(
    const FluidBoundaries& bnd)
{
  const int fdim = _W->mesh()->topology().dim() - 1;
  // Dirichlet: walls (v = wall velocity), Dirichlet inlet, symmetry v_c = 0
  auto W0 = _W->sub({0});
  auto vec_bc = [&](const std::vector<std::int32_t>& facets,
                    std::shared_ptr<fem::Function<double>> g)
  {
    auto dofs = fem::locate_dofs_topological({*W0, *_V}, fdim, facets);
    _bcs.push_back(
        std::make_shared<fem::DirichletBC<double>>(g, std::move(dofs), W0));
  };
  vec_bc(bnd.walls, _v_wall);
  vec_bc(bnd.inlet_dirichlet, _v_in);
  {
    auto W01 = _W->sub({0})->sub({bnd.symmetry_component});
    auto dofs = fem::locate_dofs_topological(*W01, fdim, bnd.symmetry);
    _bcs.push_back(std::make_shared<fem::DirichletBC<double>>(
        std::make_shared<fem::Constant<double>>(0.0), std::move(dofs), W01));
  }
}
//-----------------------------------------------------------------------------
void fsai::fluid::FluidSolver::create_matrix()
{
  _A = la::petsc::Matrix(fem::petsc::create_matrix(*_a), false);
  if (_par.assembly == "coo")
    _coo = std::make_unique<common::CooMatrixAssembler>(_A.mat(), *_a, _bcs);
}
//-----------------------------------------------------------------------------
void fsai::fluid::FluidSolver::configure_solver()
{
  const auto& p = _par;
  auto mesh = _W->mesh();
  const int tdim = mesh->topology().dim();
  // Defaults set on this KSP, then the options database (prefix fluid_)
  // overrides them: global option defaults would leak from one solver
  // instance to the next
  KSP ksp = _solver.ksp();
  PC pc;
  KSPGetPC(ksp, &pc);
  if (p.solver == "direct")
  {
    common::configure_direct_solver(ksp, mesh->comm(), tdim, true);
    // MUMPS's default (ICNTL(8) = 77) recomputes an iterative row/column
    // scaling at every numeric factorisation: 22 % of the factorisation of
    // the FE glottis flow, which refactorises every step. Its
    // threshold pivoting does without: the glottis series agreed to 1e−12.
    // The options database (-fluid_mat_mumps_icntl_8) still decides.
    common::set_option_default("fluid_mat_mumps_icntl_8", "0");
  }
  else
  {
    // Block-triangular Schur preconditioner; PSPG makes the pressure block
    // nonzero, so selfp (A_pp − A_pu diag(A_uu)⁻¹ A_up) is a usable Schur
    // approximation, and both blocks get one AMG V-cycle (or ILU(0) for a
    // mass-dominated velocity block). The previous step's solution is the
    // initial guess: a third fewer iterations in the DFG 2D-2 runs
    KSPSetType(ksp, KSPFGMRES);
    KSPGMRESSetRestart(ksp, 100);
    KSPSetTolerances(ksp, p.ksp_rtol, 1e-50, PETSC_DEFAULT, 500);
    KSPSetInitialGuessNonzero(ksp, PETSC_TRUE);
    PCSetType(pc, PCFIELDSPLIT);
    PCFieldSplitSetType(pc, PC_COMPOSITE_SCHUR);
    PCFieldSplitSetSchurFactType(pc, PC_FIELDSPLIT_SCHUR_FACT_UPPER);
    // With PCD the Schur block's matrix is only a placeholder (A_pp):
    // selfp's product would be formed for nothing
    PCFieldSplitSetSchurPre(pc,
                            p.schur == "pcd" ? PC_FIELDSPLIT_SCHUR_PRE_A11
                                             : PC_FIELDSPLIT_SCHUR_PRE_SELFP,
                            nullptr);
    // (the blocks' KSPs exist only after the first setup: see solve())
  }
  _solver.set_options_prefix("fluid_");
  _solver.set_from_options();
  PetscBool is_fieldsplit;
  PetscObjectTypeCompare((PetscObject)pc, PCFIELDSPLIT, &is_fieldsplit);
  if (is_fieldsplit)
  {
    // Velocity and pressure dofs (owned, global numbering of W)
    auto map = _W->dofmap()->index_map;
    const std::int32_t owned = map->size_local();
    for (auto [name, sub] : {std::pair{"u", &_map_v}, {"p", &_map_p}})
    {
      std::vector<std::int32_t> local;
      for (std::int32_t j : split_order(*sub, owned))
        local.push_back((*sub)[j]);
      std::vector<std::int64_t> global(local.size());
      map->local_to_global(local, global);
      std::vector<PetscInt> idx(global.begin(), global.end());
      IS is;
      ISCreateGeneral(mesh->comm(), PetscInt(idx.size()), idx.data(),
                      PETSC_COPY_VALUES, &is);
      PCFieldSplitSetIS(pc, name, is);
      ISDestroy(&is);
    }
    _configure_blocks = true;
  }
  else
    _pcd.reset(); // the options database chose another preconditioner
}
//-----------------------------------------------------------------------------
std::int64_t fsai::fluid::FluidSolver::dofs() const
{
  return _W->dofmap()->index_map->size_global();
}
//-----------------------------------------------------------------------------
void fsai::fluid::FluidSolver::split()
{
  auto up = _up->x()->array();
  auto v = _v->x()->mutable_array();
  auto p = _p->x()->mutable_array();
  for (std::size_t i = 0; i < _map_v.size(); ++i)
    v[i] = up[_map_v[i]];
  for (std::size_t i = 0; i < _map_p.size(); ++i)
    p[i] = up[_map_p[i]];
}
//-----------------------------------------------------------------------------
void fsai::fluid::FluidSolver::configure_blocks()
{
  // Block solvers of the Schur fieldsplit: one preconditioner application
  // each; set on this solver's sub-KSPs, then the options database
  // (fluid_fieldsplit_u_*, fluid_fieldsplit_p_*) overrides them
  KSP ksp = _solver.ksp();
  PC pc;
  KSPGetPC(ksp, &pc);
  KSPSetUp(ksp);
  KSP* sub = nullptr;
  PetscInt n = 0;
  PCFieldSplitGetSubKSP(pc, &n, &sub);
  for (PetscInt i = 0; i < n; ++i)
  {
    KSPSetType(sub[i], KSPPREONLY);
    PC sub_pc;
    KSPGetPC(sub[i], &sub_pc);
    // bjacobi's blocks default to ILU(0)
    if (i == 1 and _pcd)
      _pcd->attach(sub_pc);
    else
      PCSetType(sub_pc,
                (i == 0 and _par.velocity_pc == "ilu") ? PCBJACOBI : PCHYPRE);
    KSPSetFromOptions(sub[i]);
  }
  PetscFree(sub);
  _configure_blocks = false;
}
//-----------------------------------------------------------------------------
int fsai::fluid::FluidSolver::solve(bool repeat)
{
  {
    common::ScopedTimer t("fluid: assemble");
    if (_coo)
      _coo->assemble(_A.mat(), *_a);
    else
      common::assemble_matrix_per_cell(_A.mat(), *_a, _bcs);
  }
  la::Vector<double> b(_W->dofmap()->index_map, 1);
  {
    common::ScopedTimer t("fluid: assemble");
    b.set(0.0);
    fem::assemble_vector(b.mutable_array(), *_L);
    if (_coo)
    {
      // −A_{:,D} g, computed with the matrix
      auto bb = b.mutable_array();
      auto lift = _coo->lifting();
      for (std::size_t i = 0; i < lift.size(); ++i)
        bb[i] += lift[i];
    }
    else
      fem::apply_lifting<double>(
          b.mutable_array(),
          std::vector<std::shared_ptr<const fem::Form<double>>>{_a},
          std::vector<decltype(_bcs)>{_bcs},
          std::vector<std::span<const double>>{}, 1.0);
    b.scatter_rev(std::plus<double>());
    fem::set_bc<double>(b.mutable_array(), _bcs);
  }
  {
    common::ScopedTimer t("fluid: solve");
    // A kept preconditioner was built from an earlier operator (earlier
    // mesh, convecting velocity and time step coefficients)
    const bool reuse = _par.solver == "iterative" and !_configure_blocks
                       and _solves_since_setup > 0
                       and _solves_since_setup < _par.pc_lag;
    KSPSetReusePreconditioner(_solver.ksp(), reuse ? PETSC_TRUE : PETSC_FALSE);
    if (_pcd and !reuse)
      _pcd->assemble();
    _solver.set_operator(_A.mat());
    if (_configure_blocks)
      configure_blocks();
    la::petsc::Vector x(la::petsc::create_vector_wrap(*_up->x()), false);
    la::petsc::Vector bb(la::petsc::create_vector_wrap(b), false);
    KSPConvergedReason reason = KSP_CONVERGED_ITS;
    const bool refined = repeat and refine(x.vec(), bb.vec());
    if (repeat)
      ++(refined ? _refined : _refine_fallbacks);
    if (!refined)
    {
      std::vector<double> guess; // kept for a repeated solve
      if (reuse)
        guess.assign(_up->x()->array().begin(), _up->x()->array().end());
      _solver.solve(x.vec(), bb.vec());
      KSPGetConvergedReason(_solver.ksp(), &reason);
      _solves_since_setup = reuse ? _solves_since_setup + 1 : 1;
      if (reason < 0 and reuse)
      {
        // Repeat from the same initial guess with a fresh preconditioner
        std::copy(guess.begin(), guess.end(),
                  _up->x()->mutable_array().begin());
        KSPSetReusePreconditioner(_solver.ksp(), PETSC_FALSE);
        if (_pcd)
          _pcd->assemble();
        _solver.set_operator(_A.mat());
        _solver.solve(x.vec(), bb.vec());
        KSPGetConvergedReason(_solver.ksp(), &reason);
        _solves_since_setup = 1;
      }
      if (_par.solver == "iterative")
      {
        PetscInt its = 0;
        KSPGetIterationNumber(_solver.ksp(), &its);
        _krylov_its += its;
        ++_krylov_solves;
      }
    }
    if (reason < 0)
    {
      // E20: without θ_P the selfp Schur approximation is indefinite in a
      // closed porous region; E20b: AMG on selfp diverges in a strong jet
      std::string hint;
      if (_par.solver == "iterative" and _par.sigma_p > 0 and !_par.tau_porous)
        hint = "; the iterative solver needs --fluid.tau_porous where the "
               "porous region closes the channel (docs/model.md E20)";
      else if (_par.solver == "iterative" and _par.schur == "selfp")
        hint = "; AMG on the selfp Schur approximation diverges in strong "
               "jets: --fluid.schur pcd holds there (docs/model.md E20b)";
      throw std::runtime_error(fmt::format(
          "fluid: linear solve failed at t = {:.6g} s (KSPConvergedReason "
          "{}){}",
          _t, int(reason), hint));
    }
    _up->x()->scatter_fwd();
  }
  split();
  const double nv = la::norm(*_v->x());
  if (!std::isfinite(nv))
    throw std::runtime_error(
        fmt::format("fluid: velocity is not finite at t = {:.6g} s", _t));
  return 1;
}
//-----------------------------------------------------------------------------
bool fsai::fluid::FluidSolver::refine(Vec x, Vec b)
{
  // Iterative refinement x ← x + (LU)⁻¹(b − A x) with the step's kept
  // factorisation (of its first iterate's operator), from the last
  // iterate's solution; the test is on the true residual |b − A x|
  common::ScopedTimer t("fluid: refine");
  KSP ksp = _solver.ksp();
  KSPSetType(ksp, KSPRICHARDSON);
  KSPSetNormType(ksp, KSP_NORM_UNPRECONDITIONED);
  KSPSetInitialGuessNonzero(ksp, PETSC_TRUE);
  KSPSetTolerances(ksp, _par.refine_rtol, 0.0, 1e10, _par.refine_max_its);
  KSPSetReusePreconditioner(ksp, PETSC_TRUE);
  std::copy(_up_iterate.begin(), _up_iterate.end(),
            _up->x()->mutable_array().begin());
  KSPSolve(ksp, b, x);
  KSPConvergedReason reason;
  KSPGetConvergedReason(ksp, &reason);
  // Back to the direct solve for the next fresh factorisation
  KSPSetType(ksp, KSPPREONLY);
  KSPSetNormType(ksp, KSP_NORM_NONE);
  KSPSetInitialGuessNonzero(ksp, PETSC_FALSE);
  KSPSetReusePreconditioner(ksp, PETSC_FALSE);
  return reason > 0;
}
//-----------------------------------------------------------------------------
void fsai::fluid::FluidSolver::reset_history()
{
  auto v = _v->x()->array();
  std::copy(v.begin(), v.end(), _v_n->x()->mutable_array().begin());
  std::copy(v.begin(), v.end(), _v_nn->x()->mutable_array().begin());
  _steps = 0;
}
//-----------------------------------------------------------------------------
int fsai::fluid::FluidSolver::step()
{
  common::ScopedTimer timer("fluid: step");
  const double dt = _dt;
  // E19: BDF1 for the first step, then BDF2 (variable step: weights by
  // the ratio r = Δt/Δt_n)
  const auto w = common::bdf2_weights(dt, _dt_n, _steps == 0);
  _a0->value[0] = w.w0, _a1->value[0] = w.w1, _a2->value[0] = w.w2;
  _inv_dt->value[0] = inverse_tau_step(_par, dt);
  // Oseen: convecting velocity extrapolated to t_{n+1} (E20),
  // v_n + r (v_n − v_nn) (v_n at start)
  {
    const double r = _steps == 0 ? 0.0 : dt / _dt_n;
    common::extrapolate(_v_star->x()->mutable_array(), _v_n->x()->array(),
                        _v_nn->x()->array(), r);
  }
  _t += dt;
  // A step repeated from its saved state (the coupling's next iterate)
  // refines its first solve's factorisation
  const bool refining = _par.solver == "direct" and _par.refine_rtol > 0;
  const bool repeat = refining and _restored and _saved_step_solved;
  _restored = false;
  int solves = 0;
  for (int k = 0; k < _par.picard; ++k)
  {
    std::vector<double> prev(_v->x()->array().begin(), _v->x()->array().end());
    solves += solve(repeat and k == 0);
    if (k == 0 and refining)
    {
      _saved_step_solved = true;
      _up_iterate.assign(_up->x()->array().begin(), _up->x()->array().end());
    }
    if (_par.picard == 1)
      break;
    // Picard: convect with the new iterate
    auto v = _v->x()->array();
    double d2 = 0, v2 = 0;
    for (std::size_t i = 0; i < owned_entries(*_v); ++i)
      d2 += (v[i] - prev[i]) * (v[i] - prev[i]), v2 += v[i] * v[i];
    std::array<double, 2> loc{d2, v2}, glob;
    MPI_Allreduce(loc.data(), glob.data(), 2, MPI_DOUBLE, MPI_SUM,
                  _W->mesh()->comm());
    std::copy(v.begin(), v.end(), _v_star->x()->mutable_array().begin());
    if (std::sqrt(glob[0]) <= _par.picard_tol * std::sqrt(glob[1]))
      break;
  }
  // Shift the history
  std::copy(_v_n->x()->array().begin(), _v_n->x()->array().end(),
            _v_nn->x()->mutable_array().begin());
  std::copy(_v->x()->array().begin(), _v->x()->array().end(),
            _v_n->x()->mutable_array().begin());
  ++_steps;
  _dt_n = dt;
  return solves;
}
//-----------------------------------------------------------------------------
void fsai::fluid::FluidSolver::set_dt(double dt)
{
  fsai::require_positive("fluid: time step", dt);
  _dt = dt;
}
//-----------------------------------------------------------------------------
int fsai::fluid::FluidSolver::solve_steady(int max_iterations)
{
  common::ScopedTimer timer("fluid: steady");
  _a0->value[0] = _a1->value[0] = _a2->value[0] = 0.0;
  _inv_dt->value[0] = 0.0;
  for (int k = 1; k <= max_iterations; ++k)
  {
    std::copy(_v->x()->array().begin(), _v->x()->array().end(),
              _v_star->x()->mutable_array().begin());
    solve();
    auto v = _v->x()->array(), vs = _v_star->x()->array();
    double d2 = 0, v2 = 0;
    for (std::size_t i = 0; i < owned_entries(*_v); ++i)
      d2 += (v[i] - vs[i]) * (v[i] - vs[i]), v2 += v[i] * v[i];
    std::array<double, 2> loc{d2, v2}, glob;
    MPI_Allreduce(loc.data(), glob.data(), 2, MPI_DOUBLE, MPI_SUM,
                  _W->mesh()->comm());
    if (std::sqrt(glob[0]) <= _par.picard_tol * std::sqrt(glob[1]))
    {
      std::copy(v.begin(), v.end(), _v_n->x()->mutable_array().begin());
      std::copy(v.begin(), v.end(), _v_nn->x()->mutable_array().begin());
      return k;
    }
  }
  throw std::runtime_error(fmt::format(
      "fluid: steady Picard iteration did not converge in {} iterations",
      max_iterations));
}
//-----------------------------------------------------------------------------
const fsai::fluid::FluidSolver::Boundary&
fsai::fluid::FluidSolver::boundary(std::span<const std::int32_t> facets)
{
  // Cached: the same boundary is asked for every step (and every coupling
  // iteration). Locating dofs is collective, and a rank with no facets on
  // two boundaries sees one (empty) key for both, so whether to locate is
  // decided by all ranks together
  std::vector<std::int32_t> key(facets.begin(), facets.end());
  auto it = _boundaries.find(key);
  int miss = it == _boundaries.end();
  auto mesh = _W->mesh();
  MPI_Allreduce(MPI_IN_PLACE, &miss, 1, MPI_INT, MPI_MAX, mesh->comm());
  if (!miss)
    return it->second;

  const int tdim = mesh->topology().dim();
  auto map = _V->dofmap()->index_map;
  const std::int32_t owned = map->size_local();
  Boundary bnd;
  const auto located = fem::locate_dofs_topological(*_V, tdim - 1, facets);
  for (std::int32_t d : located)
    if (d < owned)
      bnd.blocks.push_back(d);

  // The residual at these dofs gathers only the cells that hold one of
  // them: assembling it over those cells alone gives the same entries as
  // over the whole mesh, at a small fraction of the cost (the wall force
  // was 6 % of a glottis step). A dof on a facet of one rank may sit in an
  // owned cell of another (a cell touching the wall at a vertex), so the
  // marks are summed to the owner and sent back to every ghost first.
  la::Vector<double> mark(map, 1);
  mark.set(0.0);
  for (std::int32_t d : located)
    mark.mutable_array()[d] = 1.0;
  mark.scatter_rev(std::plus<double>());
  mark.scatter_fwd();
  const std::int32_t cells = mesh->topology().index_map(tdim)->size_local();
  std::vector<std::int32_t> near;
  for (std::int32_t c = 0; c < cells; ++c)
    for (std::int32_t d : _V->dofmap()->cell_dofs(c))
      if (mark.array()[d] > 0)
      {
        near.push_back(c);
        break;
      }
  bnd.cells = std::make_shared<mesh::MeshTags<std::int32_t>>(
      mesh, tdim, near, std::vector<std::int32_t>(near.size(), 1));

  using kernel_t
      = std::function<void(double*, const double*, const double*, const double*,
                           const int*, const std::uint8_t*)>;
  using integrals_t = std::vector<std::pair<int, kernel_t>>;
  const auto cell_ids = _F->integral_ids(fem::IntegralType::cell);
  if (cell_ids.size() != 1)
    throw std::runtime_error("fluid: the residual form must have exactly one "
                             "cell integral");
  std::map<fem::IntegralType,
           std::pair<integrals_t, const mesh::MeshTags<std::int32_t>*>>
      integrals;
  integrals[fem::IntegralType::cell]
      = {integrals_t{{1, _F->kernel(fem::IntegralType::cell, cell_ids[0])}},
         bnd.cells.get()};
  integrals_t facet_integrals;
  for (int id : _F->integral_ids(fem::IntegralType::exterior_facet))
    facet_integrals.push_back(
        {id, _F->kernel(fem::IntegralType::exterior_facet, id)});
  integrals[fem::IntegralType::exterior_facet]
      = {facet_integrals, _tags[0].get()};
  bnd.residual = std::make_shared<fem::Form<double>>(
      _F->function_spaces(), integrals, _F->coefficients(), _F->constants(),
      _F->needs_facet_permutations(), mesh);
  return _boundaries.insert_or_assign(key, std::move(bnd)).first->second;
}
//-----------------------------------------------------------------------------
std::vector<double>
fsai::fluid::FluidSolver::boundary_residual(const Boundary& bnd)
{
  // Weak-form residual of the current solution at the boundary's owned
  // velocity dofs (owned entries summed over ranks)
  la::Vector<double> r(_W->dofmap()->index_map, 1);
  r.set(0.0);
  fem::assemble_vector(r.mutable_array(), *bnd.residual);
  r.scatter_rev(std::plus<double>());
  const int bs = _V->dofmap()->index_map_bs();
  std::vector<double> out;
  out.reserve(bnd.blocks.size() * bs);
  for (std::int32_t d : bnd.blocks)
    for (int k = 0; k < bs; ++k)
      out.push_back(r.array()[_map_v[bs * d + k]]);
  return out;
}
//-----------------------------------------------------------------------------
std::array<double, 3>
fsai::fluid::FluidSolver::force(std::span<const std::int32_t> facets)
{
  common::ScopedTimer timer("fluid: force");
  const Boundary& bnd = boundary(facets);
  const auto r = boundary_residual(bnd);
  const int bs = _V->dofmap()->index_map_bs();
  std::array<double, 3> local{0, 0, 0}, global{0, 0, 0};
  for (std::size_t i = 0; i < bnd.blocks.size(); ++i)
    for (int k = 0; k < bs; ++k)
      local[k] += r[bs * i + k];
  MPI_Allreduce(local.data(), global.data(), 3, MPI_DOUBLE, MPI_SUM,
                _W->mesh()->comm());
  // The residual at a wall dof is the traction the wall exerts on the
  // fluid there (the reaction that keeps v = g); the fluid pushes the wall
  // with the opposite force
  return {-global[0], -global[1], -global[2]};
}
//-----------------------------------------------------------------------------
void fsai::fluid::FluidSolver::nodal_forces(
    std::span<const std::int32_t> facets, fem::Function<double>& F)
{
  common::ScopedTimer timer("fluid: force");
  const Boundary& bnd = boundary(facets);
  const auto r = boundary_residual(bnd);
  const int bs = _V->dofmap()->index_map_bs();
  auto f = F.x()->mutable_array();
  std::fill(f.begin(), f.end(), 0.0);
  for (std::size_t i = 0; i < bnd.blocks.size(); ++i)
    for (int k = 0; k < bs; ++k)
      f[bs * bnd.blocks[i] + k] = -r[bs * i + k];
  F.x()->scatter_fwd();
}
//-----------------------------------------------------------------------------
void fsai::fluid::FluidSolver::save_state()
{
  auto copy = [](auto& f) {
    return std::vector<double>(f->x()->array().begin(), f->x()->array().end());
  };
  _saved = {copy(_up),   copy(_v), copy(_p), copy(_v_n),
            copy(_v_nn), _t,       _dt_n,    _steps};
  _saved_step_solved = false;
  _restored = false;
}
//-----------------------------------------------------------------------------
void fsai::fluid::FluidSolver::restore_state()
{
  if (_saved.up.empty())
    throw std::runtime_error("fluid: restore_state() without save_state()");
  auto back = [](const std::vector<double>& a, auto& f)
  { std::copy(a.begin(), a.end(), f->x()->mutable_array().begin()); };
  back(_saved.up, _up);
  back(_saved.v, _v);
  back(_saved.p, _p);
  back(_saved.v_n, _v_n);
  back(_saved.v_nn, _v_nn);
  _t = _saved.t;
  _dt_n = _saved.dt_n;
  _steps = _saved.steps;
  _restored = true;
}
//-----------------------------------------------------------------------------
void fsai::fluid::FluidSolver::save(io::RankState& state,
                                    const std::string& prefix) const
{
  // The next solve builds a fresh preconditioner, as a run restarted from
  // this checkpoint does: both continue identically
  _solves_since_setup = 0;
  // Velocity, its BDF history and the pressure, by mesh node; the mixed
  // vector up is rebuilt from v and p on load
  const auto kv = io::node_keys(*_V), kp = io::node_keys(*_Q);
  const int bs = _V->dofmap()->index_map_bs();
  const std::int32_t nv = _V->dofmap()->index_map->size_local(),
                     np = _Q->dofmap()->index_map->size_local();
  for (const auto& [name, f] :
       {std::pair{"v", _v}, {"v_n", _v_n}, {"v_nn", _v_nn}})
    io::put_blocks(state, prefix + name, f->x()->array(), bs, kv, nv);
  io::put_blocks(state, prefix + "p", _p->x()->array(), 1, kp, np);
  state[prefix + "t_steps"] = {_t, double(_steps), _dt_n};
}
//-----------------------------------------------------------------------------
void fsai::fluid::FluidSolver::load(const std::vector<io::RankState>& ranks,
                                    const std::string& prefix)
{
  const auto kv = io::node_keys(*_V), kp = io::node_keys(*_Q);
  const int bs = _V->dofmap()->index_map_bs();
  for (const auto& [name, f] :
       {std::pair{"v", _v}, {"v_n", _v_n}, {"v_nn", _v_nn}})
    io::get_blocks(ranks, prefix + name, f->x()->mutable_array(), bs, kv);
  io::get_blocks(ranks, prefix + "p", _p->x()->mutable_array(), 1, kp);
  merge();
  const auto& ts = io::state_entry(ranks.at(0), prefix + "t_steps");
  if (ts.size() < 2)
    throw fsai::InputError("restart: the checkpoint's " + prefix
                           + "t_steps is short");
  _t = ts[0];
  _steps = int(ts[1]);
  // Checkpoints of uniform-step runs before the variable step have no Δt_n
  _dt_n = ts.size() > 2 ? ts[2] : _dt;
}
//-----------------------------------------------------------------------------
void fsai::fluid::FluidSolver::merge()
{
  auto up = _up->x()->mutable_array();
  auto v = _v->x()->array(), p = _p->x()->array();
  for (std::size_t i = 0; i < _map_v.size(); ++i)
    up[_map_v[i]] = v[i];
  for (std::size_t i = 0; i < _map_p.size(); ++i)
    up[_map_p[i]] = p[i];
}
//-----------------------------------------------------------------------------
void fsai::fluid::FluidSolver::set_state(std::span<const double> v_n,
                                         std::span<const double> v_nn,
                                         std::span<const double> p, double t,
                                         int steps, double dt_n)
{
  auto put = [](std::span<const double> a, auto& f)
  {
    auto x = f->x()->mutable_array();
    if (a.size() != x.size())
      throw std::invalid_argument("fluid: set_state with a wrong array size");
    std::copy(a.begin(), a.end(), x.begin());
  };
  put(v_n, _v);
  put(v_n, _v_n);
  put(v_nn, _v_nn);
  put(p, _p);
  merge();
  _t = t;
  _steps = steps;
  _dt_n = dt_n;
  save_state();
}
//-----------------------------------------------------------------------------
double fsai::fluid::FluidSolver::flow_rate(std::span<const std::int32_t> facets)
{
  const int tdim = _W->mesh()->topology().dim();
  auto mesh = _W->mesh();
  const std::int32_t nf = mesh->topology().index_map(tdim - 1)->size_local();
  std::vector<std::int32_t> f;
  for (std::int32_t x : facets)
    if (x < nf)
      f.push_back(x);
  std::sort(f.begin(), f.end());
  std::vector<std::int32_t> ones(f.size(), 1);
  mesh::MeshTags<std::int32_t> tags(mesh, tdim - 1, std::move(f),
                                    std::move(ones));
  auto Q = fem::create_form<double>(
      fluid_forms::flux(tdim, 1), {},
      std::map<std::string, std::shared_ptr<const fem::Function<double>>>{
          {"up", _up}},
      std::map<std::string, std::shared_ptr<const fem::Constant<double>>>{},
      {{fem::IntegralType::exterior_facet, &tags}}, mesh);
  double local = fem::assemble_scalar(Q), global = 0;
  MPI_Allreduce(&local, &global, 1, MPI_DOUBLE, MPI_SUM, mesh->comm());
  return global;
}
//-----------------------------------------------------------------------------
std::array<double, 2> fsai::fluid::FluidSolver::cfl_and_cell_reynolds() const
{
  auto mesh = _W->mesh();
  const int tdim = mesh->topology().dim();
  const std::int32_t nc = mesh->topology().index_map(tdim)->size_local();
  std::vector<std::int32_t> cells(nc);
  std::iota(cells.begin(), cells.end(), 0);
  std::vector<double> h = mesh::h(*mesh, cells, tdim);
  auto dofmap = _V->dofmap();
  auto v = _v->x()->array(), w = _w->x()->array();
  const int bs = dofmap->bs();
  std::array<double, 2> local{0, 0}, global;
  for (std::int32_t c = 0; c < nc; ++c)
  {
    double vmax = 0, rmax = 0;
    for (std::int32_t d : dofmap->cell_dofs(c))
    {
      double s2 = 0, r2 = 0;
      for (int k = 0; k < bs; ++k)
      {
        s2 += v[d * bs + k] * v[d * bs + k];
        r2 += (v[d * bs + k] - w[d * bs + k]) * (v[d * bs + k] - w[d * bs + k]);
      }
      vmax = std::max(vmax, std::sqrt(s2));
      rmax = std::max(rmax, std::sqrt(r2));
    }
    local[0] = std::max(local[0], rmax * _dt / h[c]);
    local[1] = std::max(local[1], vmax * h[c] * _par.rho / _par.mu);
  }
  MPI_Allreduce(local.data(), global.data(), 2, MPI_DOUBLE, MPI_MAX,
                mesh->comm());
  return global;
}
//-----------------------------------------------------------------------------
double fsai::fluid::FluidSolver::pressure_gradient_norm()
{
  auto mesh = _W->mesh();
  auto G = fem::create_form<double>(
      fluid_forms::grad_p_sq(mesh->topology().dim(), 1), {},
      std::map<std::string, std::shared_ptr<const fem::Function<double>>>{
          {"up", _up}},
      std::map<std::string, std::shared_ptr<const fem::Constant<double>>>{}, {},
      mesh);
  double local = fem::assemble_scalar(G), global = 0;
  MPI_Allreduce(&local, &global, 1, MPI_DOUBLE, MPI_SUM, mesh->comm());
  return std::sqrt(global);
}
//-----------------------------------------------------------------------------
double fsai::fluid::FluidSolver::max_speed() const
{
  auto v = _v->x()->array();
  const int bs = _V->dofmap()->bs();
  double local = 0, global = 0;
  for (std::size_t i = 0; i + bs <= v.size(); i += bs)
  {
    double s2 = 0;
    for (int k = 0; k < bs; ++k)
      s2 += v[i + k] * v[i + k];
    local = std::max(local, std::sqrt(s2));
  }
  MPI_Allreduce(&local, &global, 1, MPI_DOUBLE, MPI_MAX, _W->mesh()->comm());
  return global;
}
//-----------------------------------------------------------------------------
