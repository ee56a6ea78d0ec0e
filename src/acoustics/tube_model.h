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
#include "piston_load.h"
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

/// Yielding walls of the 1D model: a shunt admittance per unit length
/// P/Z_w, Z_w = r + jωm + k/(jω) per unit wall area, P the wall perimeter
/// of a section: 2 × depth for a planar tract of that depth (its two
/// walls, as in the planar FE model), 2 √(π A) for a circular one
/// (depth 0). Each section is then a lossy line with
///   γ = √(z y), Z_c = z/γ, z = jωρ0/A, y = jωA/(ρ0 c0²) + P/Z_w,
///   chain [[cosh γl, Z_c sinh γl], [sinh γl / Z_c, cosh γl]]
struct TubeWall
{
  double mass = 0.0;       ///< [kg/m²] (0: rigid walls)
  double resistance = 0.0; ///< [Pa s/m]
  double stiffness = 0.0;  ///< [Pa/m]
  double depth = 0.0;      ///< planar depth L_g [m] (0: circular sections)
  bool rigid() const { return mass <= 0.0; }
};

/// What the tract's glottal end sees: closed (no `upstream` sections, the
/// classic transfer-function set-up), or the sections `upstream` (x from
/// its far end, the trachea, to its length, where it joins the tract at
/// the source point) ended by an anechoic or a rigid termination. The
/// source's volume velocity then divides between the tract and this branch:
/// H = P_L / (U_tract + P_0 / Z_up), Z_up the impedance looking upstream.
struct GlottalBranch
{
  fsai::mesh::AreaFunction upstream; ///< empty: closed glottal end
  bool anechoic = true;              ///< far end ρ0c0/A (else rigid)
  bool closed() const { return upstream.area.empty(); }
};

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
                           double x_obs = -1.0, const TubeWall& wall = {},
                           const GlottalBranch& branch = {});

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
                                       LipEnd end, double x_obs = -1.0,
                                       const TubeWall& wall = {},
                                       const GlottalBranch& branch = {});

/// The default observation point of tube_resonances for a lip end
double default_observation_point(const fsai::mesh::AreaFunction& af,
                                 LipEnd end);
} // namespace fsai::acoustics
