// Copyright (C) 2026 fsai developers
#include "ElasticBernoulliGlottis.h"
#include "waveform.h"
#include <cmath>
#include <fmt/format.h>
#include <stdexcept>

fsai::glottis::ElasticBernoulliGlottis::ElasticBernoulliGlottis(
    MPI_Comm comm, const FoldProfile& profile, const ElasticFoldParameters& ep,
    const ContactParameters& contact, const BernoulliGlottisParameters& bp,
    double ramp, const coupling::CouplingParameters& cp,
    const std::string& coupling_csv, std::size_t coupling_rows_kept)
    : _par(bp), _ramp(ramp), _fold(comm, profile, ep, contact, bp.dt),
      _explicit(ep.explicit_coupling(false)),
      _loop(comm, elastic_coupling_parameters(_explicit, cp), coupling_csv,
            coupling_rows_kept)
{
}
//-----------------------------------------------------------------------------
fsai::io::RankState fsai::glottis::ElasticBernoulliGlottis::save()
{
  _loop.clear_history();
  io::RankState state;
  _fold.save(state);
  state["glottis.t"] = {_t};
  return state;
}
//-----------------------------------------------------------------------------
void fsai::glottis::ElasticBernoulliGlottis::load(
    const std::vector<io::RankState>& ranks)
{
  // A mismatch on one rank must not leave the others waiting
  io::on_every_rank(_fold.comm(),
                    [&]
                    {
                      _fold.load(ranks);
                      _t = io::state_entry(ranks.at(0), "glottis.t", 1)[0];
                    });
}
//-----------------------------------------------------------------------------
fsai::glottis::SurfacePressure fsai::glottis::ElasticBernoulliGlottis::pressure(
    double t, const std::vector<std::array<double, 2>>& x) const
{
  return viscous_surface_pressure(x, _fold.profile().geometry().depth,
                                  pressure_ramp(t, _ramp) * _par.p_sub,
                                  _par.p_sup, _par.rho, _par.separation_ratio,
                                  _par.viscosity, _par.y_floor, _par.y_sep_min);
}
//-----------------------------------------------------------------------------
fsai::glottis::Sample fsai::glottis::ElasticBernoulliGlottis::step()
{
  const double t = _t + _par.dt;
  // H(x): the pressure of the surface moved by x, the fold's step under it,
  // its new surface displacement
  auto H = [&](std::span<const double> x, std::span<double> Hx)
  {
    _fold.restore_state();
    _fold.set_pressure(pressure(t, _fold.moved_surface(x)).p);
    _fold.step();
    const auto u = _fold.surface_displacement();
    std::copy(u.begin(), u.end(), Hx.begin());
  };
  _fold.save_state();
  std::vector<double> x = _fold.surface_prediction();
  const auto rep = _loop.step(t, x, H);
  // The sub-solver holds H(x_last): report the state it reached
  const auto xs = _fold.moved_surface(_fold.surface_displacement());
  const auto sp = pressure(t, xs);
  Sample out;
  out.t = t;
  out.gap = sp.min_gap;
  out.Q = sp.Q;
  out.Q_inlet = sp.Q; // quasi-steady: no displaced volume
  const auto f = _fold.pressure_force(xs, sp.p);
  out.drag = f[0];
  out.lift = f[1];
  _t = t;
  _fold.fill_sample(xs, rep, _explicit, "elastic glottis", out);
  return out;
}
