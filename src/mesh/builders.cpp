// Copyright (C) 2026 fsai developers
#include "builders.h"
#include "../common/errors.h"
#include "gmsh_model.h"
#include <cmath>
#include <gmsh.h>

namespace
{
/// Checks shared by the builders: positive extents, sane mesh size
template <std::size_t N>
void check_extent(const std::string& what, const std::array<double, N>& p0,
                  const std::array<double, N>& p1, double h)
{
  fsai::require_positive(what + ": mesh size h", h);
  double cells = 1.0; // Estimate of the number of cells, up to a factor
  for (std::size_t i = 0; i < N; ++i)
  {
    fsai::require(p1[i] > p0[i], what + ": extent", "positive", p1[i] - p0[i]);
    cells *= (p1[i] - p0[i]) / h;
  }
  fsai::require(std::isfinite(h) and cells <= 1e8, what + ": mesh size h",
                "large enough for at most ~1e8 cells", h);
}

/// Name the boundary of the single volume/surface `dim` by the bounding box
/// faces it lies on; `names` lists (axis, side) in group order
void tag_box_boundary(int dim, const std::vector<std::string>& names)
{
  gmsh::vectorpair boundary;
  gmsh::model::getBoundary({{dim, 1}}, boundary, false, false, false);
  double xmin, ymin, zmin, xmax, ymax, zmax;
  gmsh::model::getBoundingBox(dim, 1, xmin, ymin, zmin, xmax, ymax, zmax);
  const std::array<double, 3> lo{xmin, ymin, zmin}, hi{xmax, ymax, zmax};
  const double tol = 1e-6 * std::max({xmax - xmin, ymax - ymin, zmax - zmin});

  std::vector<std::vector<int>> groups(names.size());
  for (auto [d, tag] : boundary)
  {
    double a[3], b[3];
    gmsh::model::getBoundingBox(d, std::abs(tag), a[0], a[1], a[2], b[0], b[1],
                                b[2]);
    for (std::size_t g = 0; g < names.size(); ++g)
    {
      const std::size_t axis = g / 2;
      const double plane = g % 2 == 0 ? lo[axis] : hi[axis];
      if (std::abs(a[axis] - plane) < tol and std::abs(b[axis] - plane) < tol)
        groups[g].push_back(std::abs(tag));
    }
  }
  for (std::size_t g = 0; g < names.size(); ++g)
  {
    int t = gmsh::model::addPhysicalGroup(dim - 1, groups[g],
                                          static_cast<int>(g) + 1);
    gmsh::model::setPhysicalName(dim - 1, t, names[g]);
  }
  int t = gmsh::model::addPhysicalGroup(dim, {1}, 1);
  gmsh::model::setPhysicalName(dim, t, "domain");
}
} // namespace

//-----------------------------------------------------------------------------
fsai::mesh::MeshData fsai::mesh::rectangle(MPI_Comm comm,
                                           std::array<double, 2> p0,
                                           std::array<double, 2> p1, double h)
{
  check_extent("rectangle", p0, p1, h);
  return build_with_gmsh(
      comm, 2,
      [&]()
      {
        gmsh::model::add("rectangle");
        gmsh::model::occ::addRectangle(p0[0], p0[1], 0.0, p1[0] - p0[0],
                                       p1[1] - p0[1], 1);
        gmsh::model::occ::synchronize();
        tag_box_boundary(2, {"left", "right", "bottom", "top"});
        gmsh::option::setNumber("Mesh.MeshSizeMin", h);
        gmsh::option::setNumber("Mesh.MeshSizeMax", h);
        gmsh::model::mesh::generate(2);
      });
}
//-----------------------------------------------------------------------------
fsai::mesh::MeshData fsai::mesh::box(MPI_Comm comm, std::array<double, 3> p0,
                                     std::array<double, 3> p1, double h)
{
  check_extent("box", p0, p1, h);
  return build_with_gmsh(
      comm, 3,
      [&]()
      {
        gmsh::model::add("box");
        gmsh::model::occ::addBox(p0[0], p0[1], p0[2], p1[0] - p0[0],
                                 p1[1] - p0[1], p1[2] - p0[2], 1);
        gmsh::model::occ::synchronize();
        tag_box_boundary(3, {"xmin", "xmax", "ymin", "ymax", "zmin", "zmax"});
        gmsh::option::setNumber("Mesh.MeshSizeMin", h);
        gmsh::option::setNumber("Mesh.MeshSizeMax", h);
        gmsh::model::mesh::generate(3);
      });
}
//-----------------------------------------------------------------------------
