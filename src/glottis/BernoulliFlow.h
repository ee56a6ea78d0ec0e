// Copyright (C) 2026 fsai developers
//
// Reduced glottal flow for the closure scene: quasi-steady 1D Bernoulli
// flow with flow separation (Pelorson et al. 1994; Horáček & Švec 2002),
// the cheap end of the FE-vs-reduced comparison of docs/model.md.
// Along the moved fold surface with half-gap y(x):
//   - p_sub is the total (lung) pressure, the subglottal velocity is
//     neglected against the glottal one;
//   - the flow separates where the half-gap first reaches k_s · y_min
//     downstream of the narrowest point (k_s = 1.2; at the narrowest point
//     itself in a divergent glottis), the jet then keeps the supraglottal
//     pressure p_sup: Q = 2 L_g y_s √(2 (p_sub − p_sup)/ρ);
//   - upstream of separation p(x) = p_sub − ½ ρ (Q / (2 L_g y(x)))², after
//     it p = p_sup;
//   - closed glottis (y_min ≤ 0): Q = 0, p_sub before the contact point,
//     p_sup after it.
// Q is the full glottal flow (both folds, depth L_g). The generalised forces
// of the pressure on the surface use the same tapered virtual displacements
// as the FE flow (FoldProfile).
#pragma once
#include "FoldProfile.h"
#include <array>
#include <vector>

namespace fsai::glottis
{
struct BernoulliState
{
  double Q = 0;                        ///< full glottal flow [m³/s]
  double min_gap = 0;                  ///< smallest half-gap of the surface [m]
  double separation_x = 0;             ///< x of the separation (contact) point
  std::array<double, 2> force{};       ///< pressure force on the fold [N]
  std::array<double, 2> generalised{}; ///< (Q_h, Q_φ)
};

/// Quasi-steady flow along a surface polyline x (ordered inferior →
/// superior, the fold to its left) of depth L_g: Q, the smallest half-gap,
/// the separation (contact) point, and the pressure at every point. The
/// pressure of a point is continuous in the motion also where the
/// separation point passes it (there y = y_s, whose Bernoulli pressure is
/// p_sup)
struct SurfacePressure
{
  double Q = 0, min_gap = 0, separation_x = 0;
  std::size_t separation_index = 0; ///< last point of the attached flow
  /// Separation at x[i] + frac (x[i+1] − x[i]), i = separation_index
  double separation_frac = 0;
  std::vector<double> p; ///< [Pa], one per point
};
SurfacePressure surface_pressure(const std::vector<std::array<double, 2>>& x,
                                 double depth, double p_sub, double p_sup,
                                 double rho, double separation_ratio);

/// The same with the viscous (Poiseuille) loss of the attached flow
/// (Pelorson et al. 1994): between the surface and the axis
///   dp/dx = −12 μ Q / (L_g (2y)³),
/// so that p(x) = p_sub − ½ ρ (Q / (2 L_g y))² − Q C(x), C(x) = 12 μ/L_g
/// ∫ dx/(2y)³ (exact for y linear on each segment), and Q solves
/// ½ ρ (Q / (2 L_g y_s))² + Q C(x_s) = p_sub − p_sup. Gaps below y_floor
/// count as y_floor: the glottis is never closed for the flow, Q falls
/// like y³ as it closes (Q ≈ 1e−11 m³/s at y_floor = 0.2 µm) and the
/// pressure drops across the contact strip. The load is then a continuous
/// function of the surface, also through closure, where the inviscid law
/// jumps (the narrowest points from p_sub − k_s² Δp to p_sub or p_sup),
/// which a strongly coupled iteration cannot converge through. The
/// reported min_gap is the true one (≤ 0 in contact).
///
/// The flow separates at y_s = k_s max(y_min, y_sep_min): with y_sep_min
/// = 0 the separation point of a closing glottis follows sub-micrometre
/// ripples of the contact strip (y_s = 1.2 y_floor), jumping by a
/// millimetre between coupling iterations; the jet of a micrometre gap is
/// not Bernoulli's anyway
SurfacePressure
viscous_surface_pressure(const std::vector<std::array<double, 2>>& x,
                         double depth, double p_sub, double p_sup, double rho,
                         double separation_ratio, double mu, double y_floor,
                         double y_sep_min);

/// Moved surface points x = X + w(X) u(X)
std::vector<std::array<double, 2>> moved_surface(const FoldProfile& profile,
                                                 const RigidMotion& motion);

/// Quasi-steady flow and pressure load for the fold in `motion`
BernoulliState bernoulli_flow(const FoldProfile& profile,
                              const RigidMotion& motion, double p_sub,
                              double p_sup, double rho,
                              double separation_ratio);
} // namespace fsai::glottis
