// Copyright (C) 2026 fsai developers
#include "InterfaceMap.h"
#include <cmath>
#include <common/mpi_gather.h>
#include <dolfinx/fem/DirichletBC.h>
#include <dolfinx/fem/FunctionSpace.h>
#include <dolfinx/mesh/utils.h>
#include <fmt/format.h>
#include <stdexcept>

using namespace dolfinx;

namespace
{
using fsai::common::allgather;

/// Index of the point of `pts` (3 per point) within tol of p, or −1
std::int64_t find(const std::vector<double>& pts, const double* p, double tol)
{
  for (std::size_t k = 0; k < pts.size() / 3; ++k)
  {
    if (std::abs(pts[3 * k] - p[0]) < tol
        and std::abs(pts[3 * k + 1] - p[1]) < tol
        and std::abs(pts[3 * k + 2] - p[2]) < tol)
      return std::int64_t(k);
  }
  return -1;
}
} // namespace
//-----------------------------------------------------------------------------
fsai::coupling::InterfaceMap::InterfaceMap(
    const fem::FunctionSpace& Vf, std::span<const std::int32_t> fluid_facets,
    const fem::FunctionSpace& Vs, std::span<const std::int32_t> solid_facets,
    double tol)
    : _comm(Vf.mesh()->comm()), _bs(Vf.dofmap()->index_map_bs())
{
  if (Vs.dofmap()->index_map_bs() != _bs)
    throw std::runtime_error("InterfaceMap: fluid and solid block sizes "
                             "differ");
  const int tdim = Vf.mesh()->topology().dim(), fdim = tdim - 1;
  Vf.mesh()->topology_mutable().create_connectivity(fdim, tdim);
  Vs.mesh()->topology_mutable().create_connectivity(fdim, tdim);
  _fdofs = fem::locate_dofs_topological(Vf, fdim, fluid_facets);
  _sdofs = fem::locate_dofs_topological(Vs, fdim, solid_facets);
  const std::int32_t fo = Vf.dofmap()->index_map->size_local(),
                     so = Vs.dofmap()->index_map->size_local();
  for (auto d : _fdofs)
    if (d < fo)
      _fowned.push_back(d);
  for (auto d : _sdofs)
    if (d < so)
      _sowned.push_back(d);
  const std::vector<double> Xf = Vf.tabulate_dof_coordinates(false),
                            Xs = Vs.tabulate_dof_coordinates(false);
  auto coords
      = [](const std::vector<double>& X, const std::vector<std::int32_t>& dofs)
  {
    std::vector<double> c;
    for (auto d : dofs)
      c.insert(c.end(), X.begin() + 3 * d, X.begin() + 3 * d + 3);
    return c;
  };

  // Fluid dofs <- solid points (every fluid interface vertex is one)
  const std::vector<double> S = allgather(_comm, coords(Xs, _sowned));
  for (auto d : _fdofs)
  {
    const std::int64_t k = find(S, &Xf[3 * d], tol);
    if (k < 0)
    {
      throw std::runtime_error(fmt::format(
          "InterfaceMap: fluid interface point ({:.6g}, {:.6g}, {:.6g}) is "
          "not a solid interface dof (non-matching meshes?)",
          Xf[3 * d], Xf[3 * d + 1], Xf[3 * d + 2]));
    }
    _f_from.push_back(k);
  }

  // Solid dofs <- fluid vertices, or midpoints of fluid interface edges
  const std::vector<double> F = allgather(_comm, coords(Xf, _fowned));
  std::vector<double> edges; // (a, b) endpoint coordinates
  {
    auto& mesh = *Vf.mesh();
    std::vector<std::int32_t> facets(fluid_facets.begin(), fluid_facets.end());
    auto g = mesh::entities_to_geometry(mesh, fdim, facets, false);
    auto x = mesh.geometry().x();
    const std::size_t nv = tdim; // vertices of a simplex facet (affine)
    for (std::size_t f = 0; f < facets.size(); ++f)
      for (std::size_t i = 0; i < nv; ++i)
        for (std::size_t j = i + 1; j < nv; ++j)
          for (auto n : {g[f * nv + i], g[f * nv + j]})
            edges.insert(edges.end(), x.begin() + 3 * n, x.begin() + 3 * n + 3);
  }
  edges = allgather(_comm, edges);
  std::vector<double> mid;
  for (std::size_t e = 0; e < edges.size() / 6; ++e)
    for (int k = 0; k < 3; ++k)
      mid.push_back(0.5 * (edges[6 * e + k] + edges[6 * e + 3 + k]));
  for (auto d : _sdofs)
  {
    const std::int64_t k = find(F, &Xs[3 * d], tol);
    if (k >= 0)
    {
      _s_from.push_back({k, k});
      continue;
    }
    const std::int64_t e = find(mid, &Xs[3 * d], tol);
    const std::int64_t a = e < 0 ? -1 : find(F, &edges[6 * e], tol),
                       b = e < 0 ? -1 : find(F, &edges[6 * e + 3], tol);
    if (a < 0 or b < 0)
    {
      throw std::runtime_error(fmt::format(
          "InterfaceMap: solid interface dof at ({:.6g}, {:.6g}, {:.6g}) is "
          "neither a fluid interface vertex nor an edge midpoint",
          Xs[3 * d], Xs[3 * d + 1], Xs[3 * d + 2]));
    }
    _s_from.push_back({a, b});
  }
}
//-----------------------------------------------------------------------------
std::vector<double> fsai::coupling::InterfaceMap::gather(
    const fem::Function<double>& u,
    const std::vector<std::int32_t>& owned) const
{
  auto a = u.x()->array();
  std::vector<double> v;
  for (auto d : owned)
    for (int k = 0; k < _bs; ++k)
      v.push_back(a[_bs * d + k]);
  return allgather(_comm, v);
}
//-----------------------------------------------------------------------------
void fsai::coupling::InterfaceMap::solid_to_fluid(
    const fem::Function<double>& us, fem::Function<double>& uf) const
{
  const std::vector<double> S = gather(us, _sowned);
  auto a = uf.x()->mutable_array();
  for (std::size_t i = 0; i < _fdofs.size(); ++i)
    for (int k = 0; k < _bs; ++k)
      a[_bs * _fdofs[i] + k] = S[_bs * _f_from[i] + k];
}
//-----------------------------------------------------------------------------
void fsai::coupling::InterfaceMap::fluid_to_solid(
    const fem::Function<double>& uf, fem::Function<double>& us) const
{
  const std::vector<double> F = gather(uf, _fowned);
  auto a = us.x()->mutable_array();
  for (std::size_t j = 0; j < _sdofs.size(); ++j)
    for (int k = 0; k < _bs; ++k)
      a[_bs * _sdofs[j] + k]
          = 0.5 * (F[_bs * _s_from[j][0] + k] + F[_bs * _s_from[j][1] + k]);
}
