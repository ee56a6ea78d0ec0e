// Copyright (C) 2026 fsai developers
#include "waveform.h"
#include <algorithm>
#include <array>
#include <cmath>

fsai::glottis::CycleStats fsai::glottis::cycle_stats(
    const std::vector<double>& t, const std::vector<double>& gap,
    const std::vector<double>& Q, double t_from, double g_closed)
{
  CycleStats s;
  std::size_t i0 = 0;
  while (i0 < t.size() and t[i0] < t_from)
    ++i0;
  if (t.size() - i0 < 3)
    return s;
  const auto [gmin, gmax] = std::minmax_element(gap.begin() + i0, gap.end());
  const double mid = 0.5 * (*gmin + *gmax);
  s.gap_amplitude = 0.5 * (*gmax - *gmin);
  std::vector<double> up; // upward crossings of the mid value
  std::vector<std::size_t> up_i;
  // With hysteresis: a crossing counts only once the gap has been below
  // mid − A/4 since the last one. The open phase of the fold with f2 =
  // 155 Hz dips to 0.192 mm, 6 µm below its mid value, and without it
  // every cycle counted twice (f0 304.7 Hz for 151.8 Hz)
  const double arm = mid - 0.25 * s.gap_amplitude;
  bool armed = false;
  for (std::size_t i = i0 + 1; i < t.size(); ++i)
  {
    armed = armed or gap[i - 1] < arm;
    if (armed and gap[i - 1] < mid and gap[i] >= mid)
    {
      armed = false;
      up.push_back(t[i - 1]
                   + (t[i] - t[i - 1]) * (mid - gap[i - 1])
                         / (gap[i] - gap[i - 1]));
      up_i.push_back(i);
    }
  }
  if (up.size() < 3 or s.gap_amplitude <= 0)
    return s;
  s.cycles = int(up.size()) - 1;
  s.f0_hz = s.cycles / (up.back() - up.front());
  // Over complete cycles only
  double open = 0, total = 0;
  bool every = true;
  std::vector<double> periods, peaks;
  for (std::size_t c = 0; c + 1 < up_i.size(); ++c)
  {
    bool closed = false;
    double peak = 0;
    for (std::size_t i = up_i[c]; i < up_i[c + 1]; ++i)
    {
      const double dt = t[i] - t[i - 1];
      total += dt;
      if (gap[i] > g_closed)
        open += dt;
      else
        closed = true;
      peak = std::max(peak, Q[i]);
    }
    s.q_peak = std::max(s.q_peak, peak);
    every = every and closed;
    periods.push_back(up[c + 1] - up[c]);
    peaks.push_back(peak);
  }
  auto mean_cv = [](const std::vector<double>& v)
  {
    double m = 0, q = 0;
    for (double x : v)
      m += x / v.size();
    for (double x : v)
      q += (x - m) * (x - m) / v.size();
    return std::array<double, 2>{m, m > 0 ? std::sqrt(q) / m : 0.0};
  };
  // Later half against earlier half (the middle cycle of an odd count in
  // neither)
  auto drift = [](const std::vector<double>& v)
  {
    const std::size_t n = v.size(), h = n / 2;
    double early = 0, late = 0, all = 0;
    for (std::size_t i = 0; i < n; ++i)
    {
      all += v[i] / n;
      if (i < h)
        early += v[i] / h;
      if (i >= n - h)
        late += v[i] / h;
    }
    return h > 0 and all != 0 ? (late - early) / all : 0.0;
  };
  s.q_peak_drift = drift(peaks);
  s.period_drift = drift(periods);
  s.period_cv = mean_cv(periods)[1];
  const auto pk = mean_cv(peaks);
  s.q_peak_mean = pk[0];
  s.q_peak_cv = pk[1];
  s.open_quotient = total > 0 ? open / total : 1;
  s.closes_every_cycle = every;
  double leak = 0;
  for (std::size_t i = up_i.front(); i < up_i.back(); ++i)
    if (gap[i] <= g_closed)
      leak = std::max(leak, std::abs(Q[i]));
  s.closed_leakage = s.q_peak > 0 ? leak / s.q_peak : 0;
  return s;
}
//-----------------------------------------------------------------------------
double fsai::glottis::pressure_ramp(double t, double duration)
{
  return duration > 0 and t < duration
             ? 0.5 * (1 - std::cos(M_PI * t / duration))
             : 1.0;
}
