// Copyright (C) 2026 fsai developers
//
// The vocal tract as a 1D transmission line in the time domain (docs/model.md
// A9): the reduced voice's acoustics. The same stepped tube, yielding walls
// and flanged lip load as the chain-matrix model (tube_model, A7), stepped
// explicitly:
//   C_k ṗ_k = U_k − U_{k+1} − P_k l_k v_k     C_k = A_k l_k / (ρ0 c0²)
//   L_j U̇_j = p_{j−1} − p_j                   L_j = ρ0 (l_{j−1}/2A_{j−1}
//                                                       + l_j/2A_j)
//   m v̇_k + r v_k + k w_k = p_k,  ẇ_k = v_k  (A3, per unit wall area)
// with the glottal volume flow U_0 = U_g(t) and, at the lips, the piston's
// load as a resistance R ∥ inertance L_r, matched to the flanged impedance
// of A7 at low ka: L_r = 0.8216 ρ0 a / A_L, R = 2 · 0.8216² ρ0 c0 / A_L
// (ω²L_r²/R = ρ0 c0 (ka)²/2A_L). The lip face and the load are stepped
// implicitly (their time constant is far below the step). The microphone on
// the axis at distance r hears the half-space monopole of the lip flow,
// p(r, t) = ρ0 U̇_L(t − r/c0) / (2π r).
#pragma once
#include "MonopoleMicrophone.h"
#include "tube_model.h"
#include <mesh/area_function.h>
#include <nlohmann/json.hpp>
#include <vector>

namespace fsai::acoustics
{
struct TubeTractParameters
{
  double c0 = 343.0;         ///< [m/s]
  double rho0 = 1.2;         ///< [kg/m³]
  TubeWall wall;             ///< yielding walls (rigid by default)
  double dx = 5e-4;          ///< section length of the line [m]
  double cfl = 0.9;          ///< c0 Δt_sub / min section length
  double mic_distance = 0.3; ///< [m] beyond the lips, on the axis
};

class TubeTract
{
public:
  /// The tract `af` (from the glottis to the lips) resampled to sections of
  /// at most p.dx (smooth reading, as the 1D formants), stepped in
  /// substeps of dt (the caller's step) that keep the CFL number
  TubeTract(const mesh::AreaFunction& af, const TubeTractParameters& p,
            double dt);

  /// Advance one step of dt with the glottal volume flow going linearly
  /// from its last value to `u_glottis` [m³/s]
  void step(double u_glottis);

  double time() const { return _t; }
  /// Pressure in the first section (what the glottis sees above it) [Pa]
  double p_glottis() const { return _p.front(); }
  /// Pressure at the lips (across the radiation load) [Pa]
  double p_lips() const { return _p_rad; }
  /// Volume flow out of the lips [m³/s]
  double u_lips() const { return _u.back(); }
  /// Radiated pressure at the microphone [Pa]
  double p_mic() const { return _mic.pressure(); }
  /// Sections of the line and substeps per step
  std::size_t sections() const { return _C.size(); }
  int substeps() const { return _m; }

  /// The state for a checkpoint, and back
  nlohmann::json save() const;
  void load(const nlohmann::json& j);

private:
  TubeTractParameters _par;
  double _dt, _h;
  int _m;
  std::vector<double> _C, _L, _Pl; // compliance, face inertance, P_k l_k
  double _L_lip, _R, _L_rad;
  std::vector<double> _p, _u, _v, _w; // cell p, face U, wall v, w
  double _u_rad = 0, _p_rad = 0, _ug = 0, _t = 0;
  MonopoleMicrophone _mic; // hears the lips' U̇ over each step
  double _u_lips_prev = 0;
};
} // namespace fsai::acoustics
