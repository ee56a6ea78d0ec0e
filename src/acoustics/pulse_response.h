// Copyright (C) 2026 fsai developers
//
// Transfer-function method (docs/model.md §4): a broadband
// volume-velocity pulse U(t) enters at the glottis end of a vocal-tract
// mesh; the pressure is recorded at probe points (glottis, lips,
// microphone); H(f) = P(f)/U(f).
#pragma once

#include "WaveSolver.h"
#include "mesh/MeshData.h"
#include <array>
#include <functional>
#include <string>
#include <vector>

namespace fsai::common
{
class Parameters;
}

namespace fsai::acoustics
{
/// Parameters of the pulse run ([pulse] section)
struct PulseParameters
{
  double f_max = 5000.0;        ///< highest frequency of interest [Hz]
  double steps_per_period = 30; ///< time steps per period of f_max
  double duration = 0.05;       ///< simulated time [s]
  double window_decay = 0.0; ///< τ of the exp(-t/τ) window [s] (0: duration/5)
  int degree = 1;            ///< Lagrange degree of p'

  void bind(fsai::common::Parameters& p);
  void validate() const;
  double dt() const { return 1.0 / (f_max * steps_per_period); }
  double decay() const
  {
    return window_decay > 0 ? window_decay : duration / 5;
  }
};

/// How the mesh's groups map to the wave solver's boundary roles
struct TractBoundaryModel
{
  bool axisymmetric = false;
  /// Physical inlet area = inlet_measure × area_factor (planar: depth L_g,
  /// doubled for a half model; axisymmetric: 2π)
  double area_factor = 1.0;
  /// "sommerfeld" (with the curvature term of a circle/sphere of radius
  /// radiation_radius), "pml" (absorbing layer in the cells "layer" plus
  /// Sommerfeld outside it), "pressure-release" (p' = 0 on "lips"),
  /// "piston" (the flanged piston's load on "lips", A11)
  std::string radiation = "sommerfeld";
  double piston_area = 0.0;       ///< physical lip area for "piston" [m²]
  double radiation_radius = 0.08; ///< radius of the radiation boundary
  std::array<double, 3> centre{}; ///< centre of the radiation circle
  bool spherical = false;         ///< β = 1/R (3D, axisymmetric); else 1/(2R)
  bool curvature = true;          ///< false: plain Sommerfeld (β = 0)
  double layer = 0.0;             ///< absorbing-layer thickness [m]
  /// Yielding tract walls (WaveParameters::wall_*): local facets, empty for
  /// rigid walls
  std::vector<std::int32_t> yielding;
};

/// Time series of one pulse run
struct PulseResult
{
  double dt = 0.0;
  std::vector<double> t, U;           ///< volume velocity [m³/s]
  std::vector<std::vector<double>> p; ///< pressure per probe [Pa]
  std::vector<double> energy;         ///< acoustic energy per step
  std::int64_t dofs = 0;
  int steps = 0;
};

/// Run the pulse: U(t) = U0 exp(−((t − t0)/τ)²) with τ = 0.84/f_max (U(f)
/// down 60 dB at f_max), t0 = 4τ. `on_step(step, solver)` is called after
/// every step (output, progress).
PulseResult
pulse_response(const fsai::mesh::MeshData& m, const WaveParameters& wave,
               const PulseParameters& pulse, const TractBoundaryModel& bm,
               const std::vector<std::array<double, 3>>& probes,
               const std::function<void(int, const WaveSolver&)>& on_step = {});
} // namespace fsai::acoustics
