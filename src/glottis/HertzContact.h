// Copyright (C) 2026 fsai developers
//
// Impact of the fold on the symmetry axis (docs/model.md §5; Horáček, Šidlof &
// Švec 2005): when an edge circle of the medial surface (radius r =
// --glottis.medial_radius; inferior or superior edge, whichever crosses, both
// when the fold closes flat) crosses y = 0 by δ > 0,
//   F_H = k_H δ^{3/2} (1 + b_H δ̇),   k_H = (4/3) E/(1 − μ_H²) √r,
// pushing the fold back (+y) at the circle's lowest point.
// 2D / depth scaling: the symmetric model stands for two equal folds that
// overlap by 2δ. Two equal spheres (E* = E/(2(1 − μ²)), radius r/2,
// indentation 2δ) give exactly the sphere-on-rigid-plane force above with δ,
// so k_H needs no symmetry factor. The force acts on the whole rigid fold
// (mass ρ A L_g), like the fluid force, which is the 2D force per unit depth
// times L_g: the contact is lumped at the coronal section, not spread
// along L_g (a line contact would be linear in δ).
#pragma once
#include "FoldProfile.h"
#include <array>

namespace fsai::common
{
class Parameters;
}

namespace fsai::glottis
{
/// [contact] section
struct ContactParameters
{
  double E = 8e3;   ///< Young's modulus of the colliding tissue [Pa]
  double nu = 0.4;  ///< Poisson's ratio μ_H
  double b_H = 0.0; ///< damping coefficient b_H [s/m] (0: elastic impact)
  void bind(fsai::common::Parameters& p);
  void validate() const;
};

struct ContactState
{
  double penetration = 0; ///< largest δ ≥ 0 of the two edges [m]
  double force = 0;       ///< total F_H ≥ 0, along +y [N]
  std::array<double, 2> generalised{}; ///< (Q_h, Q_φ) of F_H
};

/// Hertz stiffness k_H [N/m^{3/2}]
double hertz_stiffness(const ContactParameters& p, double radius);

/// Contact force of the edge circles (reference centres `centres`, radius
/// `radius`) moved by `motion` with velocities (ḣ, φ̇)
ContactState hertz_contact(const ContactParameters& p,
                           const std::array<std::array<double, 2>, 2>& centres,
                           double radius, const RigidMotion& motion,
                           const std::array<double, 2>& qdot);
} // namespace fsai::glottis
