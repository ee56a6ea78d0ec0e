// Copyright (C) 2026 fsai developers
#include "Sample.h"
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <stdexcept>

//-----------------------------------------------------------------------------
void fsai::glottis::require_finite(const Sample& s, std::string_view scene)
{
  for (double v : {s.gap, s.Q, s.h, s.phi, s.lift})
  {
    if (!std::isfinite(v))
    {
      throw std::runtime_error(
          fmt::format("{}: non-finite state at t = {:.6g} s", scene, s.t));
    }
  }
}
//-----------------------------------------------------------------------------
double fsai::glottis::lowest_point(const std::vector<std::array<double, 2>>& x)
{
  double g = 1e300;
  for (const auto& p : x)
    g = std::min(g, p[1]);
  return g;
}
