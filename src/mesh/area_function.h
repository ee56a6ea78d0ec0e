// Copyright (C) 2026 fsai developers
#pragma once

#include <string>
#include <vector>

namespace fsai::mesh
{
/// A vocal-tract area function as a stepped tube: section k spans
/// [x_end[k-1], x_end[k]] from the glottis (x_end[-1] = 0) and has the
/// cross-sectional area area[k]. SI units (m, m²).
struct AreaFunction
{
  std::vector<double> x_end;
  std::vector<double> area;
  std::string source; ///< File it came from, or a description

  /// Length of the tract (glottis to lips)
  double length() const { return x_end.empty() ? 0.0 : x_end.back(); }
  /// Start of section k
  double x_start(std::size_t k) const { return k == 0 ? 0.0 : x_end[k - 1]; }
  /// Number of sections
  std::size_t size() const { return area.size(); }
  /// Centre of section k
  double x_centre(std::size_t k) const { return 0.5 * (x_start(k) + x_end[k]); }

  /// Area at x: the section's (stepped), or linear between the section
  /// centres and constant beyond the first and last centre (smooth). The
  /// smooth reading is the tract the MRI sections sample; the stepped one
  /// is the classic concatenated-tube model, whose abrupt area jumps add
  /// 2D/3D junction inertances that a 1D model does not have.
  double area_at(double x, bool smooth) const;
};

/// The same tract as a stepped tube of sections no longer than dx, each
/// with the area at its centre (area_at): the input of the 1D model, which
/// then converges to Webster's horn equation for the smooth profile
AreaFunction resample(const AreaFunction& af, bool smooth, double dx);

/// Read an area-function CSV: lines starting with '#' are comments (the
/// source line), then a header `x_cm,area_cm2`, then one row per section:
/// the distance of the section's lip-side end from the glottis [cm]
/// (strictly increasing) and its area [cm²] (> 0).
/// @throws InputError with file and line for anything malformed
AreaFunction read_area_function(const std::string& path);

/// A uniform tube of length L [m] and area A [m²]
AreaFunction uniform_tube(double L, double A);

/// The area-function file shipped for a vowel ("u", "a", "i") in meshes/
/// (FSAI_DATA_DIR); InputError for other vowels
std::string vowel_file(const std::string& vowel);
} // namespace fsai::mesh
