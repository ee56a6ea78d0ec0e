// Copyright (C) 2026 fsai developers
//
// Limit-cycle measures of the glottis scene from its time series: f0 from
// the upward mean crossings of the gap g(t) (each after the gap has been
// a quarter of its amplitude below the mean: a dip of the open phase
// across the mean is not a cycle), and per cycle whether the
// glottis closed (g ≤ g_closed: the closure threshold g_min of the scene,
// where the FE flow boundary stops and the porous region takes over), the
// open quotient (share of time with g > g_closed), the peak flow and the
// closed-phase leakage (largest |Q| while closed, relative to the peak);
// and how regular the cycles are: the coefficients of variation (standard
// deviation over mean) of the cycle periods and of the per-cycle peak
// flows (jitter- and shimmer-like; 0 for a limit cycle); and whether the
// window has settled: the drift of the per-cycle peak flow and period, the
// mean of the later half of the cycles less that of the earlier half,
// over the mean of all (0 on a limit cycle; a start-up transient that is
// still dying out, or a slow drift, makes it nonzero — the FE
// closing cycle drifts by −2 % over [0.05, 0.1] s and −1 % over
// [0.1, 0.2] s).
#pragma once
#include <vector>

namespace fsai::glottis
{
struct CycleStats
{
  int cycles = 0;            ///< complete cycles in the window
  double f0_hz = 0;          ///< 0 if fewer than 2 cycles
  double open_quotient = 1;  ///< time share with g > g_closed
  double q_peak = 0;         ///< largest Q [m³/s]
  double closed_leakage = 0; ///< max |Q| with g ≤ g_closed, over q_peak
  bool closes_every_cycle = false;
  double gap_amplitude = 0; ///< (max g − min g)/2 [m]
  double period_cv = 0;     ///< CV of the cycle periods
  double q_peak_cv = 0;     ///< CV of the per-cycle peak flows
  double q_peak_mean = 0;   ///< mean of the per-cycle peak flows [m³/s]
  double q_peak_drift = 0;  ///< drift of the per-cycle peak flows
  double period_drift = 0;  ///< drift of the cycle periods
};

/// Factor of the subglottal pressure at time t when it ramps up smoothly
/// over `duration` (½(1 − cos πt/duration), then 1; duration 0: 1)
double pressure_ramp(double t, double duration);

/// Statistics of the samples with t ≥ t_from (uniform or not)
CycleStats cycle_stats(const std::vector<double>& t,
                       const std::vector<double>& gap,
                       const std::vector<double>& Q, double t_from,
                       double g_closed = 0.0);
} // namespace fsai::glottis
