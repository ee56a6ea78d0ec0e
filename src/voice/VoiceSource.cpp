// Copyright (C) 2026 fsai developers
#include "VoiceSource.h"
#include <algorithm>
#include <cmath>
#include <common/Parameters.h>
#include <common/errors.h>
#include <common/timer.h>
#include <dolfinx/fem/utils.h>
#include <glottis/BernoulliFlow.h>
#include <glottis/ElasticFold.h>
#include <glottis/waveform.h>
#include <io/field_state.h>
#include <limits>

//-----------------------------------------------------------------------------
void fsai::voice::VoiceSourceParameters::bind(fsai::common::Parameters& p)
{
  p.add("voice.taper", taper,
        "taper Lighthill's source to zero before the flow outlet (false: "
        "truncated source, for the failure study)");
  p.add("voice.lighthill", lighthill,
        "Lighthill's source (false: the fold surface's vibration only)");
  p.add("voice.wall", wall,
        "vibrating fold surface (false: Lighthill's source only)");
  p.add("voice.glottal_slit", glottal_slit,
        "the acoustic glottis (fixed at the rest gap) "
        "follows the flow's: in the cells under the fold the momentum law "
        "of the current slit (inertia g0/g, viscous and jet resistance; "
        "false: air at rest in the rest slit)");
  p.add("voice.slit_lighthill", slit_lighthill,
        "with --voice.glottal_slit: Lighthill's force in the slit's "
        "momentum law (true: 139 dB of spurious sound in --quick) or no "
        "source in the slit cells (false)");
  p.add("voice.source_average", source_average,
        "Lighthill's source from (v_n + v_n+1)/2 (false: v_n+1)");
  p.add("voice.monopole", monopole,
        "the flow's glottal volume flow Q(t) as a volume-source pair, +Q "
        "after the fold and -Q before it (the valve's monopole, which "
        "Lighthill's rho0 v v of the incompressible flow does not carry)");
  p.add("voice.monopole_length", monopole_length,
        "--voice.monopole: extent of each source along the channel [m]");
  p.add("voice.taper_start", taper_start,
        "taper starts this far before the flow outlet [m]");
  p.add("voice.taper_end", taper_end,
        "source is zero from this far before the flow outlet [m]");
  p.add("voice.taper_inlet", taper_inlet,
        "source ramps up over this length after the inlet [m]");
}
//-----------------------------------------------------------------------------
void fsai::voice::VoiceSourceParameters::validate() const
{
  fsai::require(taper_start > taper_end and taper_end >= 0,
                "--voice.taper_start", "> --voice.taper_end >= 0", taper_start);
  fsai::require(taper_inlet >= 0, "--voice.taper_inlet", ">= 0", taper_inlet);
  fsai::require_positive("--voice.monopole_length", monopole_length);
}
//-----------------------------------------------------------------------------
double
fsai::voice::surface_height(const std::vector<std::array<double, 2>>& surface,
                            double x)
{
  double y = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i + 1 < surface.size(); ++i)
  {
    const auto& a = surface[i];
    const auto& b = surface[i + 1];
    if ((x - a[0]) * (x - b[0]) > 0 or a[0] == b[0])
      continue;
    y = std::min(y, a[1] + (b[1] - a[1]) * (x - a[0]) / (b[0] - a[0]));
  }
  return y;
}
//-----------------------------------------------------------------------------
fsai::voice::VoiceSource::VoiceSource(MPI_Comm comm,
                                      const VoiceSourceParameters& p,
                                      const glottis::FlowGlottisSetup& setup,
                                      const glottis::FoldProfile& profile,
                                      const glottis::FlowChannel* channel,
                                      const mesh::MeshData& am,
                                      acoustics::WaveSolver& sound, double dt)
    : _par(p), _profile(profile), _sound(sound), _dt(dt),
      _g_min(setup.fe.g_min), _mu(setup.fluid.mu), _rho(setup.fluid.rho),
      _comm(comm)
{
  const auto& geo = setup.geometry;
  // The slit (A5): the acoustic cells under the fold at rest (the glottal
  // slit and the gap beside the fold), with the fold's rest height there
  if (_par.glottal_slit)
  {
    const auto rest
        = glottis::moved_surface(profile, glottis::RigidMotion(0, 0, {0, 0}));
    const int tdim = am.mesh->topology().dim();
    const std::int32_t nc = am.mesh->topology().index_map(tdim)->size_local();
    const auto x = am.mesh->geometry().x();
    const auto& xdofs = am.mesh->geometry().dofmap();
    std::vector<std::int32_t> cells;
    for (std::int32_t c = 0; c < nc; ++c)
    {
      std::array<double, 2> m{0, 0};
      for (auto v : xdofs.links(c))
        for (int k = 0; k < 2; ++k)
          m[k] += x[3 * v + k] / double(xdofs.links(c).size());
      if (m[0] <= 0 or m[0] >= geo.fold_length)
        continue;
      const double g0 = surface_height(rest, m[0]);
      if (m[1] < g0)
      {
        cells.push_back(c);
        _slit_x.push_back(m[0]);
        _slit_g0.push_back(g0);
      }
    }
    _slit = std::make_shared<acoustics::SlitLaw>(cells, _par.slit_lighthill);
    _sound.set_slit(_slit);
    _inertia.assign(cells.size(), 1.0);
    _resistance.assign(cells.size(), 0.0);
  }
  // The valve's monopole pair (A6): two cos² bumps next to the fold, each
  // 2 × monopole_length long over the channel's width, +Q downstream and
  // −Q upstream (E14's right-hand side ρ0 ∂q/∂t per unit depth of the
  // half model: Q/(2 L_g))
  if (_par.monopole)
  {
    const double l = _par.monopole_length;
    fsai::require(2 * l <= geo.inlet_length and 2 * l <= geo.outlet_length,
                  "--voice.monopole_length",
                  "<= half the sub- and supraglottal channel lengths", l);
    auto bump = [l](double x, double centre)
    {
      const double u = (x - centre) / l;
      return std::abs(u) < 1 ? std::pow(std::cos(0.5 * M_PI * u), 2) : 0.0;
    };
    _monopole[0] = _sound.add_volume_source(
        [&](double x, double) { return bump(x, geo.fold_length + l); });
    _monopole[1] = _sound.add_volume_source([&](double x, double)
                                            { return bump(x, -l); });
  }
  // Lighthill's source (A1): transfer in the reference configuration and
  // its taper χ, 1 inside the flow domain, cos² ramps to 0 towards the
  // inlet and before the outlet
  if (!channel)
    _par.lighthill = false;
  {
    auto ramp = [](double s) // 0 → 0, 1 → 1
    {
      s = std::clamp(s, 0.0, 1.0);
      return std::pow(std::sin(0.5 * M_PI * s), 2);
    };
    const double x_in = -geo.inlet_length,
                 x_out = geo.fold_length + geo.outlet_length;
    const double a = x_out - _par.taper_start, b = x_out - _par.taper_end;
    auto& chi = sound.taper();
    const auto X = chi.function_space()->tabulate_dof_coordinates(false);
    auto c = chi.x()->mutable_array();
    for (std::size_t i = 0; i < c.size(); ++i)
    {
      const double x = X[3 * i];
      const double up
          = _par.taper_inlet > 0 ? ramp((x - x_in) / _par.taper_inlet) : 1.0;
      c[i] = _par.taper ? up * (1.0 - ramp((x - a) / (b - a))) : 1.0;
    }
  }
  // The fold surface's nodes (A2)
  const auto Va = sound.wall_acceleration().function_space();
  _fold_dofs = dolfinx::fem::locate_dofs_topological(
      *Va, 1, am.facet_tags->find(am.facet_tag("fold")));
  const auto X = Va->tabulate_dof_coordinates(false);
  for (auto d : _fold_dofs)
    _fold_X.push_back({X[3 * d], X[3 * d + 1]});
  _v_new = std::make_shared<dolfinx::fem::Function<double>>(
      sound.flow_velocity().function_space());
  _v_old = std::make_shared<dolfinx::fem::Function<double>>(
      sound.flow_velocity().function_space());
}
//-----------------------------------------------------------------------------
void fsai::voice::VoiceSource::start(const FoldWall& fold, double q_last)
{
  _u_wall_prev = wall_velocity(fold, slit_surface(fold));
  _q_monopole = q_last;
}
//-----------------------------------------------------------------------------
std::vector<std::array<double, 2>>
fsai::voice::VoiceSource::slit_surface(const FoldWall& fold) const
{
  if (!_par.glottal_slit)
    return {};
  return fold.surface;
}
//-----------------------------------------------------------------------------
void fsai::voice::VoiceSource::apply(const FoldWall& fold,
                                     const glottis::FlowChannel* channel,
                                     const glottis::Sample& s)
{
  if (_par.lighthill and channel)
  {
    if (channel != _transfer_channel)
    {
      _transfer = std::make_unique<acoustics::FlowSource>(
          _comm, *channel->flow().velocity_space(),
          channel->reference_coordinates(),
          *_sound.flow_velocity().function_space());
      _transfer_channel = channel;
    }
    // The source at the step's midpoint, v = (v_n + v_{n+1})/2 (the
    // trapezoidal rule's own load): the flow's step-to-step (−1)^n
    // content, which the undamped Newmark scheme would store in unresolved
    // high-frequency modes, is removed
    _transfer->transfer(*channel->flow().velocity(), *_v_new);
    auto vs = _sound.flow_velocity().x()->mutable_array();
    const auto vn = _v_new->x()->array();
    auto vo = _v_old->x()->mutable_array();
    for (std::size_t i = 0; i < vs.size(); ++i)
    {
      vs[i] = _par.source_average ? 0.5 * (vn[i] + vo[i]) : vn[i];
      vo[i] = vn[i];
    }
  }
  const std::vector<std::array<double, 2>> now = slit_surface(fold);
  if (_par.glottal_slit)
    set_slit_law(now, s);
  if (_par.monopole)
  {
    // dQ/dt over the step (the midpoint rate, as the wall's q̈). A step
    // whose coupling did not converge has a meaningless Q (measured: +0.7
    // l/s for one step while the glottis closes), and its dQ/dt, an
    // impulse, would ring the tract's lightly damped upper resonances for
    // the rest of the run: Q is held over it (the coupling logs a warning)
    const double depth = _profile.geometry().depth;
    const double dQ
        = s.converged ? (s.Q - _q_monopole) / _dt / (2 * depth) : 0.0;
    if (s.converged)
      _q_monopole = s.Q;
    _sound.set_volume_source_rate(_monopole[0], dQ);
    _sound.set_volume_source_rate(_monopole[1], -dQ);
  }
  set_wall_acceleration(fold, now);
}
//-----------------------------------------------------------------------------
void fsai::voice::VoiceSource::set_slit_law(
    const std::vector<std::array<double, 2>>& surface, const glottis::Sample& s)
{
  // A slit g/g0 as wide as the mesh's has the inertia ρ0 g0/g and the
  // resistance (g0/g) r per unit length, r = 3μ/g² (Poiseuille) + the
  // jet's kinetic loss ρ0 u_jet (Flanagan's ρ0 U/A², spread over the fold's
  // length in proportion to g), u_jet = Q / (2 g L_g) at the narrowest gap,
  // with g ≥ g_min as in the flow (A5)
  const auto& geo = _profile.geometry();
  const double g_n = std::max(s.gap, _g_min);
  const double u_jet = std::abs(s.Q) / (2 * g_n * geo.depth);
  for (std::size_t i = 0; i < _slit_x.size(); ++i)
  {
    const double g = std::max(surface_height(surface, _slit_x[i]), _g_min);
    const double r
        = 3 * _mu / (g * g) + _rho * u_jet * g / (g_n * geo.fold_length);
    const double scale = _slit_g0[i] / g;
    _inertia[i] = scale;
    _resistance[i] = scale * r;
  }
  _slit->set(_inertia, _resistance);
}
//-----------------------------------------------------------------------------
double fsai::voice::VoiceSource::open_fraction(
    double x, const std::vector<std::array<double, 2>>& surface) const
{
  // The fold surface displaces air only while the slit beside it is open:
  // fully above 2 g_min, not at all below g_min (the flow's boundary stops
  // there too, G3)
  if (!_par.glottal_slit or x <= 0 or x >= _profile.geometry().fold_length)
    return 1.0;
  return std::clamp((surface_height(surface, x) - _g_min) / _g_min, 0.0, 1.0);
}
//-----------------------------------------------------------------------------
void fsai::voice::VoiceSource::set_wall_acceleration(
    const FoldWall& fold, const std::vector<std::array<double, 2>>& surface)
{
  // The step's mean rate of the wall's velocity, a = (u_{n+1} − u_n)/Δt
  // (the trapezoidal rule's own acceleration: Newmark's end-of-step q̈
  // carries an undamped (−1)^n part whenever the load jumps). The fade
  // acts on the velocity u, not on the acceleration: a faded acceleration
  // integrates to a velocity that gains v_closing − v_opening every cycle
  // (the fade turns off while the wall moves in and on while it moves
  // out), a steady drift that the slit law modulated into a sound growing
  // through the run (docs/voice.md)
  const std::vector<double> u = wall_velocity(fold, surface);
  auto a = _sound.wall_acceleration().x()->mutable_array();
  for (std::size_t i = 0; i < _fold_dofs.size(); ++i)
    for (int c = 0; c < 2; ++c)
      a[2 * _fold_dofs[i] + c] = (u[2 * i + c] - _u_wall_prev[2 * i + c]) / _dt;
  _u_wall_prev = u;
}
//-----------------------------------------------------------------------------
std::vector<double> fsai::voice::VoiceSource::wall_velocity(
    const FoldWall& fold,
    const std::vector<std::array<double, 2>>& surface) const
{
  // The wall's velocity u faded by f = open_fraction (A2)
  std::vector<double> u(2 * _fold_dofs.size(), 0.0);
  if (!_par.wall)
    return u;
  for (std::size_t i = 0; i < _fold_dofs.size(); ++i)
  {
    const auto v = fold.velocity(_fold_X[i]);
    const double f = open_fraction(_fold_X[i][0], surface);
    for (int c = 0; c < 2; ++c)
      u[2 * i + c] = f * v[c];
  }
  return u;
}
//-----------------------------------------------------------------------------
fsai::voice::FoldWall
fsai::voice::fold_wall(const glottis::TwoDofFold& fold,
                       const glottis::FoldProfile& profile)
{
  // Tapered rigid motion (as the flow boundary), u = w (∂u/∂h q̇_h +
  // ∂u/∂φ q̇_φ)
  const auto m = fold.motion();
  const auto qd = fold.qdot();
  FoldWall w;
  w.surface = glottis::moved_surface(profile, m);
  w.velocity = [m, qd, &profile](const std::array<double, 2>& X)
  {
    const auto d = m.derivatives(X);
    const double wt = profile.weight(X);
    return std::array<double, 2>{wt * (d[0][0] * qd[0] + d[1][0] * qd[1]),
                                 wt * (d[0][1] * qd[0] + d[1][1] * qd[1])};
  };
  return w;
}
//-----------------------------------------------------------------------------
fsai::voice::FoldWall fsai::voice::fold_wall(const glottis::ElasticFold& fold)
{
  FoldWall w;
  w.surface = fold.moved_surface(fold.surface_displacement());
  const auto& X0 = fold.surface_reference();
  w.velocity = [X0, v = fold.surface_velocity()](const std::array<double, 2>& X)
  {
    // Linear between the surface points, at the nearest point of the rest
    // surface's polyline
    const auto n = glottis::nearest_on_polyline(X0, X);
    const double t = n.t;
    return std::array<double, 2>{(1 - t) * v[n.k][0] + t * v[n.k + 1][0],
                                 (1 - t) * v[n.k][1] + t * v[n.k + 1][1]};
  };
  return w;
}
//-----------------------------------------------------------------------------
void fsai::voice::VoiceSource::save(io::RankState& state) const
{
  const auto& V = *_v_old->function_space();
  io::put_blocks(state, "voice.v_old", _v_old->x()->array(),
                 V.dofmap()->index_map_bs(), io::node_keys(V),
                 V.dofmap()->index_map->size_local());
}
//-----------------------------------------------------------------------------
void fsai::voice::VoiceSource::load(const std::vector<io::RankState>& ranks)
{
  const auto& V = *_v_old->function_space();
  io::get_blocks(ranks, "voice.v_old", _v_old->x()->mutable_array(),
                 V.dofmap()->index_map_bs(), io::node_keys(V));
}
