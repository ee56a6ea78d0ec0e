// Copyright (C) 2026 fsai developers
#include "FlowChannel.h"
#include "FlowGlottis.h"
#include <algorithm>
#include <cmath>
#include <common/errors.h>
#include <common/log.h>
#include <common/mpi_gather.h>
#include <common/timer.h>
#include <dolfinx/fem/utils.h>
#include <dolfinx/mesh/utils.h>
#include <mesh/TriangleField.h>
#include <mesh/glottis_channel.h>

namespace
{
// Midpoint of triangle c in the mesh's current coordinates
std::array<double, 2> cell_midpoint(const dolfinx::mesh::Mesh& mesh,
                                    std::int32_t c)
{
  const auto x = mesh.geometry().x();
  std::array<double, 2> mid{0, 0};
  for (auto n : mesh.geometry().dofmap().links(c))
  {
    mid[0] += x[3 * n] / 3;
    mid[1] += x[3 * n + 1] / 3;
  }
  return mid;
}
} // namespace

double fsai::glottis::boundary_lift(double g, double g_min)
{
  // Lifting the whole surface keeps its shape: an earlier per-point clamp
  // flattened the superior edge round onto the axis, and the cells under
  // it, compressed 10× at one column and 20× at the next, inverted at
  // p_sub = 1200 Pa. The part of the gap the fold occupies is porous.
  const double b = g_min;
  if (g >= g_min + b)
    return 0.0;
  return g_min + b * std::exp((g - g_min - b) / b) - g;
}
//-----------------------------------------------------------------------------
fsai::glottis::FlowChannel::FlowChannel(
    MPI_Comm comm, const FoldProfile& profile, const FlowGlottisParameters& p,
    fluid::FluidParameters fp, const ale::MeshMotionParameters& ap,
    const std::vector<std::array<double, 2>>& curve)
    : _comm(comm), _profile(profile), _porous_ramp(p.porous_ramp),
      _chi_floor(
          fp.sigma_p > 0 ? std::min(
              1.0, 0.01 * fp.rho
                       / (fp.sigma_p
                          * (p.porous_floor_dt > 0 ? p.porous_floor_dt : p.dt)))
                         : 1.0)
{
  p.validate();
  const auto& g = profile.geometry();
  fsai::require(p.g_min < g.rest_gap, "--closure.g_min", "< the rest gap",
                p.g_min);
  _mesh = curve.empty() ? mesh::glottis_channel(comm, profile, p.sizes)
                        : mesh::glottis_channel(comm, profile, p.sizes, curve);
  auto find = [&](const char* name)
  { return _mesh.facet_tags->find(_mesh.facet_tag(name)); };
  _fold_facets = find("fold");
  _inlet_facets = find("inlet");
  fluid::FluidBoundaries fb;
  fb.inlet_penalty = _inlet_facets;
  fb.outlet = find("outlet");
  fb.walls = find("wall");
  fb.walls.insert(fb.walls.end(), _fold_facets.begin(), _fold_facets.end());
  fb.symmetry = find("axis");
  fp.p_in = 0; // set_inlet_pressure() ramps it
  _flow = std::make_unique<fluid::FluidSolver>(_mesh.mesh, fb, fp, p.dt);
  ale::MeshMotionBoundaries mb;
  mb.interface = _fold_facets;
  mb.fixed = _inlet_facets;
  for (const char* name : {"outlet", "wall"})
  {
    auto f = find(name);
    mb.fixed.insert(mb.fixed.end(), f.begin(), f.end());
  }
  const auto V = _flow->velocity_space();
  _F = std::make_shared<dolfinx::fem::Function<double>>(V);
  _fold_dofs = dolfinx::fem::locate_dofs_topological(*V, 1, _fold_facets);
  const std::vector<double> X = V->tabulate_dof_coordinates(false);
  _X_ref = X;
  for (auto d : _fold_dofs)
    _fold_X.push_back({X[3 * d], X[3 * d + 1]});
  {
    const auto Q = _flow->pressure()->function_space();
    const std::int32_t owned = Q->dofmap()->index_map->size_local();
    const std::vector<double> XQ = Q->tabulate_dof_coordinates(false);
    for (auto d : dolfinx::fem::locate_dofs_topological(*Q, 1, _fold_facets))
      if (d < owned)
      {
        _fold_p_dofs.push_back(d);
        _fold_p_X.push_back({XQ[3 * d], XQ[3 * d + 1]});
      }
  }
  mb.slip = {{1, fb.symmetry}};
  if (p.gap_motion == "algebraic")
  {
    // The lower envelope of the fold boundary near the axis as the mesh
    // has it: every fold node (all ranks) whose reference height is
    // within rest gap + R of the axis, by x. Each node below that envelope
    // hangs from the boundary segment above it (column top = linear
    // interpolation of the two boundary nodes, exactly the discrete
    // boundary, so no node can pass it); every rank tests its owned and
    // ghost dofs by the same geometric rule
    const double y_lim = g.rest_gap + p.gap_columns * g.medial_radius;
    std::vector<double> loc;
    for (auto& X : _fold_X)
      if (X[1] <= 1.5 * y_lim)
        loc.insert(loc.end(), {X[0], X[1]});
    const std::vector<double> all = common::allgather(comm, loc);
    std::vector<std::array<double, 2>> env;
    for (std::size_t k = 0; k + 1 < all.size(); k += 2)
      env.push_back({all[k], all[k + 1]});
    std::sort(env.begin(), env.end());
    env.erase(std::unique(env.begin(), env.end()), env.end());
    const std::int32_t nblocks = V->dofmap()->index_map->size_local()
                                 + V->dofmap()->index_map->num_ghosts();
    for (std::int32_t d = 0; d < nblocks and env.size() >= 2; ++d)
    {
      const double x = _X_ref[3 * d], y = _X_ref[3 * d + 1];
      auto it = std::upper_bound(env.begin(), env.end(),
                                 std::array<double, 2>{x, 1e300});
      if (it == env.begin() or it == env.end())
        continue;
      const auto& A = *(it - 1);
      const auto& B = *it;
      const double t = B[0] > A[0] ? (x - A[0]) / (B[0] - A[0]) : 0.0;
      const double yc = (1 - t) * A[1] + t * B[1];
      if (yc <= y_lim and y < yc - 1e-3 * g.rest_gap)
      {
        _gap_dofs.push_back(d);
        _gap_nodes.push_back({A, B});
        _gap_t.push_back(t);
        _gap_fraction.push_back(y / yc);
      }
    }
    mb.prescribed = _gap_dofs;
  }
  _motion = std::make_unique<ale::MeshMotion>(_mesh.mesh,
                                              _flow->velocity_space(), mb, ap);
  // Cells that can become porous: reference midpoint within the fold's
  // x-extent, below the attachment band
  const auto& mesh = *_mesh.mesh;
  const std::int32_t ncells = mesh.topology().index_map(2)->size_local()
                              + mesh.topology().index_map(2)->num_ghosts();
  for (std::int32_t c = 0; c < ncells; ++c)
  {
    const auto [cx, cy] = cell_midpoint(mesh, c);
    if (cx > 0 and cx < g.fold_length and cy < g.half_height - g.taper)
      _candidates.push_back(c);
  }
  // Upstream fold facets: midpoint (reference configuration) x < medial_x
  {
    auto xg = dolfinx::mesh::entities_to_geometry(mesh, 1, _fold_facets, false);
    const auto x = mesh.geometry().x();
    for (std::size_t i = 0; i < _fold_facets.size(); ++i)
      if (0.5 * (x[3 * xg[2 * i]] + x[3 * xg[2 * i + 1]]) < g.medial_x)
        _upstream_fold_facets.push_back(_fold_facets[i]);
  }
}
//-----------------------------------------------------------------------------
std::int64_t fsai::glottis::FlowChannel::cells() const
{
  return _mesh.mesh->topology().index_map(2)->size_global();
}
//-----------------------------------------------------------------------------
std::vector<fsai::io::TimeSeriesWriter::Field>
fsai::glottis::FlowChannel::fields() const
{
  return {_flow->velocity(), _flow->pressure(), _flow->porous_field(),
          _motion->displacement()};
}
//-----------------------------------------------------------------------------
std::int64_t fsai::glottis::FlowChannel::describe() const
{
  const auto per_rank = cells_per_rank();
  const std::int64_t dofs = _flow->dofs();
  log::info("FE flow: {} cells ({}–{} per rank), {} dofs", cells(), per_rank[0],
            per_rank[1], dofs);
  return dofs;
}
//-----------------------------------------------------------------------------
std::array<std::int64_t, 2> fsai::glottis::FlowChannel::cells_per_rank() const
{
  const std::int64_t n = _mesh.mesh->topology().index_map(2)->size_local();
  std::array<std::int64_t, 2> r{-n, n};
  MPI_Allreduce(MPI_IN_PLACE, r.data(), 2, MPI_INT64_T, MPI_MAX, _comm);
  return {-r[0], r[1]};
}
//-----------------------------------------------------------------------------
void fsai::glottis::FlowChannel::set_interface(const SurfaceDisplacement& u)
{
  auto a = _motion->interface_displacement().x()->mutable_array();
  for (std::size_t i = 0; i < _fold_dofs.size(); ++i)
  {
    const auto ui = u(_fold_X[i]);
    a[2 * _fold_dofs[i]] = ui[0];
    a[2 * _fold_dofs[i] + 1] = ui[1];
  }
  // Algebraic gap motion: the column of nodes under the boundary point
  // above (between boundary nodes A and B) moves with it horizontally (the axis
  // nodes slide along the axis) and is compressed vertically, a node at height
  // fraction s = y/y_s keeping s. The map (x, s) → (x + U_x(x), s Y(x)), Y the
  // new surface height, has Jacobian (1 + U_x') Y > 0: no node passes the
  // boundary above it however close the fold comes. (Shifting x by s U_x
  // instead shears the columns: with the fold rotated by φ they tilt to a slope
  // Y/U_x below the surface's φ and the cells under the superior edge invert.)
  for (std::size_t i = 0; i < _gap_dofs.size(); ++i)
  {
    const auto ua = u(_gap_nodes[i][0]);
    const auto ub = u(_gap_nodes[i][1]);
    const double t = _gap_t[i];
    a[2 * _gap_dofs[i]] = (1 - t) * ua[0] + t * ub[0];
    a[2 * _gap_dofs[i] + 1] = _gap_fraction[i] * ((1 - t) * ua[1] + t * ub[1]);
  }
}
//-----------------------------------------------------------------------------
void fsai::glottis::FlowChannel::set_wall_velocity()
{
  _motion->velocity(_flow->mesh_velocity(), _flow->dt(), _flow->dt_previous());
  auto w = _flow->mesh_velocity().x()->array();
  auto gw = _flow->wall_velocity().x()->mutable_array();
  for (auto d : _fold_dofs)
    for (int k = 0; k < 2; ++k)
      gw[2 * d + k] = w[2 * d + k];
}
//-----------------------------------------------------------------------------
void fsai::glottis::FlowChannel::mark_porous(
    const std::vector<std::array<double, 2>>& outline,
    const ToOutline& to_outline)
{
  // A cell's porous term stops its flow once σ_P χ Δt/ρ ≫ 1 (G4). Switched
  // cell-wise (δ = 0), or ramped linearly in χ, the last cell of the
  // throat opens (or the first closes) within one step: σ_P Δt/ρ ≈ 170, so
  // any χ above 1 % is a wall. That step's pressure impulse is the
  // one-step spike of the glottal flow at closing and reopening
  // (bench/glottis_clicks.py). Ramped geometrically, the cell's resistance
  // grows by the same factor per µm of depth from negligible (σ_P χ Δt/ρ =
  // 0.01) to σ_P, so the throat opens over the steps the fold takes to
  // rise by δ.
  common::ScopedTimer timer("glottis: porous marking");
  auto& chi = _flow->porous_indicator();
  auto c_arr = chi.x()->mutable_array();
  const auto dofmap = chi.function_space()->dofmap();
  const double ramp = _porous_ramp;
  // Beyond ramp/2 of the outline s is 0 or 1: distances exact within it
  const PolygonIndex fold(outline, ramp / 2);
  for (auto c : _candidates)
  {
    const auto X = to_outline(cell_midpoint(*_mesh.mesh, c));
    double x = 0;
    if (ramp > 0)
    {
      const double s
          = std::clamp(0.5 + fold.signed_distance(X) / ramp, 0.0, 1.0);
      x = s > 0 ? std::pow(_chi_floor, 1 - s) : 0.0;
    }
    else
      x = fold.contains(X) ? 1.0 : 0.0;
    c_arr[dofmap->cell_dofs(c)[0]] = x;
  }
}
//-----------------------------------------------------------------------------
void fsai::glottis::FlowChannel::solve_flow()
{
  _flow->restore_state();
  _flow->step();
}
//-----------------------------------------------------------------------------
std::vector<fsai::glottis::FlowChannel::NodalForce>
fsai::glottis::FlowChannel::fold_forces()
{
  _flow->nodal_forces(_fold_facets, *_F);
  const double Lg = _profile.geometry().depth;
  const auto F = _F->x()->array();
  const std::int32_t owned
      = _flow->velocity_space()->dofmap()->index_map->size_local();
  std::vector<NodalForce> out;
  for (std::size_t i = 0; i < _fold_dofs.size(); ++i)
  {
    const auto d = _fold_dofs[i];
    if (d < owned)
      out.push_back({_fold_X[i], {Lg * F[2 * d], Lg * F[2 * d + 1]}});
  }
  return out;
}
//-----------------------------------------------------------------------------
std::vector<double> fsai::glottis::FlowChannel::fold_pressure() const
{
  const auto p = _flow->pressure()->x()->array();
  std::vector<double> out;
  out.reserve(3 * _fold_p_dofs.size());
  for (std::size_t i = 0; i < _fold_p_dofs.size(); ++i)
    out.insert(out.end(),
               {_fold_p_X[i][0], _fold_p_X[i][1], p[_fold_p_dofs[i]]});
  return out;
}
//-----------------------------------------------------------------------------
std::vector<std::array<double, 2>>
fsai::glottis::FlowChannel::fold_boundary() const
{
  const auto d = _motion->displacement()->x()->array();
  const std::int32_t owned
      = _flow->velocity_space()->dofmap()->index_map->size_local();
  std::vector<std::array<double, 2>> out;
  for (std::size_t i = 0; i < _fold_dofs.size(); ++i)
  {
    const auto k = _fold_dofs[i];
    if (k < owned)
      out.push_back({_fold_X[i][0] + d[2 * k], _fold_X[i][1] + d[2 * k + 1]});
  }
  return out;
}
//-----------------------------------------------------------------------------
std::vector<std::array<std::array<double, 2>, 2>>
fsai::glottis::FlowChannel::fold_nodes() const
{
  const auto x = fold_boundary();
  std::vector<std::array<std::array<double, 2>, 2>> out;
  const std::int32_t owned
      = _flow->velocity_space()->dofmap()->index_map->size_local();
  for (std::size_t i = 0, k = 0; i < _fold_dofs.size(); ++i)
    if (_fold_dofs[i] < owned)
      out.push_back({_fold_X[i], x[k++]});
  return out;
}
//-----------------------------------------------------------------------------
std::array<double, 4>
fsai::glottis::FlowChannel::transfer_from(FlowChannel& old)
{
  const auto before = old.flow_rates();
  // Velocity, its history and the nodes' previous positions relative to
  // the current ones, x^{n−1} − x^n = d^{n−1} − d^n, on the old mesh as it
  // stands (all ranks' cells on every rank)
  const auto& of = old.flow();
  const auto [d_n, d_nn] = old.motion().history();
  std::vector<double> back(d_n.size());
  for (std::size_t i = 0; i < back.size(); ++i)
    back[i] = d_nn[i] - d_n[i];
  const auto fv = mesh::TriangleField::gather(_comm, *of.velocity_space(),
                                              {of.velocity()->x()->array(),
                                               of.velocity_nn()->x()->array(),
                                               std::span<const double>(back)});
  const auto fp = mesh::TriangleField::gather(
      _comm, *of.pressure()->function_space(), {of.pressure()->x()->array()});
  // At this mesh's nodes (it is at its reference, the moved fold)
  const std::vector<double> XV
      = _flow->velocity_space()->tabulate_dof_coordinates(false);
  const std::size_t nv = XV.size() / 3;
  std::vector<double> v(2 * nv), vnn(2 * nv), dnn(2 * nv);
  for (std::size_t i = 0; i < nv; ++i)
  {
    const auto a = fv({XV[3 * i], XV[3 * i + 1]});
    for (int k = 0; k < 2; ++k)
      v[2 * i + k] = a[k], vnn[2 * i + k] = a[2 + k], dnn[2 * i + k] = a[4 + k];
  }
  const std::vector<double> XQ
      = _flow->pressure()->function_space()->tabulate_dof_coordinates(false);
  std::vector<double> p(XQ.size() / 3);
  for (std::size_t i = 0; i < p.size(); ++i)
    p[i] = fp({XQ[3 * i], XQ[3 * i + 1]})[0];
  _flow->set_state(v, vnn, p, of.time(), std::max(of.steps(), 1),
                   of.dt_previous());
  _motion->continue_from(dnn);
  // The mesh velocity and the fold wall's velocity of the accepted step
  // (the flow rates through moving fold walls use them)
  auto w = _flow->mesh_velocity().x()->mutable_array();
  const auto w_old = mesh::TriangleField::gather(
      _comm, *of.velocity_space(), {old._flow->mesh_velocity().x()->array()});
  for (std::size_t i = 0; i < nv; ++i)
  {
    const auto a = w_old({XV[3 * i], XV[3 * i + 1]});
    w[2 * i] = a[0], w[2 * i + 1] = a[1];
  }
  auto gw = _flow->wall_velocity().x()->mutable_array();
  for (auto d : _fold_dofs)
    for (int k = 0; k < 2; ++k)
      gw[2 * d + k] = w[2 * d + k];
  const auto after = flow_rates();
  return {before[1], after[1], before[0], after[0]};
}
//-----------------------------------------------------------------------------
std::array<double, 2> fsai::glottis::FlowChannel::flow_rates()
{
  // The inlet flux also carries the air that the moving inferior surface
  // displaces (spikes at the closing instants, a false "leakage"). With
  // div v = 0, the flux through the section is the inlet flux minus the
  // flux through the upstream fold wall, where v equals the mesh velocity of
  // the actual fluid boundary (held at g_min near the axis, which a rigid-
  // surface correction gets wrong). The section moves with the mesh there;
  // the axis is a slip line, so this differs from a fixed section only by
  // the mesh's horizontal motion near the axis.
  const double depth2 = 2 * _profile.geometry().depth;
  const double Q_inlet = -depth2 * _flow->flow_rate(_inlet_facets);
  return {Q_inlet, Q_inlet - depth2 * _flow->flow_rate(_upstream_fold_facets)};
}
//-----------------------------------------------------------------------------
void fsai::glottis::FlowChannel::save(io::RankState& state) const
{
  _flow->save(state, "flow.");
  _motion->save(state, "ale.");
}
//-----------------------------------------------------------------------------
void fsai::glottis::FlowChannel::load(const std::vector<io::RankState>& ranks)
{
  _flow->load(ranks, "flow.");
  _motion->load(ranks, "ale.");
}
//-----------------------------------------------------------------------------
void fsai::glottis::FlowChannel::rewind()
{
  _flow->restore_state();
  _motion->rewind();
}
