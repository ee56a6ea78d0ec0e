// Copyright (C) 2026 fsai developers
#include "TubeTract.h"
#include <cmath>
#include <common/errors.h>

//-----------------------------------------------------------------------------
fsai::acoustics::TubeTract::TubeTract(const mesh::AreaFunction& af,
                                      const TubeTractParameters& p, double dt)
    : _par(p), _dt(dt), _mic(p.mic_distance, p.c0, p.rho0, dt, 0.5)
{
  fsai::require_positive("tract time step", dt);
  fsai::require_positive("--tract1d.dx", p.dx);
  fsai::require(p.cfl > 0 and p.cfl <= 1, "--tract1d.cfl", "in (0, 1]", p.cfl);
  fsai::require_positive("--mic_distance", p.mic_distance);
  fsai::require(af.size() > 0, "tract area function", "not empty", 0);
  const mesh::AreaFunction line = mesh::resample(af, true, p.dx);
  const std::size_t n = line.size();
  const double rc2 = p.rho0 * p.c0 * p.c0;
  double l_min = 1e300;
  std::vector<double> l(n);
  for (std::size_t k = 0; k < n; ++k)
  {
    l[k] = line.x_end[k] - line.x_start(k);
    l_min = std::min(l_min, l[k]);
    _C.push_back(line.area[k] * l[k] / rc2);
    // The wall's perimeter as the 1D formants take it (tube_model.h)
    const double P = p.wall.depth > 0 ? 2 * p.wall.depth
                                      : 2 * std::sqrt(M_PI * line.area[k]);
    _Pl.push_back(p.wall.rigid() ? 0.0 : P * l[k]);
  }
  // Face j between sections j−1 and j; face 0 is the glottis (U given)
  _L.assign(n, 0.0);
  for (std::size_t j = 1; j < n; ++j)
  {
    _L[j] = p.rho0
            * (0.5 * l[j - 1] / line.area[j - 1] + 0.5 * l[j] / line.area[j]);
  }
  const double AL = line.area.back();
  const PistonLoad load = flanged_piston(AL, p.c0, p.rho0);
  _L_lip = p.rho0 * 0.5 * l.back() / AL;
  _L_rad = load.inertance / AL;
  _R = load.resistance / AL;
  _m = std::max(1, int(std::ceil(p.c0 * dt / (p.cfl * l_min))));
  _h = dt / _m;
  _p.assign(n, 0.0);
  _u.assign(n + 1, 0.0);
  _v.assign(n, 0.0);
  _w.assign(n, 0.0);
}
//-----------------------------------------------------------------------------
void fsai::acoustics::TubeTract::step(double u_glottis)
{
  const std::size_t n = _p.size();
  const auto& wall = _par.wall;
  const double ug0 = _ug;
  for (int s = 1; s <= _m; ++s)
  {
    // Faces from the pressures of the substep's start (symplectic Euler)
    for (std::size_t j = 1; j < n; ++j)
      _u[j] += _h / _L[j] * (_p[j - 1] - _p[j]);
    // Lip face and the radiation load, backward Euler:
    //   L_lip U̇ = p_{n−1} − R (U − U_r),  L_rad U̇_r = R (U − U_r)
    {
      const double a = _L_lip / _h, b = _L_rad / _h;
      const double r1 = a * _u[n] + _p[n - 1], r2 = b * _u_rad;
      const double det = (a + _R) * (b + _R) - _R * _R;
      const double un = ((b + _R) * r1 + _R * r2) / det;
      const double ur = (_R * r1 + (a + _R) * r2) / det;
      _u[n] = un;
      _u_rad = ur;
      _p_rad = _R * (un - ur);
    }
    // Yielding walls (A3): resistance implicit
    if (!wall.rigid())
    {
      for (std::size_t k = 0; k < n; ++k)
      {
        _v[k] = (_v[k] + _h / wall.mass * (_p[k] - wall.stiffness * _w[k]))
                / (1 + _h * wall.resistance / wall.mass);
        _w[k] += _h * _v[k];
      }
    }
    _u[0] = ug0 + (u_glottis - ug0) * double(s) / double(_m);
    for (std::size_t k = 0; k < n; ++k)
      _p[k] += _h / _C[k] * (_u[k] - _u[k + 1] - _Pl[k] * _v[k]);
  }
  _ug = u_glottis;
  _t += _dt;
  // The lip flow's rate over the step (its value stands at the step's
  // midpoint)
  _mic.record((_u[n] - _u_lips_prev) / _dt);
  _u_lips_prev = _u[n];
}
//-----------------------------------------------------------------------------
nlohmann::json fsai::acoustics::TubeTract::save() const
{
  return {{"p", _p},
          {"u", _u},
          {"v", _v},
          {"w", _w},
          {"u_rad", _u_rad},
          {"p_rad", _p_rad},
          {"ug", _ug},
          {"t", _t},
          {"udot", _mic.save()},
          {"u_lips_prev", _u_lips_prev}};
}
//-----------------------------------------------------------------------------
void fsai::acoustics::TubeTract::load(const nlohmann::json& j)
{
  auto p = j.at("p").get<std::vector<double>>();
  fsai::require(p.size() == _p.size(), "checkpoint's 1D tract",
                "the same number of sections as this run's", p.size());
  _p = std::move(p);
  _u = j.at("u").get<std::vector<double>>();
  _v = j.at("v").get<std::vector<double>>();
  _w = j.at("w").get<std::vector<double>>();
  _u_rad = j.at("u_rad");
  _p_rad = j.at("p_rad");
  _ug = j.at("ug");
  _t = j.at("t");
  _mic.load(j.at("udot"));
  _u_lips_prev = j.at("u_lips_prev");
}
