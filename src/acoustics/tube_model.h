// Copyright (C) 2026 fsai developers
//
// 1D reference: lossless plane-wave (Webster) model of a stepped tube by
// chain (transmission-line) matrices. Section k of length l and area A:
//   [p_in; U_in] = [[cos kl, j Z sin kl], [j sin kl / Z, cos kl]] [p_out;
//   U_out]
// with k = ω/c0, Z = ρ0 c0 / A. The lip end sees p = Z_L U with
//   Z_L = 0 (pressure release), or the low-ka piston impedances
//   Z_L = (ρ0 c0 / A_L)((ka)²/4 + j 0.6133 ka)  (unflanged, Levine–Schwinger)
//   Z_L = (ρ0 c0 / A_L)((ka)²/2 + j 0.8216 ka)  (flanged)
// (Rabiner & Schafer 1978 §3.3; Levine & Schwinger 1948).
#pragma once

#include "mesh/area_function.h"
#include <complex>
#include <string>
#include <vector>

namespace fsai::acoustics
{
/// Lip termination of the 1D model
enum class LipEnd
{
  pressure_release,
  unflanged,
  flanged
};

/// Parse "pressure-release", "unflanged", "flanged"
LipEnd lip_end_from_string(const std::string& s);

/// Transfer functions of a stepped tube at frequency f [Hz]
struct TubeResponse
{
  std::complex<double> z_in;   ///< P_glottis / U_glottis
  std::complex<double> h_lips; ///< P_lips / U_glottis
  std::complex<double> h_obs;  ///< P(x_obs) / U_glottis
};

/// Chain-matrix response of `af` at frequency f; the pressure is also
/// observed at x_obs (distance from the glottis, default: the lips)
TubeResponse tube_response(const fsai::mesh::AreaFunction& af, double f,
                           double c0, double rho0, LipEnd end,
                           double x_obs = -1.0);

/// Resonances of the tube with a closed glottis: peaks of |P(x_obs)/U_g|
/// below f_max with their -3 dB bandwidths (0 for a lossless tube with
/// p = 0). x_obs should be near the lips (every mode has pressure there,
/// unlike at the glottis, where a front-cavity mode nearly cancels with an
/// antiresonance); default: the lips, or 5 mm inside them for p = 0
struct Resonance
{
  double f;
  double bandwidth;
};
std::vector<Resonance> tube_resonances(const fsai::mesh::AreaFunction& af,
                                       double f_max, double c0, double rho0,
                                       LipEnd end, double x_obs = -1.0);

/// The default observation point of tube_resonances for a lip end
double default_observation_point(const fsai::mesh::AreaFunction& af,
                                 LipEnd end);
} // namespace fsai::acoustics
