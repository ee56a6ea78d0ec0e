// Copyright (C) 2026 fsai developers
#include "HertzContact.h"
#include <cmath>
#include <common/Parameters.h>
#include <common/errors.h>

void fsai::glottis::ContactParameters::bind(fsai::common::Parameters& p)
{
  p.add("contact.E", E, "Young's modulus in the Hertz stiffness [Pa]");
  p.add("contact.nu", nu, "Poisson's ratio in the Hertz stiffness");
  p.add("contact.b_H", b_H, "Hertz damping coefficient b_H [s/m]");
}

void fsai::glottis::ContactParameters::validate() const
{
  fsai::require_positive("--contact.E", E);
  fsai::require(nu > -1.0 and nu < 0.5, "--contact.nu", "in (-1, 0.5)", nu);
  fsai::require(b_H >= 0, "--contact.b_H", ">= 0", b_H);
}

double fsai::glottis::hertz_stiffness(const ContactParameters& p, double radius)
{
  return 4.0 / 3.0 * p.E / (1 - p.nu * p.nu) * std::sqrt(radius);
}

fsai::glottis::ContactState fsai::glottis::hertz_contact(
    const ContactParameters& p,
    const std::array<std::array<double, 2>, 2>& centres, double radius,
    const RigidMotion& motion, const std::array<double, 2>& qdot)
{
  ContactState s;
  const double kH = hertz_stiffness(p, radius);
  for (const auto& centre : centres)
  {
    const auto u = motion.displacement(centre);
    const double yc = centre[1] + u[1];
    const double delta = radius - yc;
    if (delta <= 0)
      continue;
    s.penetration = std::max(s.penetration, delta);
    // δ̇ = −ẏ_c: the circle moves rigidly, its lowest point with the
    // centre's vertical velocity (the contact point slides along the axis)
    const auto du = motion.derivatives(centre);
    const double rate = -(du[0][1] * qdot[0] + du[1][1] * qdot[1]);
    const double F
        = std::max(0.0, kH * std::pow(delta, 1.5) * (1 + p.b_H * rate));
    s.force += F;
    // Generalised forces of (0, F) at the contact point (the moved centre
    // shifted by −r in y), by the virtual displacements of that material
    // point (taper weight 1 at the medial surface)
    const std::array<double, 2> xc = {centre[0] + u[0], yc - radius};
    const auto d = motion.derivatives(motion.reference_of(xc));
    s.generalised[0] += F * d[0][1];
    s.generalised[1] += F * d[1][1];
  }
  return s;
}
