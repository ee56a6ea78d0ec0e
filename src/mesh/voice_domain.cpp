// Copyright (C) 2026 fsai developers
#include "voice_domain.h"
#include "glottis_channel.h"
#include "gmsh_model.h"
#include <algorithm>
#include <cmath>
#include <common/Parameters.h>
#include <common/errors.h>
#include <glottis/FoldProfile.h>
#include <gmsh.h>

//-----------------------------------------------------------------------------
void fsai::mesh::VoiceDomainGeometry::bind(fsai::common::Parameters& p)
{
  p.add("voice.radius", radius, "radius of the radiation region [m]");
  p.add("voice.h", h, "acoustic mesh size away from the walls [m]");
  p.add("voice.h_fold", h_fold, "acoustic mesh size on the fold [m]");
  p.add("voice.growth", growth,
        "growth of the acoustic mesh size with the distance to the fold");
  p.add("voice.cells_across", cells_across,
        "minimum cells across a tract half-width");
}
//-----------------------------------------------------------------------------
void fsai::mesh::VoiceDomainGeometry::validate() const
{
  fsai::require_positive("--voice.radius", radius);
  fsai::require(layer >= 0, "absorbing layer", ">= 0", layer);
  fsai::require_positive("--voice.h", h);
  fsai::require_positive("--voice.h_fold", h_fold);
  fsai::require(h_fold <= h, "--voice.h_fold", "<= --voice.h", h_fold);
  fsai::require_range("--voice.growth", growth, 0.05, 2.0);
  fsai::require_range("--voice.cells_across", cells_across, 0.5, 20.0);
}
//-----------------------------------------------------------------------------
fsai::mesh::AreaFunction
fsai::mesh::voice_tract(const AreaFunction& vowel,
                        const glottis::FoldProfile& profile)
{
  const auto& g = profile.geometry();
  const double Lc = g.outlet_length, A_ch = 2 * g.half_height * g.depth;
  fsai::require(vowel.length() > Lc + 0.01, "area function length",
                "> the supraglottal channel + 1 cm", vowel.length());
  AreaFunction t;
  t.source
      = vowel.source
        + fmt::format(" with its first {:.1f} mm replaced by the flow domain's "
                      "channel ({:.2f} cm^2)",
                      1e3 * Lc, 1e4 * A_ch);
  // The channel as 1 mm sections, so the smooth reading (linear between
  // section centres) stays A_ch up to 0.5 mm before its end
  const int n = std::max(1, int(std::round(Lc / 1e-3)));
  for (int i = 1; i <= n; ++i)
  {
    t.x_end.push_back(Lc * i / n);
    t.area.push_back(A_ch);
  }
  for (std::size_t k = 0; k < vowel.size(); ++k)
  {
    if (vowel.x_end[k] > Lc + 1e-9)
    {
      t.x_end.push_back(vowel.x_end[k]);
      t.area.push_back(vowel.area[k]);
    }
  }
  return t;
}
//-----------------------------------------------------------------------------
fsai::mesh::AreaFunction
fsai::mesh::voice_subglottal(const glottis::FoldProfile& profile)
{
  const auto& g = profile.geometry();
  const auto& pts = profile.points();
  AreaFunction a;
  a.source = "subglottal duct and glottis at rest";
  const double Ld = g.inlet_length;
  const int nd = std::max(1, int(std::round(Ld / 1e-3)));
  for (int i = 1; i <= nd; ++i)
  {
    a.x_end.push_back(Ld * i / nd);
    a.area.push_back(2 * g.half_height * g.depth);
  }
  // Glottis: the surface's lowest y over each section's centre (the
  // polyline need not be monotone in x at the rounded edges)
  const double T = g.fold_length, dx = 0.05e-3;
  const int n = std::max(1, int(std::round(T / dx)));
  for (int i = 0; i < n; ++i)
  {
    const double xc = T * (i + 0.5) / n;
    double y = g.half_height;
    for (std::size_t k = 0; k + 1 < pts.size(); ++k)
    {
      const auto& p = pts[k];
      const auto& q = pts[k + 1];
      if ((p[0] - xc) * (q[0] - xc) <= 0.0 and p[0] != q[0])
        y = std::min(y, p[1] + (q[1] - p[1]) * (xc - p[0]) / (q[0] - p[0]));
    }
    a.x_end.push_back(Ld + T * (i + 1) / n);
    a.area.push_back(2 * std::max(y, 1e-9) * g.depth);
  }
  return a;
}
//-----------------------------------------------------------------------------
fsai::mesh::MeshData
fsai::mesh::voice_domain(MPI_Comm comm, const glottis::FoldProfile& profile,
                         const AreaFunction& tract,
                         const VoiceDomainGeometry& vg)
{
  vg.validate();
  const auto& g = profile.geometry();
  const double H = g.half_height, T = g.fold_length, x0 = -g.inlet_length,
               x1 = T + vg.channel, xL = T + tract.length(), R = vg.radius,
               Rl = R + vg.layer;
  // Planar half-width of the tract at tract coordinate s
  auto r = [&](double s) { return 0.5 * tract.area_at(s, true) / g.depth; };
  const double r_lips = r(tract.length());
  fsai::require(!vg.radiation_region or R > 1.5 * r_lips, "--voice.radius",
                "larger than the mouth half-width", R);
  fsai::require(vg.h_fold <= 0.5 * g.rest_gap, "--voice.h_fold",
                "<= half the rest gap", vg.h_fold);
  fsai::require(vg.channel > 0 or r(0) < 0.9 * H, "tract area at the glottis",
                "a half-width below 0.9 of the channel's half-height", r(0));

  // Mesh size: the callback is the only size source (fine at the fold,
  // several cells across every tract section, h elsewhere)
  const auto& pts = profile.points();
  auto size = [&, pts](int, int, double x, double y, double) -> double
  {
    double d2 = 1e300;
    for (const auto& p : pts)
      d2 = std::min(d2, (x - p[0]) * (x - p[0]) + (y - p[1]) * (y - p[1]));
    double s = std::min(vg.h, vg.h_fold + vg.growth * std::sqrt(d2));
    if (x >= x1 - 2 * H and x <= xL)
    {
      const double sx = std::clamp(x - T, vg.channel, tract.length());
      s = std::min(s, std::max(vg.h_fold, r(sx) / vg.cells_across));
    }
    else if (x > xL)
    {
      const double d = std::hypot(x - xL, y);
      s = std::min(s, r_lips / vg.cells_across + 0.5 * d);
    }
    return s;
  };

  return build_with_gmsh(
      comm, 2,
      [&]()
      {
        namespace geo = gmsh::model::geo;
        gmsh::model::add("voice_domain");
        // Boundary, counter-clockwise from the inlet's axis end
        const int p_in0 = geo::addPoint(x0, 0, 0);
        const bool open = vg.radiation_region;
        const int p_c = geo::addPoint(xL, 0, 0);
        const int p_ax1 = open ? geo::addPoint(xL + R, 0, 0) : p_c;
        const int p_top = open ? geo::addPoint(xL, R, 0) : -1;
        std::vector<int> tract_pts = {geo::addPoint(xL, r_lips, 0)};
        for (std::size_t k = tract.size(); k-- > 0;)
        {
          const double s = tract.x_centre(k);
          if (s > vg.channel + 1e-4 and s < tract.length() - 1e-4)
            tract_pts.push_back(geo::addPoint(T + s, r(s), 0));
        }
        tract_pts.push_back(geo::addPoint(x1, r(vg.channel), 0));
        // The step up to the channel's wall, or, for a tract from the
        // glottis (channel 0), to the fold's superior attachment (T, H)
        const int p_out1 = vg.channel > 0 ? geo::addPoint(x1, H, 0) : -1;
        const std::vector<int> spline = add_fold_points(profile);
        const int p_sup = spline.front(), p_inf = spline.back();
        const int p_in1 = geo::addPoint(x0, H, 0);

        const int axis = geo::addLine(p_in0, p_ax1);
        // The outer arc and the baffle, or the lip opening
        const int arc = open ? geo::addCircleArc(p_ax1, p_c, p_top)
                             : geo::addLine(p_c, tract_pts.front());
        std::vector<int> walls;
        if (open)
          walls.push_back(geo::addLine(p_top, tract_pts.front()));
        for (std::size_t i = 0; i + 1 < tract_pts.size(); ++i)
          walls.push_back(geo::addLine(tract_pts[i], tract_pts[i + 1]));
        if (p_out1 > 0)
        {
          walls.push_back(geo::addLine(tract_pts.back(), p_out1));
          walls.push_back(geo::addLine(p_out1, p_sup));
        }
        else
          walls.push_back(geo::addLine(tract_pts.back(), p_sup));
        const int fold = geo::addSpline(spline);
        const int wall_inf = geo::addLine(p_inf, p_in1);
        walls.push_back(wall_inf);
        const int inlet = geo::addLine(p_in1, p_in0);
        std::vector<int> loop = {axis, arc};
        loop.insert(loop.end(), walls.begin(), walls.end() - 1);
        loop.insert(loop.end(), {fold, wall_inf, inlet});
        const int air = geo::addPlaneSurface({geo::addCurveLoop(loop)});
        std::vector<int> axes = {axis}, outer = {arc};
        int layer = -1;
        if (open and vg.layer > 0)
        {
          // Annulus R < |x − x_L| < R + d: the absorbing layer
          const int q_ax = geo::addPoint(xL + Rl, 0, 0);
          const int q_top = geo::addPoint(xL, Rl, 0);
          const int l_axis = geo::addLine(p_ax1, q_ax);
          const int l_arc = geo::addCircleArc(q_ax, p_c, q_top);
          const int l_baffle = geo::addLine(q_top, p_top);
          layer = geo::addPlaneSurface(
              {geo::addCurveLoop({l_axis, l_arc, l_baffle, -arc})});
          axes.push_back(l_axis);
          walls.push_back(l_baffle);
          outer = {l_arc};
        }
        geo::synchronize();
        int id = 1;
        for (auto [name, tags] :
             {std::pair<const char*, std::vector<int>>{"inlet", {inlet}},
              {"axis", axes},
              {"wall", walls},
              {"fold", {fold}},
              {open ? "radiation" : "lips", outer}})
        {
          gmsh::model::addPhysicalGroup(1, tags, id);
          gmsh::model::setPhysicalName(1, id++, name);
        }
        gmsh::model::addPhysicalGroup(2, {air}, 1);
        gmsh::model::setPhysicalName(2, 1, "air");
        if (layer > 0)
        {
          gmsh::model::addPhysicalGroup(2, {layer}, 2);
          gmsh::model::setPhysicalName(2, 2, "layer");
        }
        gmsh::option::setNumber("Mesh.MeshSizeExtendFromBoundary", 0);
        gmsh::option::setNumber("Mesh.MeshSizeFromPoints", 0);
        gmsh::option::setNumber("Mesh.MeshSizeFromCurvature", 0);
        gmsh::model::mesh::setSizeCallback(size);
        gmsh::option::setNumber("Mesh.Algorithm", 6);
        gmsh::model::mesh::generate(2);
        gmsh::model::mesh::removeSizeCallback();
      });
}
