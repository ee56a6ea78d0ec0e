// Copyright (C) 2026 fsai developers
#include "PointProbes.h"
#include "../common/errors.h"
#include <dolfinx/geometry/BoundingBoxTree.h>
#include <dolfinx/geometry/utils.h>
#include <fmt/format.h>
#include <limits>

//-----------------------------------------------------------------------------
fsai::io::PointProbes::PointProbes(
    std::shared_ptr<const dolfinx::mesh::Mesh> mesh,
    std::vector<std::array<double, 3>> points)
    : _mesh(mesh), _points(std::move(points))
{
  const int tdim = mesh->topology().dim();
  const std::int32_t num_owned_cells
      = mesh->topology().index_map(tdim)->size_local();
  std::vector<double> flat;
  for (auto p : _points)
  {
    if (tdim == 2)
      p[2] = 0.0;
    flat.insert(flat.end(), p.begin(), p.end());
  }

  // Candidate cells from the bounding boxes, then exact collisions
  dolfinx::geometry::BoundingBoxTree tree(*mesh, tdim);
  auto candidates = dolfinx::geometry::compute_collisions(tree, flat);
  auto colliding
      = dolfinx::geometry::compute_colliding_cells(*mesh, candidates, flat);

  // The owner of a point is the lowest rank with an owned cell containing it
  int rank;
  MPI_Comm_rank(mesh->comm(), &rank);
  const int none = std::numeric_limits<int>::max();
  std::vector<int> claim(_points.size(), none), owner(_points.size());
  std::vector<std::int32_t> cell(_points.size(), -1);
  for (std::size_t i = 0; i < _points.size(); ++i)
  {
    for (std::int32_t c : colliding.links(i))
    {
      if (c < num_owned_cells)
      {
        claim[i] = rank;
        cell[i] = c;
        break;
      }
    }
  }
  MPI_Allreduce(claim.data(), owner.data(), int(claim.size()), MPI_INT, MPI_MIN,
                mesh->comm());
  for (std::size_t i = 0; i < _points.size(); ++i)
  {
    if (owner[i] == none)
    {
      throw fsai::InputError(
          fmt::format("probe point ({}, {}, {}) lies outside the mesh",
                      _points[i][0], _points[i][1], _points[i][2]));
    }
    if (owner[i] == rank)
    {
      _owned.push_back(i);
      _cells.push_back(cell[i]);
    }
  }
}
//-----------------------------------------------------------------------------
std::vector<double>
fsai::io::PointProbes::values(const dolfinx::fem::Function<double>& u) const
{
  const std::size_t vs = u.function_space()->element()->value_size();
  std::vector<double> local(_points.size() * vs, 0.0), global(local.size());
  if (!_owned.empty())
  {
    std::vector<double> x;
    for (std::size_t i : _owned)
      x.insert(x.end(), _points[i].begin(), _points[i].end());
    std::vector<double> val(_owned.size() * vs);
    u.eval(x, {_owned.size(), 3}, _cells, val, {_owned.size(), vs});
    for (std::size_t j = 0; j < _owned.size(); ++j)
      for (std::size_t k = 0; k < vs; ++k)
        local[_owned[j] * vs + k] = val[j * vs + k];
  }
  // Exactly one rank contributes each value
  MPI_Allreduce(local.data(), global.data(), int(local.size()), MPI_DOUBLE,
                MPI_SUM, _mesh->comm());
  return global;
}
//-----------------------------------------------------------------------------
