// Copyright (C) 2026 fsai developers
#include "vocal_tract.h"
#include "../common/Parameters.h"
#include "../common/errors.h"
#include "gmsh_model.h"
#include <cmath>
#include <gmsh.h>
#include <set>

namespace
{
/// Closed polygon between y = 0 and the wall y = r(x) + offset, with r the
/// half-width of the area function: steps at the section ends (stepped) or
/// straight lines between points at the section centres, 4 per interval
/// so the axisymmetric radius sqrt(A/π) of a linear A is followed (smooth)
/// The polygon starts at x_back <= 0 (the head's body behind the glottis,
/// so a radiation region larger than the tract cannot reach the glottis).
int tract_surface(const fsai::mesh::AreaFunction& af,
                  const fsai::mesh::VocalTractGeometry& g, double offset,
                  double x_back = 0.0)
{
  namespace occ = gmsh::model::occ;
  auto r = [&](double x)
  { return fsai::mesh::tract_half_width(g, af.area_at(x, g.smooth)) + offset; };
  std::vector<std::array<double, 2>> pts{{x_back, 0.0}};
  if (x_back < 0.0)
    pts.push_back({x_back, r(0.0)});
  if (g.smooth)
  {
    const int sub = g.model == "axisym" ? 4 : 1;
    if (x_back == 0.0)
      pts.push_back({0.0, r(0.0)});
    for (std::size_t k = 0; k < af.size(); ++k)
    {
      const double xc = af.x_centre(k);
      if (k > 0)
      {
        const double xp = af.x_centre(k - 1);
        for (int i = 1; i < sub; ++i)
        {
          const double x = xp + (xc - xp) * i / sub;
          pts.push_back({x, r(x)});
        }
      }
      pts.push_back({xc, r(xc)});
    }
    pts.push_back({af.length(), r(af.length())});
  }
  else
  {
    for (std::size_t k = 0; k < af.size(); ++k)
    {
      const double rk = fsai::mesh::tract_half_width(g, af.area[k]) + offset;
      if ((k == 0 and x_back == 0.0)
          or (k > 0 and af.area[k] != af.area[k - 1]))
        pts.push_back({af.x_start(k), rk});
      pts.push_back({af.x_end[k], rk});
      // Merge with the next section if it has the same area
      if (k + 1 < af.size() and af.area[k + 1] == af.area[k])
        pts.pop_back();
    }
  }
  pts.push_back({af.length(), 0.0});
  std::vector<int> p, l;
  for (auto [x, y] : pts)
    p.push_back(occ::addPoint(x, y, 0.0));
  for (std::size_t i = 0; i < p.size(); ++i)
    l.push_back(occ::addLine(p[i], p[(i + 1) % p.size()]));
  return occ::addPlaneSurface({occ::addCurveLoop(l)});
}

/// Upper half disk of radius R around (L, 0) (x >= L only if `baffle`)
int half_disk(double L, double R, bool baffle)
{
  namespace occ = gmsh::model::occ;
  const int disk = occ::addDisk(L, 0.0, 0.0, R, R);
  const double x0 = baffle ? L : L - 1.1 * R;
  const int box = occ::addRectangle(x0, 0.0, 0.0, L + 1.1 * R - x0, 1.1 * R);
  gmsh::vectorpair out;
  std::vector<gmsh::vectorpair> map;
  occ::intersect({{2, disk}}, {{2, box}}, out, map);
  if (out.size() != 1)
    throw std::runtime_error(
        "vocal tract: radiation half-disk is not one surface");
  return out[0].second;
}

std::vector<int> tags_of(const gmsh::vectorpair& v)
{
  std::vector<int> t;
  for (auto [d, tag] : v)
    if (d == 2)
      t.push_back(tag);
  return t;
}
} // namespace

//-----------------------------------------------------------------------------
void fsai::mesh::VocalTractGeometry::bind(fsai::common::Parameters& p)
{
  p.add("tract.half", half, "planar: symmetric half-domain y >= 0");
  p.add("tract.smooth", smooth,
        "wall straight between section centres (false: stepped sections)");
  p.add("tract.depth", depth, "depth L_g of the planar model [m]");
  p.add("tract.radius", radius, "radius of the radiation region [m]");
  p.add("tract.baffle", baffle, "wall (baffle) at the lips plane");
  p.add("tract.wall", wall, "tract wall thickness outside the mouth [m]");
  p.add("tract.cells_across", cells_across,
        "minimum number of cells across a section's half-width");
}
//-----------------------------------------------------------------------------
void fsai::mesh::VocalTractGeometry::validate() const
{
  fsai::require(model == "planar" or model == "axisym", "tract model",
                "planar or axisym", model);
  fsai::require_positive("--tract.depth", depth);
  fsai::require_positive("--tract.radius", radius);
  fsai::require_positive("--tract.wall", wall);
  fsai::require(layer >= 0.0, "absorbing layer thickness", ">= 0", layer);
  fsai::require_positive("mesh size h", h);
  fsai::require_range("--tract.cells_across", cells_across, 0.5, 20.0);
}
//-----------------------------------------------------------------------------
double fsai::mesh::tract_half_width(const VocalTractGeometry& g, double A)
{
  return g.model == "axisym" ? std::sqrt(A / M_PI) : 0.5 * A / g.depth;
}
//-----------------------------------------------------------------------------
fsai::mesh::MeshData fsai::mesh::vocal_tract(MPI_Comm comm,
                                             const AreaFunction& af,
                                             const VocalTractGeometry& g)
{
  g.validate();
  fsai::require(af.size() >= 1, "area function", "at least one section",
                af.size());
  const double L = af.length();
  std::vector<double> r(af.size());
  for (std::size_t k = 0; k < af.size(); ++k)
    r[k] = tract_half_width(g, af.area[k]);
  const double rmin = *std::min_element(r.begin(), r.end());
  if (g.open)
  {
    fsai::require(g.radius > r.back() + g.wall, "--tract.radius",
                  "larger than the mouth opening plus the wall", g.radius);
  }
  const double hmin = std::min(g.h, rmin / g.cells_across);
  const double extent = std::max(L, g.radius + g.layer);
  fsai::require(extent * extent / (hmin * hmin) < 1e8, "mesh size",
                "large enough for at most ~1e8 cells", hmin);
  const bool mirrored = g.model == "planar" and !g.half;

  return build_with_gmsh(
      comm, 2,
      [&]()
      {
        namespace occ = gmsh::model::occ;
        gmsh::model::add("vocal_tract");
        const int tract = tract_surface(af, g, 0.0);
        std::vector<int> air_in, layer_in;
        if (g.open)
        {
          // The outside of the head: the tract wall offset by `wall`
          // (unflanged), or the half-plane x < L (baffle)
          const int sector = half_disk(L, g.radius, g.baffle);
          gmsh::vectorpair out;
          std::vector<gmsh::vectorpair> map;
          if (!g.baffle)
          {
            const int head
                = tract_surface(af, g, g.wall, -1.2 * (g.radius + g.layer));
            occ::cut({{2, sector}}, {{2, head}}, out, map, -1, true,
                     g.layer <= 0.0);
            if (g.layer > 0.0)
            {
              const int big = half_disk(L, g.radius + g.layer, false);
              gmsh::vectorpair o2;
              occ::cut({{2, big}}, {{2, head}}, o2, map, -1, true, true);
              layer_in = tags_of(o2);
            }
          }
          else
          {
            out = {{2, sector}};
            if (g.layer > 0.0)
              layer_in = {half_disk(L, g.radius + g.layer, true)};
          }
          air_in = tags_of(out);
        }

        // Conforming pieces: tract, air, layer (the layer overlaps air until
        // fragmented, so air is listed first and takes the overlap)
        gmsh::vectorpair objects{{2, tract}}, tools;
        for (int t : air_in)
          tools.push_back({2, t});
        for (int t : layer_in)
          tools.push_back({2, t});
        gmsh::vectorpair out;
        std::vector<gmsh::vectorpair> map{objects};
        if (!tools.empty())
          occ::fragment(objects, tools, out, map);
        occ::synchronize();

        // Classify the fragments by their parents: map[0] is the tract,
        // then the air pieces, then the layer pieces (the part of a layer
        // piece that overlaps the air is a child of both: it is air)
        std::vector<int> tract_s = tags_of(map[0]), air_s, layer_s;
        std::set<int> seen(tract_s.begin(), tract_s.end());
        for (std::size_t i = 1; i < map.size(); ++i)
        {
          for (int s : tags_of(map[i]))
          {
            if (seen.insert(s).second)
              (i <= air_in.size() ? air_s : layer_s).push_back(s);
          }
        }

        if (mirrored)
        {
          // Full planar channel: mirror about y = 0 and glue
          gmsh::vectorpair all, copy;
          for (auto* v : {&tract_s, &air_s, &layer_s})
            for (int s : *v)
              all.push_back({2, s});
          occ::copy(all, copy);
          occ::mirror(copy, 0.0, 1.0, 0.0, 0.0);
          gmsh::vectorpair out2;
          std::vector<gmsh::vectorpair> map2;
          occ::fragment(all, copy, out2, map2);
          occ::synchronize();
          std::vector<int> t2, a2, l2;
          for (std::size_t i = 0; i < map2.size(); ++i)
          {
            const int orig = all[i % all.size()].second;
            auto& dst
                = std::find(tract_s.begin(), tract_s.end(), orig)
                          != tract_s.end()
                      ? t2
                  : std::find(air_s.begin(), air_s.end(), orig) != air_s.end()
                      ? a2
                      : l2;
            for (int s : tags_of(map2[i]))
              dst.push_back(s);
          }
          tract_s = t2, air_s = a2, layer_s = l2;
        }

        // Cell groups
        auto group =
            [](int dim, std::vector<int> tags, int id, const std::string& name)
        {
          std::sort(tags.begin(), tags.end());
          tags.erase(std::unique(tags.begin(), tags.end()), tags.end());
          if (tags.empty())
            return;
          gmsh::model::addPhysicalGroup(dim, tags, id);
          gmsh::model::setPhysicalName(dim, id, name);
        };
        group(2, tract_s, 1, "tract");
        group(2, air_s, 2, "air");
        group(2, layer_s, 3, "layer");

        // Facet groups by position
        gmsh::vectorpair surfaces, boundary;
        for (auto* v : {&tract_s, &air_s, &layer_s})
          for (int s : *v)
            surfaces.push_back({2, s});
        gmsh::model::getBoundary(surfaces, boundary, true, false, false);
        // OCC bounding boxes are padded by its tolerance (~1e-7): compare
        // loosely
        const double tol = 1e-5 * extent;
        const double r_out = g.radius + g.layer;
        std::vector<int> glottis, wall, axis, lips, radiation;
        for (auto [d, c] : boundary)
        {
          c = std::abs(c);
          double x0, y0, z0, x1, y1, z1;
          gmsh::model::getBoundingBox(1, c, x0, y0, z0, x1, y1, z1);
          std::vector<double> lo, hi, mid;
          gmsh::model::getParametrizationBounds(1, c, lo, hi);
          gmsh::model::getValue(1, c, {0.5 * (lo[0] + hi[0])}, mid);
          if (x1 < tol)
            glottis.push_back(c);
          else if (!mirrored and std::abs(y0) < tol and std::abs(y1) < tol)
            axis.push_back(c);
          else if (!g.open and std::abs(x0 - L) < tol
                   and std::abs(x1 - L) < tol)
            lips.push_back(c);
          else if (g.open
                   and std::abs(std::hypot(mid[0] - L, mid[1]) - r_out)
                           < 1e-6 * r_out)
            radiation.push_back(c);
          else
            wall.push_back(c);
        }
        group(1, glottis, 1, "glottis");
        group(1, wall, 2, "wall");
        group(1, axis, 3, "axis");
        group(1, lips, 4, "lips");
        group(1, radiation, 5, "radiation");

        // Mesh size: h, finer where a section is narrow (cells_across
        // cells across its half-width), at the points of the profile
        gmsh::vectorpair points;
        gmsh::model::getEntities(points, 0);
        for (auto [d, pt] : points)
        {
          double x0, y0, z0, x1, y1, z1;
          gmsh::model::getBoundingBox(0, pt, x0, y0, z0, x1, y1, z1);
          double size = g.h;
          for (std::size_t k = 0; k < af.size(); ++k)
          {
            if (x0 >= af.x_start(k) - tol and x0 <= af.x_end[k] + tol
                and std::abs(y0) <= r[k] + g.wall + tol)
            {
              size = std::min(size, r[k] / g.cells_across);
            }
          }
          gmsh::model::mesh::setSize({{0, pt}}, size);
        }
        gmsh::option::setNumber("Mesh.MeshSizeMax", g.h);
        gmsh::option::setNumber("Mesh.Algorithm", 6);
        gmsh::model::mesh::generate(2);
      });
}
//-----------------------------------------------------------------------------
