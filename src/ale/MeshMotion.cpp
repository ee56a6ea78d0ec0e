// Copyright (C) 2026 fsai developers
#include "MeshMotion.h"
#include "../common/Parameters.h"
#include "../common/bdf.h"
#include "../common/errors.h"
#include "../common/petsc_solver.h"
#include "../common/timer.h"
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <dolfinx/fem/assembler.h>
#include <dolfinx/fem/petsc.h>
#include <dolfinx/fem/utils.h>
#include <fmt/format.h>
#include <fsai_forms/ale.h>
#include <io/field_state.h>
#include <mpi.h>

using namespace dolfinx;
namespace ale_forms = fsai::forms::ale;

//-----------------------------------------------------------------------------
void fsai::ale::MeshMotionParameters::bind(fsai::common::Parameters& p)
{
  p.add_choice("ale.method", method, {"harmonic", "elastic"},
               "mesh motion: harmonic or pseudo-elastic extension");
  p.add_choice("ale.stiffening", stiffening, {"none", "size", "jacobian"},
               "cell stiffening: none, reference size (V_max/V)^chi, or "
               "size and squeeze J^-chi");
  p.add("ale.chi", chi, "stiffening exponent chi");
  p.add("ale.iterations", iterations,
        "fixed-point iterations per move (jacobian stiffening)");
  p.add("ale.lambda", lambda, "lambda/mu of the pseudo-elastic medium");
  p.add("ale.min_quality", min_quality,
        "smallest accepted scaled Jacobian (error below it)");
}
//-----------------------------------------------------------------------------
void fsai::ale::MeshMotionParameters::validate() const
{
  fsai::require(method == "harmonic" or method == "elastic", "--ale.method",
                "harmonic or elastic", method);
  fsai::require(stiffening == "none" or stiffening == "size"
                    or stiffening == "jacobian",
                "--ale.stiffening", "none, size or jacobian", stiffening);
  fsai::require_range("--ale.chi", chi, 0.0, 5.0);
  fsai::require(iterations >= 1 and iterations <= 100, "--ale.iterations",
                "in [1, 100]", iterations);
  fsai::require(lambda > -2.0 / 3.0, "--ale.lambda", "> -2/3 (coercive)",
                lambda);
  fsai::require(min_quality >= 0 and min_quality < 1, "--ale.min_quality",
                "in [0, 1)", min_quality);
}
//-----------------------------------------------------------------------------
namespace
{
/// Signed Jacobian det(x_1 − x_0, …, x_d − x_0) and the scaled Jacobian
/// (min over corners of |det| / product of the corner's edge lengths,
/// equilateral = 1) of the simplex with vertices `v` (3 coordinates each)
std::pair<double, double> simplex_jacobian(const std::array<double, 12>& v,
                                           int d)
{
  auto edge = [&](int i, int j, int k) { return v[3 * j + k] - v[3 * i + k]; };
  double det;
  if (d == 2)
    det = edge(0, 1, 0) * edge(0, 2, 1) - edge(0, 1, 1) * edge(0, 2, 0);
  else
  {
    const double a[3] = {edge(0, 1, 0), edge(0, 1, 1), edge(0, 1, 2)};
    const double b[3] = {edge(0, 2, 0), edge(0, 2, 1), edge(0, 2, 2)};
    const double c[3] = {edge(0, 3, 0), edge(0, 3, 1), edge(0, 3, 2)};
    det = a[0] * (b[1] * c[2] - b[2] * c[1])
          - a[1] * (b[0] * c[2] - b[2] * c[0])
          + a[2] * (b[0] * c[1] - b[1] * c[0]);
  }
  const double norm = d == 2 ? 2.0 / std::sqrt(3.0) : std::sqrt(2.0);
  double q = 1e300;
  for (int i = 0; i <= d; ++i)
  {
    double prod = 1;
    for (int j = 0; j <= d; ++j)
    {
      if (j != i)
        prod *= std::hypot(edge(i, j, 0), edge(i, j, 1), edge(i, j, 2));
    }
    q = std::min(q, std::abs(det) / prod * norm);
  }
  return {det, q};
}

/// Vertex coordinates of cell c from a geometry array
std::array<double, 12> cell_vertices(const mesh::Mesh& mesh,
                                     std::span<const double> x, int c)
{
  auto nodes = mesh.geometry().dofmap().links(c);
  std::array<double, 12> v{};
  const int nv = mesh.topology().dim() + 1;
  for (int i = 0; i < nv; ++i)
    for (int k = 0; k < 3; ++k)
      v[3 * i + k] = x[3 * nodes[i] + k];
  return v;
}
} // namespace
//-----------------------------------------------------------------------------
namespace
{
/// mesh_quality with the reference cell Jacobians given by det0(c)
template <typename F>
fsai::ale::MeshQuality quality(const mesh::Mesh& mesh, F det0_of)
{
  const int tdim = mesh.topology().dim();
  const std::int32_t nc = mesh.topology().index_map(tdim)->size_local();
  auto x = mesh.geometry().x();
  struct
  {
    double q;
    int rank;
  } loc{1e300, 0}, glob;
  MPI_Comm_rank(mesh.comm(), &loc.rank);
  std::array<double, 3> where{};
  for (std::int32_t c = 0; c < nc; ++c)
  {
    auto v = cell_vertices(mesh, x, c);
    auto [det, q] = simplex_jacobian(v, tdim);
    if (det * det0_of(c) <= 0)
    {
      q = -q; // inverted relative to the reference orientation
      if (std::getenv("FSAI_DEBUG_INVERTED"))
      {
        for (int i = 0; i <= tdim; ++i)
          std::fprintf(stderr, "inverted cell %d: x (%.6e, %.6e)\n", c,
                       v[3 * i], v[3 * i + 1]);
      }
    }
    if (q < loc.q)
    {
      loc.q = q;
      where = {0, 0, 0};
      for (int i = 0; i <= tdim; ++i)
        for (int k = 0; k < 3; ++k)
          where[k] += v[3 * i + k] / (tdim + 1);
    }
  }
  MPI_Allreduce(&loc, &glob, 1, MPI_DOUBLE_INT, MPI_MINLOC, mesh.comm());
  MPI_Bcast(where.data(), 3, MPI_DOUBLE, glob.rank, mesh.comm());
  return {glob.q, where};
}
} // namespace
//-----------------------------------------------------------------------------
fsai::ale::MeshQuality
fsai::ale::mesh_quality(const mesh::Mesh& mesh,
                        std::span<const double> reference_x)
{
  const int tdim = mesh.topology().dim();
  return quality(mesh,
                 [&](int c) {
                   return simplex_jacobian(cell_vertices(mesh, reference_x, c),
                                           tdim)
                       .first;
                 });
}
//-----------------------------------------------------------------------------
fsai::ale::MeshMotion::MeshMotion(std::shared_ptr<mesh::Mesh> mesh,
                                  std::shared_ptr<const fem::FunctionSpace> V,
                                  const MeshMotionBoundaries& bnd,
                                  const MeshMotionParameters& p)
    : _mesh(mesh), _V(V), _par(p), _A(nullptr, false), _solver(mesh->comm())
{
  common::ScopedTimer timer("ale: setup");
  p.validate();
  const int tdim = mesh->topology().dim();
  auto x = mesh->geometry().x();
  _X.assign(x.begin(), x.end());

  // Geometry node -> P1 dof: the same vertex order in each (affine) cell
  const std::int32_t ncells = mesh->topology().index_map(tdim)->size_local()
                              + mesh->topology().index_map(tdim)->num_ghosts();
  _node_dof.assign(_X.size() / 3, -1);
  for (std::int32_t c = 0; c < ncells; ++c)
  {
    auto nodes = mesh->geometry().dofmap().links(c);
    auto dofs = V->dofmap()->cell_dofs(c);
    if (nodes.size() != dofs.size())
      throw std::runtime_error("ALE: mesh geometry must be affine (P1)");
    for (std::size_t i = 0; i < nodes.size(); ++i)
      _node_dof[nodes[i]] = dofs[i];
  }

  auto fn = [](auto space, const std::string& name)
  {
    auto f = std::make_shared<fem::Function<double>>(space);
    f->name = name;
    f->x()->set(0.0);
    return f;
  };
  _d = fn(V, "mesh_displacement");
  _d_interface = fn(V, "interface_displacement");
  _d_n.assign(_d->x()->array().size(), 0.0);
  _d_nn = _d_n;
  _history = 1; // the reference configuration, at rest

  // Size factor (V_max / V_K)^χ from the reference cell volumes
  auto Q = std::make_shared<fem::FunctionSpace>(fem::create_functionspace(
      ale_forms::functionspace_a(tdim, 1), "k", mesh));
  _k = fn(Q, "ale_stiffening");
  _det0.resize(ncells);
  double vmax = 0;
  for (std::int32_t c = 0; c < ncells; ++c)
  {
    _det0[c] = simplex_jacobian(cell_vertices(*mesh, _X, c), tdim).first;
    vmax = std::max(vmax, std::abs(_det0[c]));
  }
  MPI_Allreduce(MPI_IN_PLACE, &vmax, 1, MPI_DOUBLE, MPI_MAX, mesh->comm());
  _k_size.resize(ncells);
  _J.assign(ncells, 1.0);
  for (std::int32_t c = 0; c < ncells; ++c)
  {
    _k_size[c] = p.stiffening == "size"
                     ? std::pow(vmax / std::abs(_det0[c]), p.chi)
                     : 1.0;
  }

  // Boundary conditions (collective: every rank locates every list).
  // The interface comes last so that its values win at shared nodes.
  const int fdim = tdim - 1;
  mesh->topology_mutable().create_connectivity(fdim, tdim);
  auto zero = fn(V, "zero");
  _bcs.push_back(std::make_shared<fem::DirichletBC<double>>(
      zero, fem::locate_dofs_topological(*V, fdim, bnd.fixed)));
  for (auto& [component, facets] : bnd.slip)
  {
    fsai::require(component >= 0 and component < mesh->geometry().dim(),
                  "ALE slip component", "a coordinate index", component);
    auto Vc = V->sub({component});
    _bcs.push_back(std::make_shared<fem::DirichletBC<double>>(
        std::make_shared<fem::Constant<double>>(0.0),
        fem::locate_dofs_topological(*Vc, fdim, facets), Vc));
  }
  _bcs.push_back(std::make_shared<fem::DirichletBC<double>>(
      _d_interface, fem::locate_dofs_topological(*V, fdim, bnd.interface)));
  if (!bnd.prescribed.empty())
  {
    std::vector<std::int32_t> dofs = bnd.prescribed;
    std::sort(dofs.begin(), dofs.end());
    dofs.erase(std::unique(dofs.begin(), dofs.end()), dofs.end());
    _bcs.push_back(std::make_shared<fem::DirichletBC<double>>(_d_interface,
                                                              std::move(dofs)));
  }

  // The operator lives on the reference mesh: assembled and factorised once
  _a = std::make_shared<fem::Form<double>>(fem::create_form<double>(
      ale_forms::a(tdim, 1), {V, V}, {{"k", _k}},
      {{"elastic", std::make_shared<fem::Constant<double>>(
                       p.method == "elastic" ? 1.0 : 0.0)},
       {"lmbda", std::make_shared<fem::Constant<double>>(p.lambda)}},
      {}));
  _A = la::petsc::Matrix(fem::petsc::create_matrix(*_a), false);
  assemble();
  common::configure_direct_solver(_solver.ksp(), mesh->comm(), tdim);
  _solver.set_options_prefix("ale_");
  _solver.set_from_options();
  _solver.set_operator(_A.mat());
}
//-----------------------------------------------------------------------------
void fsai::ale::MeshMotion::assemble()
{
  // k on every local cell (owned and ghost): the size factor, times
  // J^(−χ) of the current d for "jacobian" (J from the cell's vertex
  // displacements; squeezed or inverted iterates are capped at J = 1e-3)
  const int tdim = _mesh->topology().dim();
  auto Q = _k->function_space();
  auto k = _k->x()->mutable_array();
  auto d = _d->x()->array();
  const int bs = _V->dofmap()->index_map_bs();
  for (std::size_t c = 0; c < _k_size.size(); ++c)
  {
    double J = 1;
    if (_par.stiffening == "jacobian")
    {
      auto v = cell_vertices(*_mesh, _X, c);
      auto nodes = _mesh->geometry().dofmap().links(c);
      for (int i = 0; i <= tdim; ++i)
        for (int j = 0; j < tdim; ++j)
          v[3 * i + j] += d[bs * _node_dof[nodes[i]] + j];
      const double Jd
          = std::max(simplex_jacobian(v, tdim).first / _det0[c], 1e-3);
      // Under-relaxed (geometric mean with the last J): the plain fixed
      // point oscillates between squeezing one cell layer and the next
      _J[c] = std::sqrt(_J[c] * Jd);
      J = _J[c];
    }
    k[Q->dofmap()->cell_dofs(c)[0]] = _k_size[c] * std::pow(J, -_par.chi);
  }
  MatZeroEntries(_A.mat());
  fem::assemble_matrix(la::petsc::Matrix::set_block_fn(_A.mat(), ADD_VALUES),
                       *_a, _bcs);
  MatAssemblyBegin(_A.mat(), MAT_FLUSH_ASSEMBLY);
  MatAssemblyEnd(_A.mat(), MAT_FLUSH_ASSEMBLY);
  fem::set_diagonal<double>(la::petsc::Matrix::set_fn(_A.mat(), INSERT_VALUES),
                            *_V, _bcs);
  MatAssemblyBegin(_A.mat(), MAT_FINAL_ASSEMBLY);
  MatAssemblyEnd(_A.mat(), MAT_FINAL_ASSEMBLY);
}
//-----------------------------------------------------------------------------
void fsai::ale::MeshMotion::extend(fem::Function<double>& d)
{
  _d_interface->x()->scatter_fwd();
  // The operator is that of the reference mesh: its lifting must be too
  auto x = _mesh->geometry().x();
  std::copy(_X.begin(), _X.end(), x.begin());
  const int passes = _par.stiffening == "jacobian" ? _par.iterations : 1;
  for (int it = 0; it < passes; ++it)
  {
    // Jacobian stiffening: k from the last d (the previous move's at first)
    if (_par.stiffening == "jacobian")
    {
      assemble();
      _solver.set_operator(_A.mat());
    }
    la::Vector<double> b(_V->dofmap()->index_map, _V->dofmap()->index_map_bs());
    b.set(0.0);
    fem::apply_lifting<double>(
        b.mutable_array(),
        std::vector<std::shared_ptr<const fem::Form<double>>>{_a},
        std::vector<decltype(_bcs)>{_bcs},
        std::vector<std::span<const double>>{}, 1.0);
    b.scatter_rev(std::plus<double>());
    fem::set_bc<double>(b.mutable_array(), _bcs);
    la::petsc::Vector xx(la::petsc::create_vector_wrap(*d.x()), false);
    la::petsc::Vector bb(la::petsc::create_vector_wrap(b), false);
    _solver.solve(xx.vec(), bb.vec());
    d.x()->scatter_fwd();
  }
}
//-----------------------------------------------------------------------------
fsai::ale::MeshQuality fsai::ale::MeshMotion::move(double t)
{
  common::ScopedTimer timer("ale: move");
  extend(*_d);
  return place_and_check(t);
}
//-----------------------------------------------------------------------------
std::vector<double> fsai::ale::MeshMotion::extension()
{
  if (!linear())
    throw std::runtime_error("ALE: the Jacobian-stiffened extension is not "
                             "linear; it has no fixed extension operator");
  common::ScopedTimer timer("ale: extension");
  fem::Function<double> d(_V);
  d.x()->set(0.0);
  extend(d);
  place_mesh(); // back to X + (the current) d
  return std::vector<double>(d.x()->array().begin(), d.x()->array().end());
}
//-----------------------------------------------------------------------------
fsai::ale::MeshQuality fsai::ale::MeshMotion::move_to(std::span<const double> d,
                                                      double t)
{
  common::ScopedTimer timer("ale: move");
  auto out = _d->x()->mutable_array();
  if (d.size() != out.size())
    throw std::runtime_error("ALE: move_to() needs a displacement with the "
                             "local size of the mesh displacement");
  std::copy(d.begin(), d.end(), out.begin());
  return place_and_check(t);
}
//-----------------------------------------------------------------------------
fsai::ale::MeshQuality fsai::ale::MeshMotion::place_and_check(double t)
{
  place_mesh(); // x = X + d at every geometry node (owned and ghost)

  // The reference Jacobians, computed once (_det0)
  MeshQuality q = quality(*_mesh, [&](int c) { return _det0[c]; });
  if (!std::isfinite(q.min_scaled_jacobian)
      or q.min_scaled_jacobian <= _par.min_quality)
  {
    throw MeshInvertedError(fmt::format(
        "ALE mesh motion ({}{}): {} at t = {:.6g} s near ({:.4g}, {:.4g}, "
        "{:.4g}) m, min scaled Jacobian {:.3g} (limit {:g})",
        _par.method,
        _par.stiffening == "none" ? ""
                                  : fmt::format(", {} stiffening, chi {:g}",
                                                _par.stiffening, _par.chi),
        q.min_scaled_jacobian <= 0 ? "cell inverted" : "cell quality too low",
        t, q.where[0], q.where[1], q.where[2], q.min_scaled_jacobian,
        _par.min_quality));
  }
  return q;
}
//-----------------------------------------------------------------------------
void fsai::ale::MeshMotion::velocity(fem::Function<double>& w, double dt,
                                     double dt_n) const
{
  auto d = _d->x()->array();
  auto out = w.x()->mutable_array();
  if (out.size() != d.size())
    throw std::runtime_error("ALE: mesh velocity must be in the P1 space");
  const auto c = common::bdf2_weights(dt, dt_n, _history < 2);
  for (std::size_t i = 0; i < d.size(); ++i)
    out[i] = c.w0 * d[i] + c.w1 * _d_n[i] + c.w2 * _d_nn[i];
}
//-----------------------------------------------------------------------------
void fsai::ale::MeshMotion::advance()
{
  _d_nn = _d_n;
  auto d = _d->x()->array();
  _d_n.assign(d.begin(), d.end());
  _history = std::min(_history + 1, 2);
}
//-----------------------------------------------------------------------------
void fsai::ale::MeshMotion::save(io::RankState& state,
                                 const std::string& prefix) const
{
  const auto kn = io::node_keys(*_V), kc = io::cell_keys(*_mesh);
  const int bs = _V->dofmap()->index_map_bs();
  const std::int32_t nb
      = _V->dofmap()->index_map->size_local(),
      nc = _mesh->topology().index_map(_mesh->topology().dim())->size_local();
  io::put_blocks(state, prefix + "d", _d->x()->array(), bs, kn, nb);
  io::put_blocks(state, prefix + "d_n", _d_n, bs, kn, nb);
  io::put_blocks(state, prefix + "d_nn", _d_nn, bs, kn, nb);
  io::put_blocks(state, prefix + "J", _J, 1, kc, nc);
  state[prefix + "history"] = {double(_history)};
}
//-----------------------------------------------------------------------------
void fsai::ale::MeshMotion::load(const std::vector<io::RankState>& ranks,
                                 const std::string& prefix)
{
  const auto kn = io::node_keys(*_V), kc = io::cell_keys(*_mesh);
  const int bs = _V->dofmap()->index_map_bs();
  io::get_blocks(ranks, prefix + "d", _d->x()->mutable_array(), bs, kn);
  io::get_blocks(ranks, prefix + "d_n", _d_n, bs, kn);
  io::get_blocks(ranks, prefix + "d_nn", _d_nn, bs, kn);
  io::get_blocks(ranks, prefix + "J", _J, 1, kc);
  _history = int(io::state_entry(ranks.at(0), prefix + "history", 1)[0]);
  place_mesh(); // as after the last accepted move
}
//-----------------------------------------------------------------------------
void fsai::ale::MeshMotion::continue_from(std::span<const double> d_nn)
{
  if (d_nn.size() != _d_nn.size())
    throw std::invalid_argument("ALE: continue_from with a wrong array size");
  std::fill(_d_n.begin(), _d_n.end(), 0.0);
  _d_nn.assign(d_nn.begin(), d_nn.end());
  auto d = _d->x()->mutable_array();
  std::fill(d.begin(), d.end(), 0.0);
  std::fill(_J.begin(), _J.end(), 1.0);
  _history = 2;
  place_mesh();
}
//-----------------------------------------------------------------------------
void fsai::ale::MeshMotion::rewind()
{
  std::copy(_d_n.begin(), _d_n.end(), _d->x()->mutable_array().begin());
  place_mesh();
}
//-----------------------------------------------------------------------------
void fsai::ale::MeshMotion::place_mesh()
{
  auto d = _d->x()->array();
  auto x = _mesh->geometry().x();
  const int gdim = _mesh->geometry().dim();
  const int bs = _V->dofmap()->index_map_bs();
  for (std::size_t i = 0; i < _node_dof.size(); ++i)
    for (int k = 0; k < gdim; ++k)
      x[3 * i + k] = _X[3 * i + k] + d[bs * _node_dof[i] + k];
}
