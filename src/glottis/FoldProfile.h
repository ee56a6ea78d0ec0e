// Copyright (C) 2026 fsai developers
//
// The coronal profile of one vocal fold in the 2D symmetric glottis scene
// (docs/model.md §5), and its rigid motion.
//
// Coordinates: x along the flow (inferior → superior), y across the
// channel; the symmetry axis y = 0 is the contact plane, the channel wall
// y = H carries the fold. The profile is M5-like (Scherer et al. 2001): a
// straight convergent inferior surface from the wall at x = 0, a flat
// medial surface of thickness T_m at the rest half-gap g0 with rounded
// inferior and superior edges (circles of radius R), and a steep straight
// superior surface back to the wall at x = T:
//
//       y = H ──┐                               ┌── wall
//                \ inferior               superior /
//                 \                              /
//                  ╰──(R)──── T_m ────(R)──╯     medial surface y = g0
//       y = 0 ─────────────── symmetry axis ───────────────
//
// A rigid rotation tilts the flat medial surface, so the glottis becomes
// convergent or divergent: the mechanism of flow-induced self-oscillation
// of a rigid 2-DOF profile (a fully rounded medial surface would not change
// shape under rotation).
//
// The 2-DOF fold moves this profile rigidly: translation h (positive
// towards the axis) and rotation φ (counter-clockwise) about the elastic
// axis X_EA (docs/model.md G1):
//   u(X) = (0, −h) + (R(φ) − I)(X − X_EA).
// The profile within `taper` of the wall is the attachment band (the fold's
// body, fixed to the thyroid cartilage); the part below it is the vibrating
// rigid body (cover and ligament) whose mass and inertia the 2-DOF model
// uses. On the surface the motion fades smoothly to zero across the band,
// so the flow boundary stays a closed, untangled curve; the generalised
// forces use the same tapered virtual displacements (consistent work).
#pragma once
#include <array>
#include <cmath>
#include <optional>
#include <vector>

namespace fsai::common
{
class Parameters;
}

namespace fsai::glottis
{
/// Profile and channel geometry ([glottis] section), lengths in m
struct GlottisGeometry
{
  double half_height = 8e-3; ///< channel half-width H (trachea ≈ 16–20 mm)
  double inlet_length = 20e-3;    ///< subglottal channel before the fold
  double outlet_length = 40e-3;   ///< supraglottal channel after the fold
  double fold_length = 9e-3;      ///< T: fold extent along the wall (x)
  double medial_x = 5.5e-3;       ///< x of the medial surface's centre
  double medial_thickness = 4e-3; ///< T_m: flat medial surface length
  double medial_radius = 1e-3;    ///< R: edge curvature radius (Hertz radius)
  double rest_gap = 0.2e-3;       ///< g0: rest half-gap
  double depth = 18e-3;           ///< L_g: fold length (anterior–posterior)
  double taper = 3e-3; ///< attachment band at the wall (fixed body; motion
                       ///< fades across it)
  void bind(fsai::common::Parameters& p);
  void validate() const;
};

/// Rigid-body mass properties of the vibrating part (below the attachment
/// band) of the profile, times the depth
struct MassProperties
{
  double area = 0;                  ///< cross-section [m²]
  std::array<double, 2> centroid{}; ///< [m]
  double mass = 0;                  ///< ρ A L_g [kg]
  double inertia_centroid = 0;      ///< about the centroid [kg m²]
};

class FoldProfile
{
public:
  /// @param[in] n Points on the polyline (≥ 50)
  explicit FoldProfile(const GlottisGeometry& g, int n = 300);

  /// Reference surface points, ordered from the inferior wall attachment
  /// (x = 0, y = H) to the superior one (x = T, y = H); the fold lies to
  /// the left of this direction
  const std::vector<std::array<double, 2>>& points() const { return _pts; }
  /// Taper weight w ∈ [0, 1] of each point (0 at the wall)
  const std::vector<double>& weights() const { return _w; }
  /// Midpoints of the surface segments [i, i + 1] and their taper weights
  const std::vector<std::array<double, 2>>& midpoints() const { return _mid; }
  const std::vector<double>& midpoint_weights() const { return _wmid; }
  /// Taper weight of any reference point (by its distance from the wall)
  double weight(const std::array<double, 2>& X) const;
  /// Centres of the inferior and superior edge circles (reference)
  const std::array<std::array<double, 2>, 2>& edge_centres() const
  {
    return _centres;
  }
  const GlottisGeometry& geometry() const { return _g; }
  MassProperties mass_properties(double density) const;
  /// True if the reference point lies inside the fold
  bool contains(const std::array<double, 2>& X) const;
  /// Arc length from the inferior attachment along the surface to the
  /// point of the surface nearest to X [m]
  double arc_length(const std::array<double, 2>& X) const;

private:
  GlottisGeometry _g;
  std::array<std::array<double, 2>, 2> _centres;
  std::vector<std::array<double, 2>> _pts;
  std::vector<double> _w;
  std::vector<std::array<double, 2>> _mid;
  std::vector<double> _wmid;
};

/// The point of the open polyline p nearest to X: on segment k (p[k] to
/// p[k + 1]) at the fraction t ∈ [0, 1], at the squared distance d2 (the
/// first such segment on ties)
struct PolylinePoint
{
  std::size_t k = 0;
  double t = 0;
  double d2 = 0;
};
PolylinePoint nearest_on_polyline(const std::vector<std::array<double, 2>>& p,
                                  const std::array<double, 2>& X);

/// The first proper crossing of two non-adjacent segments of the open
/// polyline p, or nullopt
std::optional<std::array<double, 2>>
polyline_crossing(const std::vector<std::array<double, 2>>& p);

/// Whether X lies inside the closed polygon p (the last point joined to the
/// first; even–odd rule)
bool polygon_contains(const std::vector<std::array<double, 2>>& p,
                      const std::array<double, 2>& X);

/// Distance of X from the closed polygon p's outline, positive inside
/// (even–odd rule), negative outside
double polygon_signed_distance(const std::vector<std::array<double, 2>>& p,
                               const std::array<double, 2>& X);

/// The closed polygon p (even–odd rule) for many inside tests and
/// distances, each the same as polygon_contains / polygon_signed_distance
/// gives: the edges are binned in horizontal strips, so a query visits only
/// the edges its horizontal ray can cross and those within `reach` of it
/// (the porous marking queries every candidate cell at every mesh move).
/// p must outlive the index.
class PolygonIndex
{
public:
  /// @param[in] reach Distances below it are exact; beyond it
  /// signed_distance() gives a value of the right sign and |d| ≥ reach
  PolygonIndex(const std::vector<std::array<double, 2>>& p, double reach);
  bool contains(const std::array<double, 2>& X) const;
  double signed_distance(const std::array<double, 2>& X) const;

private:
  int strip(double y) const; // −1 below the polygon, _n above it
  const std::vector<std::array<double, 2>>& _p;
  double _reach, _y0 = 0, _h = 1;
  int _n = 0;
  // Per strip (CSR), the edges i (from p[i] to p[i−1]) whose y-range meets
  // it, and those whose y-range widened by reach meets it
  std::vector<int> _cross_start, _cross, _near_start, _near;
};

/// Rigid motion of the profile by (h, φ) about the elastic axis
struct RigidMotion
{
  RigidMotion() = default;
  RigidMotion(double h_, double phi_, std::array<double, 2> axis_)
      : h(h_), phi(phi_), axis(axis_), _c(std::cos(phi_)), _s(std::sin(phi_))
  {
  }
  double h = 0, phi = 0;        ///< translation [m], rotation [rad]
  std::array<double, 2> axis{}; ///< X_EA (reference)
  /// Displacement u(X) of a reference point (untapered)
  std::array<double, 2> displacement(const std::array<double, 2>& X) const;
  /// ∂u/∂h and ∂u/∂φ at X (virtual displacements for generalised forces)
  std::array<std::array<double, 2>, 2>
  derivatives(const std::array<double, 2>& X) const;
  /// Inverse map: the reference point that moves to x (for "is x inside
  /// the moved fold?")
  std::array<double, 2> reference_of(const std::array<double, 2>& x) const;

private:
  double _c = 1, _s = 0; // cos φ, sin φ
};
} // namespace fsai::glottis
