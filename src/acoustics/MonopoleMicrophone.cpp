// Copyright (C) 2026 fsai developers
#include "MonopoleMicrophone.h"
#include <algorithm>
#include <cmath>
#include <common/errors.h>

fsai::acoustics::MonopoleMicrophone::MonopoleMicrophone(double distance,
                                                        double c0, double rho0,
                                                        double dt, double lag)
    : _r(distance), _c0(c0), _rho0(rho0), _dt(dt), _lag(lag)
{
  fsai::require_positive("--mic_distance", distance);
  fsai::require_positive("microphone: time step", dt);
}
//-----------------------------------------------------------------------------
void fsai::acoustics::MonopoleMicrophone::record(double udot)
{
  _udot.push_back(udot);
  const std::size_t keep = std::size_t(std::ceil(_r / _c0 / _dt)) + 2;
  while (_udot.size() > keep)
    _udot.pop_front();
}
//-----------------------------------------------------------------------------
double fsai::acoustics::MonopoleMicrophone::pressure() const
{
  // U̇_L(t − r/c0), linear between the recorded values
  if (_udot.empty())
    return 0.0;
  const double back = std::max(0.0, _r / _c0 / _dt - _lag);
  const std::size_t i = std::size_t(std::floor(back));
  const double w = back - double(i);
  const std::size_t last = _udot.size() - 1;
  const double a = _udot[last - std::min(i, last)];
  const double b = _udot[last - std::min(i + 1, last)];
  const double udot = (1 - w) * a + w * b;
  return _rho0 * udot / (2 * M_PI * _r);
}
