// Copyright (C) 2026 fsai developers
#include "glottis_channel.h"
#include "gmsh_model.h"
#include <common/errors.h>
#include <glottis/FoldProfile.h>
#include <gmsh.h>
#include <stdexcept>

std::vector<int>
fsai::mesh::add_fold_points(const glottis::FoldProfile& profile)
{
  const auto& g = profile.geometry();
  const auto& pts = profile.points();
  namespace geo = gmsh::model::geo;
  std::vector<int> tags = {geo::addPoint(g.fold_length, g.half_height, 0)};
  for (int i = int(pts.size()) - 3; i >= 2; i -= 2)
    tags.push_back(geo::addPoint(pts[i][0], pts[i][1], 0));
  tags.push_back(geo::addPoint(0, g.half_height, 0));
  return tags;
}

namespace
{
/// The channel (and with `with_fold` the fold's own surface, bounded by
/// the shared fold curve and its lateral attachment at y = H) in the
/// current gmsh model, meshed
void build_channel(const fsai::glottis::FoldProfile& profile,
                   const fsai::mesh::ChannelSizes& h, bool with_fold,
                   const std::vector<std::array<double, 2>>& curve = {})
{
  using namespace fsai::mesh;
  namespace geo = gmsh::model::geo;
  const auto& g = profile.geometry();
  gmsh::model::add("glottis_channel");
  const double H = g.half_height, x0 = -g.inlet_length,
               x1 = g.fold_length + g.outlet_length;
  const int p_in0 = geo::addPoint(x0, 0, 0);
  const int p_out0 = geo::addPoint(x1, 0, 0);
  const int p_out1 = geo::addPoint(x1, H, 0);
  // The fold surface, superior attachment to inferior (the domain
  // boundary runs counter-clockwise)
  std::vector<int> spline;
  if (curve.empty())
    spline = add_fold_points(profile);
  else
  {
    spline.push_back(geo::addPoint(g.fold_length, H, 0));
    for (auto it = curve.rbegin(); it != curve.rend(); ++it)
      spline.push_back(geo::addPoint((*it)[0], (*it)[1], 0));
    spline.push_back(geo::addPoint(0, H, 0));
  }
  const int p_sup = spline.front(), p_inf = spline.back();
  const int p_in1 = geo::addPoint(x0, H, 0);
  const int axis = geo::addLine(p_in0, p_out0);
  const int outlet = geo::addLine(p_out0, p_out1);
  const int wall_sup = geo::addLine(p_out1, p_sup);
  // A remeshed boundary is the old mesh's, straight between its nodes: a
  // spline through them would overshoot where the fold surface turns
  // sharply (at the attachments, onto the wall)
  const int fold
      = curve.empty() ? geo::addSpline(spline) : geo::addPolyline(spline);
  const int wall_inf = geo::addLine(p_inf, p_in1);
  const int inlet = geo::addLine(p_in1, p_in0);
  const int loop
      = geo::addCurveLoop({axis, outlet, wall_sup, fold, wall_inf, inlet});
  const int surface = geo::addPlaneSurface({loop});
  int attachment = -1, fold_surface = -1;
  if (with_fold)
  {
    attachment = geo::addLine(p_inf, p_sup);
    fold_surface
        = geo::addPlaneSurface({geo::addCurveLoop({fold, attachment})});
  }
  geo::synchronize();
  int id = 1;
  std::vector<std::pair<const char*, std::vector<int>>> groups
      = {{"inlet", {inlet}},
         {"outlet", {outlet}},
         {"axis", {axis}},
         {"wall", {wall_sup, wall_inf}},
         {"fold", {fold}}};
  if (with_fold)
    groups.push_back({"attachment", {attachment}});
  for (const auto& [name, tags] : groups)
  {
    gmsh::model::addPhysicalGroup(1, tags, id);
    gmsh::model::setPhysicalName(1, id++, name);
  }
  gmsh::model::addPhysicalGroup(2, {surface}, 1);
  gmsh::model::setPhysicalName(2, 1, "fluid");
  if (with_fold)
  {
    gmsh::model::addPhysicalGroup(2, {fold_surface}, 2);
    gmsh::model::setPhysicalName(2, 2, "fold");
  }
  size_near_curves({fold}, h.h_gap, h.h_far, h.grading, 1000,
                   h.fine_height > 0 ? SizeBand{{axis}, h.fine_height}
                                     : SizeBand{},
                   SizeBox{h.h_jet, {0, x1, 0, h.jet_height}, h.grading},
                   SizeBox{h.h_inlet, {x0, -2 * h.grading, 0, H}, h.grading});
  gmsh::option::setNumber("Mesh.Algorithm", 6);
  gmsh::model::mesh::generate(2);
}

void check_sizes(const fsai::glottis::FoldProfile& profile,
                 const fsai::mesh::ChannelSizes& h)
{
  const auto& g = profile.geometry();
  const double h_far = h.h_far, h_gap = h.h_gap, h_jet = h.h_jet;
  fsai::require(h_gap > 0 and h_gap <= g.rest_gap, "--fe.h_gap",
                "in (0, rest_gap]", h_gap);
  fsai::require(h_far >= h_gap and h_far <= g.half_height / 2, "--fe.h_far",
                "in [h_gap, half_height/2]", h_far);
  fsai::require(h_jet == 0 or (h_jet >= h_gap and h_jet <= h_far), "--fe.h_jet",
                "0 or in [h_gap, h_far]", h_jet);
  fsai::require(h.h_inlet == 0
                    or (h.h_inlet >= h_far and h.h_inlet <= g.half_height / 2),
                "--fe.h_inlet", "0 or in [h_far, half_height/2]", h.h_inlet);
  fsai::require(h.h_inlet == 0 or 3 * h.grading < g.inlet_length,
                "--fe.grading", "< inlet_length / 3 with --fe.h_inlet",
                h.grading);
}
} // namespace

fsai::mesh::MeshData
fsai::mesh::glottis_channel(MPI_Comm comm, const glottis::FoldProfile& profile,
                            const ChannelSizes& sizes)
{
  check_sizes(profile, sizes);
  return build_with_gmsh(comm, 2,
                         [&]() { build_channel(profile, sizes, false); });
}

fsai::mesh::MeshData
fsai::mesh::glottis_channel(MPI_Comm comm, const glottis::FoldProfile& profile,
                            const ChannelSizes& sizes,
                            const std::vector<std::array<double, 2>>& curve)
{
  check_sizes(profile, sizes);
  fsai::require(curve.size() >= 2, "remeshed fold curve", ">= 2 points",
                double(curve.size()));
  return build_with_gmsh(
      comm, 2, [&]() { build_channel(profile, sizes, false, curve); });
}

fsai::mesh::FluidSolidMeshes
fsai::mesh::glottis_channel_and_fold(MPI_Comm comm,
                                     const glottis::FoldProfile& profile,
                                     const ChannelSizes& sizes)
{
  // The fold's mesh shares the channel's size field, which has no fine
  // band, jet box or coarser inlet here
  if (sizes.fine_height != 0 or sizes.h_jet != 0 or sizes.h_inlet != 0)
    throw std::invalid_argument("glottis_channel_and_fold: fine_height, "
                                "h_jet and h_inlet must be 0");
  check_sizes(profile, sizes);
  auto parts = build_parts_with_gmsh(
      comm, 2, [&]() { build_channel(profile, sizes, true); },
      {"fluid", "fold"});
  return {std::move(parts[0]), std::move(parts[1])};
}
