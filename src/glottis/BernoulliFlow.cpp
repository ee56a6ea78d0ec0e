// Copyright (C) 2026 fsai developers
#include "BernoulliFlow.h"
#include <algorithm>
#include <cmath>
#include <tuple>
#include <utility>

namespace
{
/// Separation where the half-gap y(i) first reaches y_s downstream of the
/// narrowest point imin, located between surface points (a continuous
/// function of the motion: a jump from point to point would stall the
/// implicit coupling): the last attached point i and the fraction of the
/// segment [i, i + 1] before the separation (0 without interpolation)
template <typename Height>
std::pair<std::size_t, double> separation(Height y, std::size_t n,
                                          std::size_t imin, double ys,
                                          bool interpolate)
{
  std::size_t i = imin;
  while (i + 1 < n and y(i + 1) < ys)
    ++i;
  const double frac
      = (i + 1 < n and interpolate) ? (ys - y(i)) / (y(i + 1) - y(i)) : 0.0;
  return {i, frac};
}
} // namespace

std::vector<std::array<double, 2>>
fsai::glottis::moved_surface(const FoldProfile& profile,
                             const RigidMotion& motion)
{
  const auto& X = profile.points();
  const auto& w = profile.weights();
  std::vector<std::array<double, 2>> x(X.size());
  for (std::size_t i = 0; i < X.size(); ++i)
  {
    const auto u = motion.displacement(X[i]);
    x[i] = {X[i][0] + w[i] * u[0], X[i][1] + w[i] * u[1]};
  }
  return x;
}

fsai::glottis::SurfacePressure
fsai::glottis::surface_pressure(const std::vector<std::array<double, 2>>& x,
                                double Lg, double p_sub, double p_sup,
                                double rho, double separation_ratio)
{
  const std::size_t n = x.size();
  SurfacePressure s;
  const auto imin = std::size_t(std::min_element(x.begin(), x.end(),
                                                 [](auto& a, auto& b)
                                                 { return a[1] < b[1]; })
                                - x.begin());
  s.min_gap = x[imin][1];
  const double dp = std::max(0.0, p_sub - p_sup);
  s.p.assign(n, p_sup);
  std::size_t isep = imin;
  if (s.min_gap <= 0)
  {
    for (std::size_t i = 0; i < imin; ++i)
      s.p[i] = p_sub;
    s.Q = 0;
  }
  else
  {
    // Separation where y first reaches k_s y_min after the narrowest point
    const double ys = separation_ratio * s.min_gap;
    std::tie(isep, s.separation_frac)
        = separation([&](std::size_t i) { return x[i][1]; }, n, imin, ys,
                     separation_ratio > 1);
    s.Q = 2 * Lg * ys * std::sqrt(2 * dp / rho);
    for (std::size_t i = 0; i <= isep; ++i)
    {
      const double v = s.Q / (2 * Lg * x[i][1]);
      s.p[i] = p_sub - 0.5 * rho * v * v;
    }
  }
  s.separation_index = isep;
  s.separation_x = x[isep][0];
  return s;
}
//-----------------------------------------------------------------------------
fsai::glottis::SurfacePressure fsai::glottis::viscous_surface_pressure(
    const std::vector<std::array<double, 2>>& x, double Lg, double p_sub,
    double p_sup, double rho, double separation_ratio, double mu,
    double y_floor, double y_sep_min)
{
  const std::size_t n = x.size();
  SurfacePressure s;
  std::vector<double> y(n);
  s.min_gap = x[0][1];
  for (std::size_t i = 0; i < n; ++i)
  {
    y[i] = std::max(x[i][1], y_floor);
    s.min_gap = std::min(s.min_gap, x[i][1]);
  }
  const auto imin
      = std::size_t(std::min_element(y.begin(), y.end()) - y.begin());
  const double dp = std::max(0.0, p_sub - p_sup);
  // Separation where y first reaches k_s y_min after the narrowest point
  const double ys = separation_ratio * std::max(y[imin], y_sep_min);
  std::size_t isep;
  std::tie(isep, s.separation_frac) = separation(
      [&](std::size_t i) { return y[i]; }, n, imin, ys, separation_ratio > 1);
  // C at each point up to the separation, and at the separation point:
  // ∫ dx/(2y)³ = Δx (y0 + y1) / (16 y0² y1²) for y linear on a segment
  auto segment = [&](double dx, double y0, double y1) {
    return 12 * mu / Lg * std::abs(dx) * (y0 + y1) / (16 * y0 * y0 * y1 * y1);
  };
  std::vector<double> C(isep + 1, 0.0);
  for (std::size_t i = 1; i <= isep; ++i)
    C[i] = C[i - 1] + segment(x[i][0] - x[i - 1][0], y[i - 1], y[i]);
  double Cs = C[isep];
  if (isep + 1 < n)
    Cs += segment(s.separation_frac * (x[isep + 1][0] - x[isep][0]), y[isep],
                  ys);
  // ½ρ Q²/(2 L_g y_s)² + C_s Q = Δp, the positive root in a stable form
  const double a = 0.5 * rho / std::pow(2 * Lg * ys, 2);
  s.Q = 2 * dp / (Cs + std::sqrt(Cs * Cs + 4 * a * dp));
  s.p.assign(n, p_sup);
  for (std::size_t i = 0; i <= isep; ++i)
  {
    const double v = s.Q / (2 * Lg * y[i]);
    s.p[i] = p_sub - 0.5 * rho * v * v - s.Q * C[i];
  }
  s.separation_index = isep;
  s.separation_x = x[isep][0]
                   + s.separation_frac
                         * (isep + 1 < n ? x[isep + 1][0] - x[isep][0] : 0.0);
  return s;
}
//-----------------------------------------------------------------------------
fsai::glottis::BernoulliState
fsai::glottis::bernoulli_flow(const FoldProfile& profile,
                              const RigidMotion& motion, double p_sub,
                              double p_sup, double rho, double separation_ratio)
{
  const auto x = moved_surface(profile, motion);
  const std::size_t n = x.size();
  const double Lg = profile.geometry().depth;
  const auto sp = surface_pressure(x, Lg, p_sub, p_sup, rho, separation_ratio);
  const auto& p = sp.p;
  const std::size_t isep = sp.separation_index;
  BernoulliState s;
  s.Q = sp.Q;
  s.min_gap = sp.min_gap;
  s.separation_x = sp.separation_x;
  // The segment that holds the separation point: the attached part ends at
  // p_sup (there the gap is y_s, the jet speed), the rest is p_sup
  double p_seg_sep = NAN; // mean pressure of segment [isep, isep + 1]
  if (s.min_gap > 0 and isep + 1 < n)
  {
    const double frac = sp.separation_frac;
    p_seg_sep = frac * 0.5 * (p[isep] + p_sup) + (1 - frac) * p_sup;
  }

  // Force of the pressure on each segment (into the fold: the fold lies to
  // the left of the point order), and its virtual work on (h, φ)
  const auto& Xm = profile.midpoints();
  const auto& wm = profile.midpoint_weights();
  for (std::size_t i = 0; i + 1 < n; ++i)
  {
    const double tx = x[i + 1][0] - x[i][0], ty = x[i + 1][1] - x[i][1];
    const double pm = (i == isep and !std::isnan(p_seg_sep))
                          ? p_seg_sep
                          : 0.5 * (p[i] + p[i + 1]);
    const std::array<double, 2> f = {-pm * ty * Lg, pm * tx * Lg};
    s.force[0] += f[0];
    s.force[1] += f[1];
    const auto d = motion.derivatives(Xm[i]);
    for (int k = 0; k < 2; ++k)
      s.generalised[k] += wm[i] * (f[0] * d[k][0] + f[1] * d[k][1]);
  }
  return s;
}
