// Copyright (C) 2026 fsai developers
//
// The microphone of a tract that ends at the lips (A9, A11): on the axis at
// distance r it hears the half-space monopole of the lip flow,
//   p(r, t) = ρ0 U̇_L(t − r/c0) / (2π r),
// the lips' U̇ kept for as long as the sound takes to reach it.
#pragma once
#include <deque>
#include <nlohmann/json.hpp>

namespace fsai::acoustics
{
class MonopoleMicrophone
{
public:
  /// @param[in] distance r [m]; c0 [m/s], rho0 [kg/m³]; dt the step of
  ///   record() [s]
  /// @param[in] lag where a recorded value stands, in steps before the
  ///   step's end (½ for a rate over the step, 0 for an end value)
  MonopoleMicrophone(double distance, double c0, double rho0, double dt,
                     double lag);
  /// U̇_L [m³/s²] of the step just taken
  void record(double udot);
  /// Pressure at the microphone at the end of the last step [Pa]
  double pressure() const;
  /// The recorded U̇_L still needed (for a checkpoint), and back
  nlohmann::json save() const { return _udot; }
  void load(const nlohmann::json& j) { _udot = j.get<std::deque<double>>(); }

private:
  double _r, _c0, _rho0, _dt, _lag;
  std::deque<double> _udot; // newest last
};
} // namespace fsai::acoustics
