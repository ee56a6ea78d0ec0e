// Copyright (C) 2026 fsai developers
//
// Reduced glottal flow for the closure scene: quasi-steady 1D Bernoulli
// flow with flow separation (Pelorson et al. 1994; Horáček & Švec 2002),
// the cheap end of the FE-vs-reduced comparison of shared/DESIGN.md §2.
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

/// Moved surface points x = X + w(X) u(X)
std::vector<std::array<double, 2>> moved_surface(const FoldProfile& profile,
                                                 const RigidMotion& motion);

/// Quasi-steady flow and pressure load for the fold in `motion`
BernoulliState bernoulli_flow(const FoldProfile& profile,
                              const RigidMotion& motion, double p_sub,
                              double p_sup, double rho,
                              double separation_ratio);
} // namespace fsai::glottis
