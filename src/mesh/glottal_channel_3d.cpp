// Copyright (C) 2026 fsai developers
#include "glottal_channel_3d.h"
#include "../common/Parameters.h"
#include "../common/errors.h"
#include "gmsh_model.h"
#include <cmath>
#include <fmt/format.h>
#include <gmsh.h>
#include <map>
#include <set>
#include <string>

//-----------------------------------------------------------------------------
void fsai::mesh::GlottalChannel3dGeometry::bind(fsai::common::Parameters& p)
{
  p.add("channel.half_gap", half_gap,
        "rest half-gap, medial surface to the symmetry plane [m]");
  p.add("channel.subglottal", subglottal, "channel length below the fold [m]");
  p.add("channel.supraglottal", supraglottal,
        "channel length above the fold [m]");
  p.add("channel.h_gap", h_gap, "cell size at the medial surface [m]");
  p.add("channel.h_far", h_far, "cell size far from the glottis [m]");
  p.add("channel.transition", transition,
        "distance over which the cells grow from h_gap to h_far [m]");
}
//-----------------------------------------------------------------------------
void fsai::mesh::GlottalChannel3dGeometry::validate() const
{
  for (auto [name, v] : {std::pair{"half_gap", half_gap},
                         {"subglottal", subglottal},
                         {"supraglottal", supraglottal},
                         {"h_gap", h_gap},
                         {"h_far", h_far},
                         {"transition", transition}})
  {
    fsai::require_positive(std::string("--channel.") + name, v);
  }
  fsai::require(h_gap <= h_far, "--channel.h_gap", "<= --channel.h_far", h_gap);
  // A cell count bound: the glottal box alone holds ~ 10 mm³ / (0.12 h³)
  fsai::require(h_gap >= 0.05e-3, "--channel.h_gap",
                ">= 0.05 mm (a 3D mesh of millions of cells)", h_gap);
}
//-----------------------------------------------------------------------------
fsai::mesh::FluidSolidMeshes
fsai::mesh::glottal_channel_3d(MPI_Comm comm, const VocalFoldGeometry& g,
                               const GlottalChannel3dGeometry& c)
{
  g.validate();
  c.validate();
  const double xm = c.midplane(g);
  const double y0 = -c.subglottal, y1 = g.height + c.supraglottal;
  auto parts = build_parts_with_gmsh(
      comm, 3,
      [&]()
      {
        namespace occ = gmsh::model::occ;
        gmsh::model::add("glottal_channel_3d");
        const int channel = occ::addBox(0, y0, 0, xm, y1 - y0, g.length);
        const int fold = add_fold_body(g, 3);
        gmsh::vectorpair out;
        std::vector<gmsh::vectorpair> map;
        occ::fragment({{3, channel}}, {{3, fold}}, out, map);
        occ::synchronize();
        // Two volumes: the fold (the smaller) and the air around it
        std::vector<int> fluid, solid;
        if (out.size() == 2)
        {
          double v0, v1;
          occ::getMass(3, out[0].second, v0);
          occ::getMass(3, out[1].second, v1);
          solid.push_back(out[v0 < v1 ? 0 : 1].second);
          fluid.push_back(out[v0 < v1 ? 1 : 0].second);
        }
        if (fluid.size() != 1 or solid.size() != 1)
          throw std::runtime_error("3D glottal channel: unexpected fragments");
        const double tol = 1e-6 * g.length;
        const std::set<int> ff = tag_fluid_solid_3d(
            fluid[0], solid[0],
            [&](const std::array<double, 3>& c) -> std::string
            {
              return c[1] < y0 + tol   ? "inlet"
                     : c[1] > y1 - tol ? "outlet"
                     : c[0] > xm - tol ? "midplane"
                                       : "walls";
            });

        // In the air and on its boundary: h_gap around the medial surface
        // and the glottal slit (the fold's rounded medial corners
        // included), growing to h_far. Inside the fold: fold.h (its
        // surface is the interface's, at the air's sizes)
        namespace field = gmsh::model::mesh::field;
        const int box = field::add("Box");
        field::setNumber(box, "VIn", c.h_gap);
        field::setNumber(box, "VOut", c.h_far);
        field::setNumber(box, "XMin", g.depth - std::max(g.a, g.r_inf));
        field::setNumber(box, "XMax", xm);
        field::setNumber(box, "YMin", 0.0);
        field::setNumber(box, "YMax", g.height);
        field::setNumber(box, "ZMin", 0.0);
        field::setNumber(box, "ZMax", g.length);
        field::setNumber(box, "Thickness", c.transition);
        std::vector<double> air_faces(ff.begin(), ff.end()), air_curves;
        {
          gmsh::vectorpair b, e;
          for (int f : ff)
            b.push_back({2, f});
          gmsh::model::getBoundary(b, e, false, false, false);
          std::set<int> curves;
          for (auto [d, t] : e)
            curves.insert(std::abs(t));
          air_curves.assign(curves.begin(), curves.end());
        }
        const int in_air = field::add("Restrict");
        field::setNumber(in_air, "IField", box);
        field::setNumbers(in_air, "RegionsList", {double(fluid[0])});
        field::setNumbers(in_air, "FacesList", air_faces);
        field::setNumbers(in_air, "EdgesList", air_curves);
        const int fold_h = field::add("MathEval");
        field::setString(fold_h, "F", fmt::format("{:.17g}", g.h));
        const int in_fold = field::add("Restrict");
        field::setNumber(in_fold, "IField", fold_h);
        field::setNumbers(in_fold, "RegionsList", {double(solid[0])});
        const int size = field::add("Min");
        field::setNumbers(size, "FieldsList",
                          {double(in_air), double(in_fold)});
        field::setAsBackgroundMesh(size);
        gmsh::option::setNumber("Mesh.MeshSizeExtendFromBoundary", 0);
        gmsh::option::setNumber("Mesh.MeshSizeFromPoints", 0);
        gmsh::option::setNumber("Mesh.MeshSizeFromCurvature", 0);
        gmsh::model::mesh::generate(3);
      },
      {"fluid", "solid"});
  return {std::move(parts[0]), std::move(parts[1])};
}
