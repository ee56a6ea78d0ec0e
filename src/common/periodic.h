// Copyright (C) 2026 fsai developers
//
// Statistics of a periodic signal in the convention of the Turek–Hron
// benchmark (turek_hron_results.csv): over the samples of a window,
// mean = (max + min)/2, amplitude = (max − min)/2, frequency from the
// upward crossings of that mean (linear interpolation between samples).
#pragma once
#include <vector>

namespace fsai::common
{
struct PeriodicStats
{
  double mean = 0, amplitude = 0;
  double frequency = 0; ///< 0 when fewer than two upward crossings
  int crossings = 0;
};

/// Statistics of the samples (t, v) with t ≥ t_from
PeriodicStats periodic_stats(const std::vector<double>& t,
                             const std::vector<double>& v, double t_from);
} // namespace fsai::common
