// Copyright (C) 2026 fsai developers
#include "ElasticFlowGlottis.h"
#include "waveform.h"
#include <algorithm>
#include <cmath>
#include <common/bdf.h>
#include <common/errors.h>
#include <common/log.h>
#include <common/mpi_gather.h>
#include <common/timer.h>
#include <fmt/format.h>
#include <io/RunSummary.h>
#include <io/TimeSeriesWriter.h>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <tuple>

namespace
{
// Linear interpolation at s of the values v(k) given at the sorted nodes
// s_k (constant beyond the ends)
template <typename V>
auto interpolate(const std::vector<double>& s_k, double s, V v)
{
  auto it = std::upper_bound(s_k.begin(), s_k.end(), s);
  if (it == s_k.begin())
    return v(0);
  if (it == s_k.end())
    return v(s_k.size() - 1);
  const std::size_t j = std::size_t(it - s_k.begin());
  const double len = s_k[j] - s_k[j - 1];
  const double f = len > 0 ? (s - s_k[j - 1]) / len : 0.0;
  auto a = v(j - 1);
  const auto b = v(j);
  for (std::size_t c = 0; c < a.size(); ++c)
    a[c] += f * (b[c] - a[c]);
  return a;
}
} // namespace

fsai::glottis::ElasticFlowGlottis::ElasticFlowGlottis(
    MPI_Comm comm, const FoldProfile& profile, const ElasticFoldParameters& ep,
    const ContactParameters& contact, const FlowGlottisParameters& p,
    fluid::FluidParameters fp, const ale::MeshMotionParameters& ap,
    const coupling::CouplingParameters& cp, const std::string& coupling_csv,
    std::size_t coupling_rows_kept)
    : _comm(comm), _profile(profile), _par(p),
      _fold(comm, profile, ep, contact, p.dt), _fp(fp), _ap(ap),
      _channel(std::make_unique<FlowChannel>(comm, profile, p, fp, ap)),
      _explicit(ep.explicit_coupling(true)),
      _loop(comm, elastic_coupling_parameters(_explicit, cp), coupling_csv,
            coupling_rows_kept)
{
  for (const auto& X : _fold.surface_reference())
  {
    _s.push_back(_profile.arc_length(X));
    _w.push_back(_profile.weight(X));
  }
  fsai::require(std::is_sorted(_s.begin(), _s.end()),
                "elastic fold: surface points", "ordered by arc length",
                "unordered");
}
//-----------------------------------------------------------------------------
double
fsai::glottis::ElasticFlowGlottis::arc_length(const std::array<double, 2>& X)
{
  auto [it, added] = _arc_cache.try_emplace(X, 0.0);
  if (!added)
    return it->second;
  if (_remesh.count == 0)
    return it->second = _profile.arc_length(X);
  // Remeshed: the arc length of the nearest point of the boundary as it was
  // meshed (linear between its points), the attachments (on the wall, not
  // in the curve) at its ends
  const auto& g = _profile.geometry();
  const auto& c = _remesh.curve;
  const auto& cs = _remesh.s;
  auto n = nearest_on_polyline(c, X);
  double s = cs[n.k] + n.t * (cs[n.k + 1] - cs[n.k]);
  for (const auto& [a, b, sa, sb] :
       {std::tuple{std::array<double, 2>{0, g.half_height}, c.front(), 0.0,
                   cs.front()},
        std::tuple{c.back(),
                   std::array<double, 2>{g.fold_length, g.half_height},
                   cs.back(), _s.back()}})
  {
    const auto e = nearest_on_polyline({a, b}, X);
    if (e.d2 < n.d2)
      n = e, s = sa + e.t * (sb - sa);
  }
  return it->second = s;
}
//-----------------------------------------------------------------------------
std::vector<double> fsai::glottis::ElasticFlowGlottis::local_lifts(
    const std::vector<std::array<double, 2>>& x) const
{
  // l(s_k) = max_j boundary_lift(y_j) exp(−((s_k − s_j)/σ)²), σ = R/2:
  // every point keeps at least its own lift (so stays above g_min), and
  // the lift fades over about a millimetre along the surface
  const double sigma = 0.5 * _profile.geometry().medial_radius;
  std::vector<double> l(x.size(), 0.0);
  for (std::size_t j = 0; j < x.size(); ++j)
  {
    const double lj = boundary_lift(x[j][1], _par.g_min);
    if (lj <= 0)
      continue;
    for (std::size_t k = 0; k < x.size(); ++k)
    {
      const double z = (_s[k] - _s[j]) / sigma;
      if (z * z < 40)
        l[k] = std::max(l[k], lj * std::exp(-z * z));
    }
  }
  return l;
}
//-----------------------------------------------------------------------------
void fsai::glottis::keep_out_of_wedges(std::vector<std::array<double, 2>>& x,
                                       const GlottisGeometry& g, double angle)
{
  if (angle <= 0)
    return;
  // Below the wall, and below the lines through the attachments (0, H)
  // and (T, H) at the wedge angle to it, on the fluid's side of each
  const double H = g.half_height, T = g.fold_length;
  const double slope = std::tan(angle * M_PI / 180);
  for (auto& p : x)
  {
    const double beyond = std::max({0.0, -p[0], p[0] - T});
    p[1] = std::min(p[1], H - slope * beyond);
  }
}
//-----------------------------------------------------------------------------
void fsai::glottis::ElasticFlowGlottis::move_boundary(
    double t, std::vector<std::array<double, 2>> x)
{
  // The fluid's fold boundary follows the surface x, less the wedges at the
  // attachments (G3a): the displacements below, the porous region and, at
  // a remeshing, the reference are all of that boundary
  keep_out_of_wedges(x, _profile.geometry(), _par.wedge_angle);
  const auto& X = _fold.surface_reference();
  const double lift = boundary_lift(lowest_point(x), _par.g_min);
  const bool remeshed = _remesh.count > 0;
  if (_par.lift == "local")
  {
    // Each fold point's displacement with its own spread lift (and, after
    // a remeshing, less those at the remeshing)
    const auto l = local_lifts(x);
    std::vector<std::array<double, 2>> b(X.size());
    for (std::size_t k = 0; k < X.size(); ++k)
    {
      b[k] = {x[k][0] - X[k][0], x[k][1] - X[k][1] + _w[k] * l[k]};
      if (remeshed)
        b[k][0] -= _remesh.u[k][0], b[k][1] -= _remesh.u[k][1];
    }
    _channel->set_interface(
        [&](const std::array<double, 2>& Y)
        {
          return interpolate(_s, arc_length(Y),
                             [&](std::size_t k) { return b[k]; });
        });
  }
  else
  {
    // The fluid boundary: the fold surface's displacement at the same arc
    // length, plus the lift, tapered to the wall like the 2-DOF fold's
    // (after a remeshing: their changes since)
    _channel->set_interface(
        [&](const std::array<double, 2>& Y) -> std::array<double, 2>
        {
          const double s = arc_length(Y);
          auto u = interpolate(
              _s, s,
              [&](std::size_t k) -> std::array<double, 2>
              {
                std::array<double, 2> uk{x[k][0] - X[k][0], x[k][1] - X[k][1]};
                if (remeshed)
                  uk[0] -= _remesh.u[k][0], uk[1] -= _remesh.u[k][1];
                return uk;
              });
          const double w = remeshed ? _profile.weight(interpolate(
                               _s, s, [&](std::size_t k) { return X[k]; }))
                                    : _profile.weight(Y);
          u[1] += w * (lift - _remesh.lift);
          return u;
        });
  }
  _quality = _channel->move(t).min_scaled_jacobian;
  _x_moved = x;
  _channel->set_wall_velocity();
  // Ω^P_t: inside the deformed fold (the polyline ends on the wall, y = H:
  // closed along it)
  _channel->mark_porous(x, [](const std::array<double, 2>& m) { return m; });
}
//-----------------------------------------------------------------------------
std::vector<double> fsai::glottis::ElasticFlowGlottis::surface_pressure()
{
  const auto all = common::allgather(_comm, _channel->fold_pressure());
  const std::size_t n = all.size() / 3;
  if (_p_order.size() != n)
  {
    // The same owned fold dofs in the same rank order at every call
    std::vector<double> s(n);
    for (std::size_t i = 0; i < n; ++i)
      s[i] = arc_length({all[3 * i], all[3 * i + 1]});
    _p_order.resize(n);
    std::iota(_p_order.begin(), _p_order.end(), 0);
    std::stable_sort(_p_order.begin(), _p_order.end(),
                     [&](auto a, auto b) { return s[a] < s[b]; });
    _p_s.resize(n);
    for (std::size_t k = 0; k < n; ++k)
      _p_s[k] = s[_p_order[k]];
  }
  std::vector<double> p;
  p.reserve(_s.size());
  for (double s : _s)
    p.push_back(interpolate(_p_s, s,
                            [&](std::size_t k) -> std::array<double, 1>
                            { return {all[3 * _p_order[k] + 2]}; })[0]);
  return p;
}
//-----------------------------------------------------------------------------
std::vector<double> fsai::glottis::ElasticFlowGlottis::predict()
{
  if (_par.predictor == "displacement" or _steps < 2)
    return _fold.surface_prediction();
  // The pressures of the last two steps extrapolated to the end of this
  // one (steps of any length: a cut step)
  const auto& flow = _channel->flow();
  const double r = flow.dt() / flow.dt_previous();
  std::vector<double> p(_p_n.size());
  common::extrapolate(p, _p_n, _p_nn, r);
  // The trial step is repeated by the first evaluation (H restores the
  // fold's state first)
  _fold.restore_state();
  _fold.set_pressure(p);
  _fold.step();
  return _fold.surface_displacement();
}
//-----------------------------------------------------------------------------
fsai::glottis::Sample fsai::glottis::ElasticFlowGlottis::step()
{
  coupling::StepReport total;
  total.converged = true;
  total.first_residual = std::numeric_limits<double>::quiet_NaN();
  advance(_par.dt, 0, total);
  _loop.record(_t, total);
  // Not while the glottis is nearly closed: a gap narrower than the mesh
  // size gets fewer nodes across from a new isotropic mesh than it had in
  // the compressed one (on the 0.1 mm mesh a remeshing at a 40 µm gap
  // changed the glottal flow by 23 %); the gap columns keep the
  // compressed cells valid until the glottis opens
  Sample out = sample(total);
  if (_par.remesh_quality > 0 and _quality < _par.remesh_quality
      and out.gap > 2 * _par.sizes.h_gap)
    remesh();
  return out;
}
//-----------------------------------------------------------------------------
void fsai::glottis::ElasticFlowGlottis::advance(double dt, int cuts,
                                                coupling::StepReport& total)
{
  // E13b: a failed attempt is discarded and the step taken as two halves;
  // at the last level an inverted cell remeshes and the step is repeated
  // (E13a), an unconverged step is accepted with a warning
  const bool last = cuts >= _par.step_cuts;
  bool accepted = false;
  try
  {
    accepted = attempt(dt, !last, total);
  }
  catch (const ale::MeshInvertedError& e)
  {
    // Every rank throws (the quality is a global minimum)
    if (last and (_par.remesh_quality <= 0 or _x_accepted.empty()))
      throw;
    _channel->rewind();
    _fold.restore_state();
    if (last)
    {
      log::warn("{}: meshing again at the last step and repeating it",
                e.what());
      remesh();
      accepted = attempt(dt, false, total);
    }
    else
      log::info("{}: the step of {:.3g} s taken as two halves", e.what(), dt);
  }
  if (!accepted)
  {
    ++_step_cuts;
    advance(dt / 2, cuts + 1, total);
    advance(dt / 2, cuts + 1, total);
    return;
  }
  _min_quality = std::min(_min_quality, _quality);
}
//-----------------------------------------------------------------------------
bool fsai::glottis::ElasticFlowGlottis::attempt(double dt, bool may_retry,
                                                coupling::StepReport& total)
{
  common::ScopedTimer timer("glottis: elastic fe step");
  const double t = _t + dt;
  auto& flow = _channel->flow();
  flow.set_dt(dt);
  _fold.set_dt(dt);
  flow.set_inlet_pressure(pressure_ramp(t, _par.ramp) * _par.p_sub);
  flow.save_state();
  _fold.save_state();
  // H(x): fluid boundary and mesh at the surface moved by x, the flow step,
  // the fold's step under its pressure, the fold's new surface displacement
  auto H = [&](std::span<const double> x, std::span<double> Hx)
  {
    move_boundary(t, _fold.moved_surface(x));
    _channel->solve_flow();
    _p = surface_pressure();
    _fold.restore_state();
    _fold.set_pressure(_p);
    _fold.step();
    const auto u = _fold.surface_displacement();
    std::copy(u.begin(), u.end(), Hx.begin());
  };
  std::vector<double> x = predict();
  const auto rep
      = _loop.step(t, x, H, {.record = false, .may_retry = may_retry});
  // The step's report: its evaluations of H, discarded attempts included
  total.iterations += rep.iterations;
  if (!rep.converged and may_retry and !_explicit)
  {
    log::info("coupling: not converged at t = {:.6g} s after {} iterations "
              "(relative interface residual {:.3e}): the step of {:.3g} s "
              "taken as two halves",
              t, rep.iterations, rep.residual, dt);
    _channel->rewind();
    _fold.restore_state();
    if (_par.cut_history == "clear")
      _loop.clear_history();
    return false;
  }
  if (std::isnan(total.first_residual)) // the step's first accepted part
    total.first_residual = rep.first_residual,
    total.first_residual_abs = rep.first_residual_abs;
  total.residual = std::max(total.residual, rep.residual);
  total.residual_abs = std::max(total.residual_abs, rep.residual_abs);
  total.converged = total.converged and rep.converged;
  total.omega = rep.omega;
  _channel->advance();
  _x_accepted = _x_moved;
  _p_nn = std::move(_p_n);
  _p_n = _p;
  ++_steps;
  _t = t;
  return true;
}
//-----------------------------------------------------------------------------
fsai::glottis::Sample
fsai::glottis::ElasticFlowGlottis::sample(const coupling::StepReport& rep)
{
  // The flow holds the step at the mesh of the last iterate, the fold
  // H(last iterate): report the fold's state and the flow's
  Sample out;
  out.t = _t;
  const auto xs = _fold.moved_surface(_fold.surface_displacement());
  out.gap = lowest_point(xs);
  const auto Q = _channel->flow_rates();
  out.Q_inlet = Q[0];
  out.Q = Q[1];
  std::array<double, 2> f{0, 0};
  for (const auto& nf : _channel->fold_forces())
  {
    f[0] += nf.f[0];
    f[1] += nf.f[1];
  }
  MPI_Allreduce(MPI_IN_PLACE, f.data(), 2, MPI_DOUBLE, MPI_SUM, _comm);
  out.drag = f[0];
  out.lift = f[1];
  _fold.fill_sample(xs, rep, _explicit, "elastic FE glottis", out);
  return out;
}
//-----------------------------------------------------------------------------
fsai::io::RankState fsai::glottis::ElasticFlowGlottis::save()
{
  _loop.clear_history();
  io::RankState state;
  _channel->save(state);
  _fold.save(state);
  // The remeshed boundary (the restart meshes it again the same way):
  // count, lift, points, then per point s, x, y; per fold point u
  std::vector<double> r{double(_remesh.count), _remesh.lift,
                        double(_remesh.s.size()), double(_remesh.u.size())};
  for (std::size_t k = 0; k < _remesh.s.size(); ++k)
    r.insert(r.end(), {_remesh.s[k], _remesh.curve[k][0], _remesh.curve[k][1]});
  for (const auto& u : _remesh.u)
    r.insert(r.end(), {u[0], u[1]});
  r.insert(r.end(), {_min_quality});
  state["glottis.remesh"] = r;
  // The accepted step's moved surface (where a remeshing puts the boundary)
  std::vector<double> xa;
  for (const auto& x : _x_accepted)
    xa.insert(xa.end(), {x[0], x[1]});
  state["glottis.x_accepted"] = xa;
  // The surface pressures (the same on every rank): sizes, then values
  std::vector<double> p{double(_p_n.size()), double(_p_nn.size())};
  p.insert(p.end(), _p_n.begin(), _p_n.end());
  p.insert(p.end(), _p_nn.begin(), _p_nn.end());
  state["glottis.p_history"] = p;
  state["glottis.t_steps"]
      = {_t, double(_steps), double(_step_cuts), double(refine_counts()[0]),
         double(refine_counts()[1])};
  return state;
}
//-----------------------------------------------------------------------------
void fsai::glottis::ElasticFlowGlottis::load(
    const std::vector<io::RankState>& ranks)
{
  // A mismatch on one rank must not leave the others waiting
  io::on_every_rank(
      _comm,
      [&]
      {
        const auto& r0 = ranks.at(0);
        if (auto it = r0.find("glottis.remesh"); it != r0.end())
        {
          const auto& r = it->second;
          const std::size_t n = r.size() >= 4 ? std::size_t(r[2]) : 0,
                            nu = r.size() >= 4 ? std::size_t(r[3]) : 0;
          if (r.size() != 4 + 3 * n + 2 * nu + 1
              or (nu != 0 and nu != _s.size()))
            throw InputError("restart: the checkpoint's remeshed boundary "
                             "does not fit this fold");
          Remeshing m;
          m.count = int(r[0]);
          m.lift = r[1];
          for (std::size_t k = 0; k < n; ++k)
          {
            m.s.push_back(r[4 + 3 * k]);
            m.curve.push_back({r[5 + 3 * k], r[6 + 3 * k]});
          }
          for (std::size_t k = 0; k < nu; ++k)
            m.u.push_back({r[4 + 3 * n + 2 * k], r[5 + 3 * n + 2 * k]});
          _min_quality = r.back();
          if (m.count > 0)
          {
            _remesh = std::move(m);
            _arc_cache.clear();
            _p_order.clear();
            _channel = make_channel();
          }
        }
        if (auto it = r0.find("glottis.x_accepted"); it != r0.end())
        {
          _x_accepted.clear();
          for (std::size_t k = 0; k + 1 < it->second.size(); k += 2)
            _x_accepted.push_back({it->second[k], it->second[k + 1]});
        }
        _channel->load(ranks);
        _fold.load(ranks);
        const auto& p = io::state_entry(r0, "glottis.p_history");
        const std::size_t n1 = p.size() >= 2 ? std::size_t(p[0]) : 0,
                          n2 = p.size() >= 2 ? std::size_t(p[1]) : 0;
        if (p.size() != 2 + n1 + n2 or (n1 > 0 and n1 != _s.size())
            or (n2 > 0 and n2 != _s.size()))
          throw InputError("restart: the checkpoint's fold surface differs");
        _p_n.assign(p.begin() + 2, p.begin() + 2 + long(n1));
        _p_nn.assign(p.begin() + 2 + long(n1), p.end());
        _p = _p_n;
        const auto& ts = io::state_entry(r0, "glottis.t_steps");
        if (ts.size() < 2)
          throw InputError(
              "restart: the checkpoint's glottis.t_steps is short");
        _t = ts[0];
        _steps = int(ts[1]);
        _step_cuts = ts.size() > 2 ? int(ts[2]) : 0;
        // (the loaded channel's flow starts its counts at 0)
        _refines_before = ts.size() > 4
                              ? std::array<int, 2>{int(ts[3]), int(ts[4])}
                              : std::array<int, 2>{0, 0};
      });
}
//-----------------------------------------------------------------------------
std::optional<double>
fsai::glottis::ElasticFlowGlottis::write_last_good(const std::string& path)
{
  _channel->rewind();
  _fold.restore_state();
  io::TimeSeriesWriter xdmf(path, _channel->fields());
  xdmf.write(_t);
  return _t;
}
//-----------------------------------------------------------------------------
std::unique_ptr<fsai::glottis::FlowChannel>
fsai::glottis::ElasticFlowGlottis::make_channel() const
{
  return std::make_unique<FlowChannel>(_comm, _profile, _par, _fp, _ap,
                                       _remesh.curve);
}
//-----------------------------------------------------------------------------
void fsai::glottis::ElasticFlowGlottis::remesh()
{
  common::ScopedTimer timer("glottis: remeshing");
  // The fluid's fold boundary where the last accepted step left it, by arc
  // length (all ranks), without the attachments on the wall
  std::vector<double> loc;
  for (const auto& [X, x] : _channel->fold_nodes())
    loc.insert(loc.end(), {arc_length(X), x[0], x[1]});
  const auto all = common::allgather(_comm, loc);
  std::vector<std::array<double, 3>> pts;
  const double H = _profile.geometry().half_height;
  for (std::size_t i = 0; i + 2 < all.size(); i += 3)
    if (all[i + 2] < H * (1 - 1e-9))
      pts.push_back({all[i], all[i + 1], all[i + 2]});
  std::sort(pts.begin(), pts.end());
  pts.erase(std::unique(pts.begin(), pts.end(),
                        [](const auto& a, const auto& b)
                        { return a[0] == b[0]; }),
            pts.end());
  Remeshing r;
  r.count = _remesh.count + 1;
  for (const auto& p : pts)
  {
    r.s.push_back(p[0]);
    r.curve.push_back({p[1], p[2]});
  }
  {
    // gmsh cannot mesh a boundary that crosses itself (and its error,
    // thrown in an OpenMP region, would end the process): say where
    const auto& g = _profile.geometry();
    std::vector<std::array<double, 2>> b = {{-g.inlet_length, H}, {0, H}};
    b.insert(b.end(), r.curve.begin(), r.curve.end());
    b.insert(b.end(),
             {{g.fold_length, H}, {g.fold_length + g.outlet_length, H}});
    if (const auto c = polyline_crossing(b))
      throw std::runtime_error(fmt::format(
          "remeshing at t = {:.5f} s: the fold boundary crosses itself near "
          "({:.4g}, {:.4g}) mm; it cannot be meshed",
          _t, 1e3 * (*c)[0], 1e3 * (*c)[1]));
  }
  // The fold's displacement and the lift the fluid boundary was moved by
  const auto& X = _fold.surface_reference();
  const auto& x = _x_accepted;
  for (std::size_t k = 0; k < X.size(); ++k)
    r.u.push_back({x[k][0] - X[k][0], x[k][1] - X[k][1]});
  r.lift = boundary_lift(lowest_point(x), _par.g_min);
  if (_par.lift == "local")
  {
    // The lift is in the points' displacements
    const auto l = local_lifts(x);
    for (std::size_t k = 0; k < X.size(); ++k)
      r.u[k][1] += _w[k] * l[k];
    r.lift = 0;
  }
  const double q_old = _quality;
  std::unique_ptr<FlowChannel> old = std::move(_channel);
  _remesh = std::move(r);
  _arc_cache.clear();
  _p_order.clear();
  _channel = make_channel();
  const auto Q = _channel->transfer_from(*old);
  _refines_before[0] += old->flow().refined_solves();
  _refines_before[1] += old->flow().refine_fallbacks();
  old.reset();
  _quality = 1;
  // The coupling's secant history belongs to the old mesh's flow
  _loop.clear_history();
  log::info("remeshing {} at t = {:.5f} s (min scaled Jacobian {:.3f}): {} "
            "cells; glottal flow {:.4e} -> {:.4e} m3/s, inlet {:.4e} -> "
            "{:.4e} m3/s",
            _remesh.count, _t, q_old, _channel->cells(), Q[0], Q[1], Q[2],
            Q[3]);
}
//-----------------------------------------------------------------------------
void fsai::glottis::ElasticFlowGlottis::report(io::RunSummary& summary) const
{
  summary.set("remeshes", _remesh.count);
  summary.set("mesh_quality_min", _min_quality);
  summary.set("step_cuts", _step_cuts);
  // Coupling iterates after a step's first: flow solves by refinement of
  // the step's factorisation, and those that factorised afresh
  summary.set("flow_refined_solves", refine_counts()[0]);
  summary.set("flow_refine_fallbacks", refine_counts()[1]);
}
//-----------------------------------------------------------------------------
std::array<int, 2> fsai::glottis::ElasticFlowGlottis::refine_counts() const
{
  return {_refines_before[0] + _channel->flow().refined_solves(),
          _refines_before[1] + _channel->flow().refine_fallbacks()};
}
