// Copyright (C) 2026 fsai developers
#include "benchmarks.h"
#include "../common/errors.h"
#include "gmsh_model.h"
#include <cmath>
#include <gmsh.h>
#include <map>
#include <set>

fsai::mesh::MeshData fsai::mesh::turek_hron_beam(MPI_Comm comm, double h)
{
  fsai::require(h > 1e-4 and h <= 0.02, "Turek-Hron beam: mesh size h",
                "in (1e-4, 0.02] m", h);
  return build_with_gmsh(
      comm, 2,
      [&]()
      {
        namespace occ = gmsh::model::occ;
        gmsh::model::add("turek_hron_beam");
        const int rect = occ::addRectangle(0.2, 0.19, 0.0, 0.4, 0.02);
        const int disk = occ::addDisk(0.2, 0.2, 0.0, 0.05, 0.05);
        gmsh::vectorpair out;
        std::vector<gmsh::vectorpair> map;
        occ::cut({{2, rect}}, {{2, disk}}, out, map);
        // Point A on the free end as a vertex: split the end edge
        const int pA = occ::addPoint(0.6, 0.2, 0.0);
        gmsh::vectorpair out2;
        occ::fragment(out, {{0, pA}}, out2, map);
        occ::synchronize();
        out.clear();
        for (auto [d, t] : out2)
          if (d == 2)
            out.push_back({d, t});

        gmsh::vectorpair boundary;
        gmsh::model::getBoundary(out, boundary, true, false, false);
        std::vector<int> clamped, free;
        for (auto [d, c] : boundary)
        {
          c = std::abs(c);
          std::vector<double> lo, hi, mid;
          gmsh::model::getParametrizationBounds(1, c, lo, hi);
          gmsh::model::getValue(1, c, {0.5 * (lo[0] + hi[0])}, mid);
          const double r = std::hypot(mid[0] - 0.2, mid[1] - 0.2);
          (std::abs(r - 0.05) < 1e-6 ? clamped : free).push_back(c);
        }
        gmsh::model::addPhysicalGroup(1, clamped, 1);
        gmsh::model::setPhysicalName(1, 1, "clamped");
        gmsh::model::addPhysicalGroup(1, free, 2);
        gmsh::model::setPhysicalName(1, 2, "free");
        std::vector<int> s;
        for (auto [d, t] : out)
          s.push_back(t);
        gmsh::model::addPhysicalGroup(2, s, 1);
        gmsh::model::setPhysicalName(2, 1, "beam");
        gmsh::option::setNumber("Mesh.MeshSizeMax", h);
        gmsh::option::setNumber("Mesh.MeshSizeMin", h);
        gmsh::model::mesh::generate(2);
      });
}
//-----------------------------------------------------------------------------
fsai::mesh::MeshData fsai::mesh::dfg_channel(MPI_Comm comm, double h,
                                             double h_cyl)
{
  fsai::require(h > 0 and h <= 0.1, "DFG channel: mesh size h", "in (0, 0.1] m",
                h);
  fsai::require(h_cyl > 2e-4 and h_cyl <= h, "DFG channel: cylinder mesh size",
                "in (2e-4, h] m", h_cyl);
  return build_with_gmsh(
      comm, 2,
      [&]()
      {
        namespace occ = gmsh::model::occ;
        gmsh::model::add("dfg_channel");
        const int rect = occ::addRectangle(0.0, 0.0, 0.0, 2.2, 0.41);
        const int disk = occ::addDisk(0.2, 0.2, 0.0, 0.05, 0.05);
        gmsh::vectorpair out;
        std::vector<gmsh::vectorpair> map;
        occ::cut({{2, rect}}, {{2, disk}}, out, map);
        occ::synchronize();
        gmsh::vectorpair boundary;
        gmsh::model::getBoundary(out, boundary, true, false, false);
        std::vector<int> inlet, outlet, walls, cylinder;
        for (auto [d, c] : boundary)
        {
          c = std::abs(c);
          double x0, y0, z0, x1, y1, z1;
          gmsh::model::getBoundingBox(1, c, x0, y0, z0, x1, y1, z1);
          if (x1 < 1e-6)
            inlet.push_back(c);
          else if (x0 > 2.2 - 1e-6)
            outlet.push_back(c);
          else if (y1 < 1e-6 or y0 > 0.41 - 1e-6)
            walls.push_back(c);
          else
            cylinder.push_back(c);
        }
        int id = 1;
        for (auto [name, tags] : {std::pair{"inlet", inlet},
                                  {"outlet", outlet},
                                  {"walls", walls},
                                  {"cylinder", cylinder}})
        {
          gmsh::model::addPhysicalGroup(1, tags, id);
          gmsh::model::setPhysicalName(1, id++, name);
        }
        gmsh::model::addPhysicalGroup(2, {out[0].second}, 1);
        gmsh::model::setPhysicalName(2, 1, "fluid");

        // Size: h_cyl on the cylinder, growing linearly to h at 0.3 m
        size_near_curves(cylinder, h_cyl, h, 0.3);
        gmsh::option::setNumber("Mesh.Algorithm", 6);
        gmsh::model::mesh::generate(2);
      });
}
//-----------------------------------------------------------------------------
fsai::mesh::FluidSolidMeshes fsai::mesh::turek_hron_fsi(MPI_Comm comm, double h,
                                                        double h_i)
{
  fsai::require(h > 0 and h <= 0.1, "Turek-Hron FSI: mesh size h",
                "in (0, 0.1] m", h);
  fsai::require(h_i > 2e-4 and h_i <= std::min(h, 0.01),
                "Turek-Hron FSI: interface mesh size",
                "in (2e-4, min(h, 0.01)] m", h_i);
  auto parts = build_parts_with_gmsh(
      comm, 2,
      [&]()
      {
        namespace occ = gmsh::model::occ;
        gmsh::model::add("turek_hron_fsi");
        const double xc = 0.2, yc = 0.2, r = 0.05;
        const int channel = occ::addRectangle(0, 0, 0, 2.5, 0.41);
        const int disk = occ::addDisk(xc, yc, 0, r, r);
        const int beam = occ::addRectangle(0.2, 0.19, 0, 0.4, 0.02);
        const int pA = occ::addPoint(0.6, 0.2, 0);
        gmsh::vectorpair out;
        std::vector<gmsh::vectorpair> map;
        occ::fragment({{2, channel}}, {{2, disk}, {2, beam}, {0, pA}}, out,
                      map);
        occ::synchronize();
        // Sort the fragments: inside the cylinder (removed), beam, fluid
        std::vector<int> fluid, solid;
        gmsh::vectorpair inside;
        for (auto [d, t] : out)
        {
          if (d != 2)
            continue;
          double cx, cy, cz, area;
          occ::getCenterOfMass(d, t, cx, cy, cz);
          occ::getMass(d, t, area);
          if (std::hypot(cx - xc, cy - yc) < r)
            inside.push_back({d, t});
          else if (area < 0.01) // the beam, 0.35 x 0.02 m² less its clamp
            solid.push_back(t);
          else
            fluid.push_back(t);
        }
        occ::remove(inside, true);
        occ::synchronize();
        if (fluid.size() != 1 or solid.size() != 1)
          throw std::runtime_error("Turek-Hron FSI: unexpected fragments");

        auto curves = [](int surface)
        {
          gmsh::vectorpair b;
          gmsh::model::getBoundary({{2, surface}}, b, false, false, false);
          std::set<int> c;
          for (auto [d, t] : b)
            c.insert(std::abs(t));
          return c;
        };
        const std::set<int> cf = curves(fluid[0]), cs = curves(solid[0]);
        std::map<std::string, std::vector<int>> groups;
        for (int c : cf)
        {
          std::vector<double> lo, hi, m;
          gmsh::model::getParametrizationBounds(1, c, lo, hi);
          gmsh::model::getValue(1, c, {0.5 * (lo[0] + hi[0])}, m);
          std::string g;
          if (cs.count(c))
            g = "interface";
          else if (std::abs(std::hypot(m[0] - xc, m[1] - yc) - r) < 1e-6)
            g = "cylinder";
          else if (m[0] < 1e-9)
            g = "inlet";
          else if (m[0] > 2.5 - 1e-9)
            g = "outlet";
          else
            g = "walls";
          groups[g].push_back(c);
        }
        for (int c : cs)
          if (!cf.count(c))
            groups["clamped"].push_back(c);
        int id = 1;
        for (auto& [name, cs_] : groups)
        {
          gmsh::model::addPhysicalGroup(1, cs_, id);
          gmsh::model::setPhysicalName(1, id++, name);
        }
        gmsh::model::addPhysicalGroup(2, fluid, 1);
        gmsh::model::setPhysicalName(2, 1, "fluid");
        gmsh::model::addPhysicalGroup(2, solid, 2);
        gmsh::model::setPhysicalName(2, 2, "solid");

        // Size: h_i on the cylinder and the beam, growing to h at 0.3 m
        std::vector<int> near;
        for (auto* g :
             {&groups["cylinder"], &groups["interface"], &groups["clamped"]})
          near.insert(near.end(), g->begin(), g->end());
        size_near_curves(near, h_i, h, 0.3);
        gmsh::option::setNumber("Mesh.Algorithm", 6);
        gmsh::model::mesh::generate(2);
      },
      {"fluid", "solid"});
  return {std::move(parts[0]), std::move(parts[1])};
}
//-----------------------------------------------------------------------------
fsai::mesh::FluidSolidMeshes fsai::mesh::channel_flap_3d(MPI_Comm comm,
                                                         double h)
{
  fsai::require(h >= 0.01 and h <= 0.1, "3D flap channel: mesh size h",
                "in [0.01, 0.1] m", h);
  auto parts = build_parts_with_gmsh(
      comm, 3,
      [&]()
      {
        namespace occ = gmsh::model::occ;
        gmsh::model::add("channel_flap_3d");
        const int channel = occ::addBox(0, 0, 0, 1.0, 0.4, 0.4);
        const int flap = occ::addBox(0.4, 0, 0.1, 0.05, 0.25, 0.2);
        gmsh::vectorpair out;
        std::vector<gmsh::vectorpair> map;
        occ::fragment({{3, channel}}, {{3, flap}}, out, map);
        occ::synchronize();
        std::vector<int> fluid, solid;
        for (auto [d, t] : out)
        {
          double v;
          occ::getMass(d, t, v);
          (v < 0.01 ? solid : fluid).push_back(t);
        }
        if (fluid.size() != 1 or solid.size() != 1)
          throw std::runtime_error("3D flap channel: unexpected fragments");
        tag_fluid_solid_3d(fluid[0], solid[0],
                           [](const std::array<double, 3>& c) -> std::string {
                             return c[0] < 1e-9       ? "inlet"
                                    : c[0] > 1 - 1e-9 ? "outlet"
                                                      : "walls";
                           });
        gmsh::option::setNumber("Mesh.MeshSizeMax", h);
        gmsh::option::setNumber("Mesh.MeshSizeMin", h / 4);
        gmsh::model::mesh::generate(3);
      },
      {"fluid", "solid"});
  return {std::move(parts[0]), std::move(parts[1])};
}
