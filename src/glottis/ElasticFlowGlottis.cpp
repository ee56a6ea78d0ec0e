// Copyright (C) 2026 fsai developers
#include "ElasticFlowGlottis.h"
#include "waveform.h"
#include <algorithm>
#include <cmath>
#include <common/errors.h>
#include <common/mpi_gather.h>
#include <common/timer.h>
#include <fmt/format.h>
#include <io/TimeSeriesWriter.h>
#include <numeric>
#include <stdexcept>

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
      _fold(comm, profile, ep, contact, p.dt),
      _channel(comm, profile, p, fp, ap), _explicit(ep.explicit_coupling(true)),
      _loop(comm, elastic_coupling_parameters(_explicit, cp), coupling_csv,
            coupling_rows_kept)
{
  for (const auto& X : _fold.surface_reference())
    _s.push_back(_profile.arc_length(X));
  fsai::require(std::is_sorted(_s.begin(), _s.end()),
                "elastic fold: surface points", "ordered by arc length",
                "unordered");
}
//-----------------------------------------------------------------------------
double
fsai::glottis::ElasticFlowGlottis::arc_length(const std::array<double, 2>& X)
{
  auto [it, added] = _arc_cache.try_emplace(X, 0.0);
  if (added)
    it->second = _profile.arc_length(X);
  return it->second;
}
//-----------------------------------------------------------------------------
void fsai::glottis::ElasticFlowGlottis::move_boundary(
    double t, const std::vector<std::array<double, 2>>& x)
{
  const auto& X = _fold.surface_reference();
  const double lift = boundary_lift(lowest_point(x), _par.g_min);
  // The fluid boundary: the fold surface's displacement at the same arc
  // length, plus the lift, tapered to the wall like the 2-DOF fold's
  _channel.set_interface(
      [&](const std::array<double, 2>& Y) -> std::array<double, 2>
      {
        auto u = interpolate(_s, arc_length(Y),
                             [&](std::size_t k) -> std::array<double, 2> {
                               return {x[k][0] - X[k][0], x[k][1] - X[k][1]};
                             });
        u[1] += _profile.weight(Y) * lift;
        return u;
      });
  _channel.move(t);
  _channel.set_wall_velocity();
  // Ω^P_t: inside the deformed fold (the polyline ends on the wall, y = H:
  // closed along it)
  _channel.mark_porous(x, [](const std::array<double, 2>& m) { return m; });
}
//-----------------------------------------------------------------------------
std::vector<double> fsai::glottis::ElasticFlowGlottis::surface_pressure()
{
  const auto all = common::allgather(_comm, _channel.fold_pressure());
  const std::size_t n = all.size() / 3;
  if (_p_order.size() != n)
  {
    // The same owned fold dofs in the same rank order at every call
    std::vector<double> s(n);
    for (std::size_t i = 0; i < n; ++i)
      s[i] = _profile.arc_length({all[3 * i], all[3 * i + 1]});
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
  std::vector<double> p(_p_n.size());
  for (std::size_t k = 0; k < p.size(); ++k)
    p[k] = 2 * _p_n[k] - _p_nn[k];
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
  common::ScopedTimer timer("glottis: elastic fe step");
  const double t = _t + _par.dt;
  auto& flow = _channel.flow();
  flow.set_inlet_pressure(pressure_ramp(t, _par.ramp) * _par.p_sub);
  flow.save_state();
  _fold.save_state();
  // H(x): fluid boundary and mesh at the surface moved by x, the flow step,
  // the fold's step under its pressure, the fold's new surface displacement
  auto H = [&](std::span<const double> x, std::span<double> Hx)
  {
    move_boundary(t, _fold.moved_surface(x));
    _channel.solve_flow();
    _p = surface_pressure();
    _fold.restore_state();
    _fold.set_pressure(_p);
    _fold.step();
    const auto u = _fold.surface_displacement();
    std::copy(u.begin(), u.end(), Hx.begin());
  };
  std::vector<double> x = predict();
  const auto rep = _loop.step(t, x, H);
  _channel.advance();
  _p_nn = std::move(_p_n);
  _p_n = _p;
  ++_steps;
  _t = t;

  // The flow holds the step at the mesh of the last iterate, the fold
  // H(last iterate): report the fold's state and the flow's
  Sample out;
  out.t = t;
  const auto xs = _fold.moved_surface(_fold.surface_displacement());
  out.gap = lowest_point(xs);
  const auto Q = _channel.flow_rates();
  out.Q_inlet = Q[0];
  out.Q = Q[1];
  std::array<double, 2> f{0, 0};
  for (const auto& nf : _channel.fold_forces())
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
  _channel.save(state);
  _fold.save(state);
  // The surface pressures (the same on every rank): sizes, then values
  std::vector<double> p{double(_p_n.size()), double(_p_nn.size())};
  p.insert(p.end(), _p_n.begin(), _p_n.end());
  p.insert(p.end(), _p_nn.begin(), _p_nn.end());
  state["glottis.p_history"] = p;
  state["glottis.t_steps"] = {_t, double(_steps)};
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
        _channel.load(ranks);
        _fold.load(ranks);
        const auto& r0 = ranks.at(0);
        const auto& p = io::state_entry(r0, "glottis.p_history");
        const std::size_t n1 = p.size() >= 2 ? std::size_t(p[0]) : 0,
                          n2 = p.size() >= 2 ? std::size_t(p[1]) : 0;
        if (p.size() != 2 + n1 + n2 or (n1 > 0 and n1 != _s.size())
            or (n2 > 0 and n2 != _s.size()))
          throw InputError("restart: the checkpoint's fold surface differs");
        _p_n.assign(p.begin() + 2, p.begin() + 2 + long(n1));
        _p_nn.assign(p.begin() + 2 + long(n1), p.end());
        _p = _p_n;
        const auto& ts = io::state_entry(r0, "glottis.t_steps", 2);
        _t = ts[0];
        _steps = int(ts[1]);
      });
}
//-----------------------------------------------------------------------------
std::optional<double>
fsai::glottis::ElasticFlowGlottis::write_last_good(const std::string& path)
{
  _channel.rewind();
  _fold.restore_state();
  io::TimeSeriesWriter xdmf(path, _channel.fields());
  xdmf.write(_t);
  return _t;
}
