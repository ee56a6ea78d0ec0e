// Copyright (C) 2026 fsai developers
#include "vocal_fold.h"
#include "../common/Parameters.h"
#include "../common/errors.h"
#include "gmsh_model.h"
#include <cmath>
#include <dolfinx/mesh/utils.h>
#include <gmsh.h>
#include <numeric>
#include <stdexcept>
#include <string>

//-----------------------------------------------------------------------------
void fsai::mesh::VocalFoldGeometry::bind(fsai::common::Parameters& p)
{
  p.add("fold.depth", depth, "lateral-medial depth [m]");
  p.add("fold.height", height, "height at the lateral wall [m]");
  p.add("fold.length", length, "anterior-posterior length [m]");
  p.add("fold.a", a, "superior-medial corner, horizontal semi-axis [m]");
  p.add("fold.b", b, "superior-medial corner, vertical semi-axis [m]");
  p.add("fold.t_medial", t_medial, "height of the vertical medial surface [m]");
  p.add("fold.r_inf", r_inf, "inferior-medial corner radius [m]");
  p.add("fold.cover", cover, "cover thickness of a two-layer fold [m]");
  p.add("fold.h", h, "mesh size [m]");
}
//-----------------------------------------------------------------------------
void fsai::mesh::VocalFoldGeometry::validate() const
{
  for (auto [name, v] : {std::pair{"depth", depth},
                         {"height", height},
                         {"length", length},
                         {"a", a},
                         {"b", b},
                         {"t_medial", t_medial},
                         {"r_inf", r_inf},
                         {"cover", cover},
                         {"h", h}})
  {
    fsai::require_positive(std::string("--fold.") + name, v);
  }
  fsai::require(a + r_inf < depth, "--fold.a", "< depth - r_inf", a);
  fsai::require(b + t_medial + r_inf < height, "--fold.b",
                "< height - t_medial - r_inf", b);
  fsai::require(h <= 0.5 * std::min(depth, length), "--fold.h",
                "<= half the depth and the length", h);
  fsai::require(std::pow(std::max(depth, length) / h, 3) < 2e7, "--fold.h",
                "large enough for at most ~1e8 cells", h);
}
//-----------------------------------------------------------------------------
std::vector<std::array<double, 2>>
fsai::mesh::VocalFoldGeometry::free_profile() const
{
  const int n = 12; // segments per rounded corner
  std::vector<std::array<double, 2>> p{{0.0, height}};
  const double cx = depth - a, cy = height - b;
  for (int i = 0; i <= n; ++i) // superior-medial corner, 90° → 0°
  {
    const double t = 0.5 * M_PI * (1.0 - double(i) / n);
    p.push_back({cx + a * std::cos(t), cy + b * std::sin(t)});
  }
  const double y1 = cy - t_medial; // bottom of the medial surface
  const double ix = depth - r_inf;
  for (int i = 0; i <= n; ++i) // inferior-medial corner, 0° → −90°
  {
    const double t = -0.5 * M_PI * double(i) / n;
    p.push_back({ix + r_inf * std::cos(t), y1 + r_inf * std::sin(t)});
  }
  p.push_back({0.0, 0.0}); // inferior surface down to the lateral wall
  return p;
}
//-----------------------------------------------------------------------------
int fsai::mesh::add_fold_body(const VocalFoldGeometry& g, int dim)
{
  namespace occ = gmsh::model::occ;
  std::vector<int> pts;
  for (auto [x, y] : g.free_profile())
    pts.push_back(occ::addPoint(x, y, 0.0));
  std::vector<int> lines;
  for (std::size_t i = 0; i + 1 < pts.size(); ++i)
    lines.push_back(occ::addLine(pts[i], pts[i + 1]));
  lines.push_back(occ::addLine(pts.back(), pts.front())); // lateral wall
  const int s = occ::addPlaneSurface({occ::addCurveLoop(lines)});
  if (dim == 2)
    return s;
  gmsh::vectorpair out;
  occ::extrude({{2, s}}, 0.0, 0.0, g.length, out);
  for (auto [d, t] : out)
    if (d == 3)
      return t;
  throw std::runtime_error("vocal fold: the profile's extrusion has no volume");
}
//-----------------------------------------------------------------------------
fsai::mesh::MeshData fsai::mesh::vocal_fold(MPI_Comm comm,
                                            const VocalFoldGeometry& g, int dim)
{
  g.validate();
  fsai::require(dim == 2 or dim == 3, "vocal fold mesh: dimension", "2 or 3",
                dim);
  return build_with_gmsh(
      comm, dim,
      [&]()
      {
        namespace occ = gmsh::model::occ;
        gmsh::model::add("vocal_fold");
        const int body = add_fold_body(g, dim);
        occ::synchronize();

        // The section's boundary: the lateral line x = 0 and the free
        // profile; the solid's also the anterior and posterior faces
        gmsh::vectorpair faces;
        gmsh::model::getBoundary({{dim, body}}, faces, false, false, false);
        const double tol = 1e-6 * g.length;
        std::vector<int> lateral, anterior, posterior, surface;
        for (auto [d, f] : faces)
        {
          double x0, y0, z0, x1, y1, z1;
          gmsh::model::getBoundingBox(dim - 1, std::abs(f), x0, y0, z0, x1, y1,
                                      z1);
          if (x1 < 10 * tol)
            lateral.push_back(std::abs(f));
          else if (dim == 3 and z1 < 10 * tol)
            anterior.push_back(std::abs(f));
          else if (dim == 3 and z0 > g.length - 10 * tol)
            posterior.push_back(std::abs(f));
          else
            surface.push_back(std::abs(f));
        }
        auto group = [](int d, const std::vector<int>& t, int id,
                        const std::string& name)
        {
          gmsh::model::addPhysicalGroup(d, t, id);
          gmsh::model::setPhysicalName(d, id, name);
        };
        group(dim - 1, lateral, 1, "lateral");
        if (dim == 3)
        {
          group(2, anterior, 2, "anterior");
          group(2, posterior, 3, "posterior");
        }
        group(dim - 1, surface, 4, "surface");
        group(dim, {body}, 1, "fold");
        gmsh::option::setNumber("Mesh.MeshSizeMax", g.h);
        gmsh::option::setNumber("Mesh.MeshSizeMin", 0.25 * g.h);
        gmsh::model::mesh::generate(dim);
      });
}
//-----------------------------------------------------------------------------
std::vector<std::int32_t> fsai::mesh::attached_facets(const MeshData& m)
{
  std::vector<std::int32_t> facets;
  const bool solid = m.mesh->topology().dim() == 3;
  for (const char* g : {"lateral", "anterior", "posterior"})
  {
    if (solid or std::string(g) == "lateral")
    {
      auto f = m.facet_tags->find(m.facet_tag(g));
      facets.insert(facets.end(), f.begin(), f.end());
    }
  }
  return facets;
}
//-----------------------------------------------------------------------------
std::vector<std::int32_t>
fsai::mesh::cells_near_curve(const dolfinx::mesh::Mesh& mesh,
                             const std::vector<std::array<double, 2>>& curve,
                             double distance)
{
  const int tdim = mesh.topology().dim();
  const std::int32_t n = mesh.topology().index_map(tdim)->size_local()
                         + mesh.topology().index_map(tdim)->num_ghosts();
  std::vector<std::int32_t> all(n);
  std::iota(all.begin(), all.end(), 0);
  std::vector<double> mid = dolfinx::mesh::compute_midpoints(mesh, tdim, all);
  std::vector<std::int32_t> near;
  for (std::int32_t c = 0; c < n; ++c)
  {
    const double px = mid[3 * c], py = mid[3 * c + 1];
    double d2 = 1e300;
    for (std::size_t i = 0; i + 1 < curve.size(); ++i)
    {
      const auto [ax, ay] = curve[i];
      const auto [bx, by] = curve[i + 1];
      const double ex = bx - ax, ey = by - ay;
      const double t = std::clamp(
          ((px - ax) * ex + (py - ay) * ey) / (ex * ex + ey * ey), 0.0, 1.0);
      const double dx = px - ax - t * ex, dy = py - ay - t * ey;
      d2 = std::min(d2, dx * dx + dy * dy);
    }
    if (d2 < distance * distance)
      near.push_back(c);
  }
  return near;
}
//-----------------------------------------------------------------------------
std::vector<std::int32_t>
fsai::mesh::cover_cells(const dolfinx::mesh::Mesh& mesh,
                        const VocalFoldGeometry& g)
{
  return cells_near_curve(mesh, g.free_profile(), g.cover);
}
//-----------------------------------------------------------------------------
