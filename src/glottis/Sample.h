// Copyright (C) 2026 fsai developers
#pragma once
#include <array>
#include <string_view>
#include <vector>

namespace fsai::glottis
{
/// One time step of the glottis scene (a row of series.csv)
struct Sample
{
  double t = 0;
  double gap = 0; ///< half-gap g: lowest point of the fold [m] (< 0: overlap)
  double Q = 0;   ///< glottal flow through the section at the medial surface's
                  ///< centre, both folds, depth L_g [m³/s]
  double Q_inlet = 0; ///< flow at the inlet (FE model; includes the air the
                      ///< moving inferior surface displaces) [m³/s]
  double h = 0;       ///< translation [m]
  double phi = 0;     ///< rotation [rad]
  double lift = 0;    ///< fluid force on the fold along +y [N]
  double drag = 0;    ///< fluid force along +x [N]
  double moment = 0;  ///< generalised fluid force Q_φ [N m]
  double contact_force = 0; ///< Hertz F_H [N]
  double penetration = 0;   ///< δ [m]
  int iterations = 0;       ///< coupling iterations of the step
  bool converged = true;    ///< coupling reached its tolerance
};

/// Throws std::runtime_error naming `scene` if the sample's gap, flow rate,
/// medial motion or lift is not finite (a diverged step must stop the run,
/// never write NaN rows)
void require_finite(const Sample& s, std::string_view scene);

/// The half-gap of a moved fold surface: the lowest y of its points (< 0:
/// across the symmetry axis)
double lowest_point(const std::vector<std::array<double, 2>>& x);
} // namespace fsai::glottis
