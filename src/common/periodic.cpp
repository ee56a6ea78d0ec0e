// Copyright (C) 2026 fsai developers
#include "periodic.h"
#include <algorithm>
#include <stdexcept>

fsai::common::PeriodicStats
fsai::common::periodic_stats(const std::vector<double>& t,
                             const std::vector<double>& v, double t_from)
{
  if (t.size() != v.size())
    throw std::invalid_argument("periodic_stats: t and v differ in length");
  std::size_t i0 = 0;
  while (i0 < t.size() and t[i0] < t_from)
    ++i0;
  PeriodicStats s;
  if (i0 == t.size())
    return s;
  const auto [lo, hi] = std::minmax_element(v.begin() + i0, v.end());
  s.mean = 0.5 * (*lo + *hi);
  s.amplitude = 0.5 * (*hi - *lo);
  double first = 0, last = 0;
  for (std::size_t i = i0 + 1; i < t.size(); ++i)
  {
    if (v[i - 1] < s.mean and v[i] >= s.mean)
    {
      const double tc
          = t[i - 1]
            + (t[i] - t[i - 1]) * (s.mean - v[i - 1]) / (v[i] - v[i - 1]);
      if (s.crossings++ == 0)
        first = tc;
      last = tc;
    }
  }
  if (s.crossings >= 2)
    s.frequency = (s.crossings - 1) / (last - first);
  return s;
}
