// Copyright (C) 2026 fsai developers
#include "FoldProfile.h"
#include <algorithm>
#include <cmath>
#include <common/Parameters.h>
#include <common/errors.h>
#include <limits>
#include <utility>

void fsai::glottis::GlottisGeometry::bind(fsai::common::Parameters& p)
{
  p.add("glottis.half_height", half_height, "channel half-width H [m]");
  p.add("glottis.inlet_length", inlet_length,
        "subglottal channel length before the fold [m]");
  p.add("glottis.outlet_length", outlet_length,
        "supraglottal channel length after the fold [m]");
  p.add("glottis.fold_length", fold_length,
        "fold extent T along the wall (inferior-superior) [m]");
  p.add("glottis.medial_x", medial_x, "x of the medial surface's centre [m]");
  p.add("glottis.medial_thickness", medial_thickness,
        "flat medial surface length T_m [m]");
  p.add("glottis.medial_radius", medial_radius,
        "curvature radius R of the medial edges (the Hertz radius) [m]");
  p.add("glottis.rest_gap", rest_gap, "rest half-gap g0 [m]");
  p.add("glottis.depth", depth, "fold length L_g (anterior-posterior) [m]");
  p.add("glottis.taper", taper,
        "attachment band at the wall: fixed fold body, the motion fades "
        "across it; the profile below it vibrates [m]");
}

void fsai::glottis::GlottisGeometry::validate() const
{
  for (auto [name, v] : {std::pair{"--glottis.half_height", half_height},
                         {"--glottis.inlet_length", inlet_length},
                         {"--glottis.outlet_length", outlet_length},
                         {"--glottis.fold_length", fold_length},
                         {"--glottis.medial_radius", medial_radius},
                         {"--glottis.medial_thickness", medial_thickness},
                         {"--glottis.rest_gap", rest_gap},
                         {"--glottis.depth", depth},
                         {"--glottis.taper", taper}})
  {
    fsai::require_positive(name, v);
  }
  fsai::require(rest_gap + 2 * medial_radius < half_height,
                "--glottis.rest_gap + 2 medial_radius", "< half_height",
                rest_gap + 2 * medial_radius);
  fsai::require(medial_x - medial_thickness / 2 - medial_radius > 0
                    and medial_x + medial_thickness / 2 + medial_radius
                            < fold_length,
                "--glottis.medial_x",
                "at least T_m/2 + R inside (0, fold_length)", medial_x);
  fsai::require(taper < half_height - rest_gap - medial_radius,
                "--glottis.taper", "< half_height - rest_gap - medial_radius",
                taper);
}

namespace
{
using P2 = std::array<double, 2>;

// Tangent point on the circle (c, r) of the line through p, for a path that
// runs counter-clockwise around the circle: `arrive` = the path comes from p
// to the circle, otherwise it leaves the circle towards p
double tangent_angle(P2 p, P2 c, double r, bool arrive)
{
  const double dx = p[0] - c[0], dy = p[1] - c[1];
  const double d = std::hypot(dx, dy);
  const double base = std::atan2(dy, dx), a = std::acos(r / d);
  for (double th : {base + a, base - a})
  {
    const P2 t = {c[0] + r * std::cos(th), c[1] + r * std::sin(th)};
    // counter-clockwise tangent direction at th
    const P2 dir = {-std::sin(th), std::cos(th)};
    const double s = arrive ? (t[0] - p[0]) * dir[0] + (t[1] - p[1]) * dir[1]
                            : (p[0] - t[0]) * dir[0] + (p[1] - t[1]) * dir[1];
    if (s > 0)
      return th;
  }
  return base; // not reached for d > r
}
} // namespace

fsai::glottis::FoldProfile::FoldProfile(const GlottisGeometry& g, int n) : _g(g)
{
  g.validate();
  const double H = g.half_height, R = g.medial_radius;
  _centres = {{{g.medial_x - g.medial_thickness / 2, g.rest_gap + R},
               {g.medial_x + g.medial_thickness / 2, g.rest_gap + R}}};
  const P2 A = {0.0, H}, B = {g.fold_length, H};
  const double bottom = 1.5 * M_PI; // lowest point of a circle
  double th1 = tangent_angle(A, _centres[0], R, true);
  while (th1 > bottom)
    th1 -= 2 * M_PI;
  double th2 = tangent_angle(B, _centres[1], R, false);
  while (th2 < bottom)
    th2 += 2 * M_PI;
  auto on = [&](int c, double th) -> P2
  {
    return {_centres[c][0] + R * std::cos(th),
            _centres[c][1] + R * std::sin(th)};
  };
  const P2 T1 = on(0, th1), T2 = on(1, th2);
  // Pieces: inferior line, inferior edge arc, flat medial surface,
  // superior edge arc, superior line
  const std::array<double, 5> len
      = {std::hypot(T1[0] - A[0], T1[1] - A[1]), R * (bottom - th1),
         g.medial_thickness, R * (th2 - bottom),
         std::hypot(B[0] - T2[0], B[1] - T2[1])};
  double L = 0;
  for (double l : len)
    L += l;
  n = std::max(n, 50);
  _pts.reserve(n);
  for (int i = 0; i < n; ++i)
  {
    double s = L * i / (n - 1);
    int piece = 0;
    while (piece < 4 and s > len[piece])
      s -= len[piece++];
    const double a = std::clamp(s / len[piece], 0.0, 1.0);
    P2 x;
    switch (piece)
    {
    case 0:
      x = {A[0] + a * (T1[0] - A[0]), A[1] + a * (T1[1] - A[1])};
      break;
    case 1:
      x = on(0, th1 + s / R);
      break;
    case 2:
      x = {_centres[0][0] + s, g.rest_gap};
      break;
    case 3:
      x = on(1, bottom + s / R);
      break;
    default:
      x = {T2[0] + a * (B[0] - T2[0]), T2[1] + a * (B[1] - T2[1])};
    }
    _pts.push_back(x);
  }
  _w.reserve(n);
  for (auto& x : _pts)
    _w.push_back(weight(x));
  for (std::size_t i = 0; i + 1 < _pts.size(); ++i)
  {
    _mid.push_back({0.5 * (_pts[i][0] + _pts[i + 1][0]),
                    0.5 * (_pts[i][1] + _pts[i + 1][1])});
    _wmid.push_back(weight(_mid.back()));
  }
}

double fsai::glottis::FoldProfile::weight(const std::array<double, 2>& X) const
{
  const double s = std::clamp((_g.half_height - X[1]) / _g.taper, 0.0, 1.0);
  return s * s * (3 - 2 * s);
}

fsai::glottis::MassProperties
fsai::glottis::FoldProfile::mass_properties(double density) const
{
  // The vibrating body is the part of the profile below the attachment
  // band (y ≤ H − taper); the band belongs to the fixed fold body. Clip the
  // closed surface polygon (counter-clockwise, the fold on the left) at
  // y = H − taper (Sutherland–Hodgman), then area, first and second moments
  // by Green's theorem.
  const double yc = _g.half_height - _g.taper;
  std::vector<std::array<double, 2>> poly;
  const std::size_t n0 = _pts.size();
  for (std::size_t i = 0; i < n0; ++i)
  {
    const auto& a = _pts[i];
    const auto& b = _pts[(i + 1) % n0];
    const bool ia = a[1] <= yc, ib = b[1] <= yc;
    if (ia)
      poly.push_back(a);
    if (ia != ib)
    {
      const double f = (yc - a[1]) / (b[1] - a[1]);
      poly.push_back({a[0] + f * (b[0] - a[0]), yc});
    }
  }
  double A = 0, Sx = 0, Sy = 0, Ixx = 0, Iyy = 0;
  const std::size_t n = poly.size();
  for (std::size_t i = 0; i < n; ++i)
  {
    const auto& p = poly[i];
    const auto& q = poly[(i + 1) % n];
    const double c = p[0] * q[1] - q[0] * p[1];
    A += 0.5 * c;
    Sx += c * (p[0] + q[0]) / 6;
    Sy += c * (p[1] + q[1]) / 6;
    Iyy += c * (p[0] * p[0] + p[0] * q[0] + q[0] * q[0]) / 12; // ∫x²
    Ixx += c * (p[1] * p[1] + p[1] * q[1] + q[1] * q[1]) / 12; // ∫y²
  }
  MassProperties m;
  m.area = A;
  m.centroid = {Sx / A, Sy / A};
  const double polar
      = Iyy + Ixx
        - A * (m.centroid[0] * m.centroid[0] + m.centroid[1] * m.centroid[1]);
  m.mass = density * A * _g.depth;
  m.inertia_centroid = density * polar * _g.depth;
  return m;
}

bool fsai::glottis::FoldProfile::contains(const std::array<double, 2>& X) const
{
  return polygon_contains(_pts, X);
}

double
fsai::glottis::FoldProfile::arc_length(const std::array<double, 2>& X) const
{
  // Of the nearest point of the polyline
  const auto n = nearest_on_polyline(_pts, X);
  auto length = [&](std::size_t i)
  {
    const double tx = _pts[i + 1][0] - _pts[i][0],
                 ty = _pts[i + 1][1] - _pts[i][1];
    return std::sqrt(tx * tx + ty * ty);
  };
  double arc = 0;
  for (std::size_t i = 0; i < n.k; ++i)
    arc += length(i);
  return arc + n.t * length(n.k);
}

fsai::glottis::PolylinePoint
fsai::glottis::nearest_on_polyline(const std::vector<std::array<double, 2>>& p,
                                   const std::array<double, 2>& X)
{
  PolylinePoint best{0, 0, std::numeric_limits<double>::infinity()};
  for (std::size_t k = 0; k + 1 < p.size(); ++k)
  {
    const double ex = p[k + 1][0] - p[k][0], ey = p[k + 1][1] - p[k][1];
    const double l2 = ex * ex + ey * ey;
    const double t
        = l2 > 0 ? std::clamp(
              ((X[0] - p[k][0]) * ex + (X[1] - p[k][1]) * ey) / l2, 0.0, 1.0)
                 : 0.0;
    const double dx = p[k][0] + t * ex - X[0], dy = p[k][1] + t * ey - X[1];
    if (dx * dx + dy * dy < best.d2)
      best = {k, t, dx * dx + dy * dy};
  }
  return best;
}

namespace
{
using Point = std::array<double, 2>;

// Whether the edge ab crosses the horizontal ray from X towards +x (the
// even–odd rule's test: one end above X, the other not)
bool ray_crosses(const Point& a, const Point& b, const Point& X)
{
  return (a[1] > X[1]) != (b[1] > X[1])
         and X[0] < (b[0] - a[0]) * (X[1] - a[1]) / (b[1] - a[1]) + a[0];
}

// Squared distance from X to the segment ab
double distance2(const Point& a, const Point& b, const Point& X)
{
  const double tx = b[0] - a[0], ty = b[1] - a[1];
  const double l2 = tx * tx + ty * ty;
  const double f = l2 > 0 ? std::clamp(
                       ((X[0] - a[0]) * tx + (X[1] - a[1]) * ty) / l2, 0.0, 1.0)
                          : 0.0;
  const double dx = a[0] + f * tx - X[0], dy = a[1] + f * ty - X[1];
  return dx * dx + dy * dy;
}

// Even–odd inside test of X against the closed polygon p and, if asked,
// the squared distance from X to p's outline
std::pair<bool, double> locate(const std::vector<std::array<double, 2>>& p,
                               const std::array<double, 2>& X, bool distance)
{
  bool in = false;
  double d2 = std::numeric_limits<double>::infinity();
  const std::size_t n = p.size();
  for (std::size_t i = 0, j = n - 1; i < n; j = i++)
  {
    if (ray_crosses(p[i], p[j], X))
      in = !in;
    if (distance)
      d2 = std::min(d2, distance2(p[i], p[j], X));
  }
  return {in, d2};
}
} // namespace

std::optional<std::array<double, 2>>
fsai::glottis::polyline_crossing(const std::vector<std::array<double, 2>>& p)
{
  using P = std::array<double, 2>;
  auto cross = [](const P& o, const P& a, const P& b)
  { return (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0]); };
  const std::size_t n = p.size();
  for (std::size_t i = 0; i + 1 < n; ++i)
    for (std::size_t j = i + 2; j + 1 < n; ++j)
    {
      const P &a = p[i], &b = p[i + 1], &c = p[j], &d = p[j + 1];
      const double d1 = cross(c, d, a), d2 = cross(c, d, b);
      const double d3 = cross(a, b, c), d4 = cross(a, b, d);
      // Proper crossings only: segments i and i + 2 meeting at a point
      // shared with i + 1 cannot, as they share none
      if (((d1 > 0 and d2 < 0) or (d1 < 0 and d2 > 0))
          and ((d3 > 0 and d4 < 0) or (d3 < 0 and d4 > 0)))
      {
        const double t = d1 / (d1 - d2);
        return P{a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1])};
      }
    }
  return std::nullopt;
}
//-----------------------------------------------------------------------------
bool fsai::glottis::polygon_contains(
    const std::vector<std::array<double, 2>>& p, const std::array<double, 2>& X)
{
  return locate(p, X, false).first;
}

double fsai::glottis::polygon_signed_distance(
    const std::vector<std::array<double, 2>>& p, const std::array<double, 2>& X)
{
  const auto [in, d2] = locate(p, X, true);
  return in ? std::sqrt(d2) : -std::sqrt(d2);
}

fsai::glottis::PolygonIndex::PolygonIndex(
    const std::vector<std::array<double, 2>>& p, double reach)
    : _p(p), _reach(reach)
{
  const std::size_t n = p.size();
  if (n == 0)
    return;
  double ymin = p[0][1], ymax = p[0][1];
  for (const auto& a : p)
    ymin = std::min(ymin, a[1]), ymax = std::max(ymax, a[1]);
  // Strips about as high as reach (or 1/1024 of the polygon)
  const double height = ymax - ymin + 2 * reach;
  const double target = std::max(reach, height / 1024);
  _n = target > 0 ? std::clamp(int(std::ceil(height / target)), 1, 4096) : 1;
  _y0 = ymin - reach;
  _h = height > 0 ? height / _n : 1.0;
  // floor((y − y0)/h) is monotone in y, so an edge whose range contains y
  // is listed in y's strip
  auto fill = [&](double widen, std::vector<int>& start, std::vector<int>& list)
  {
    std::vector<std::pair<int, int>> span(n);
    std::vector<int> count(_n + 1, 0);
    for (std::size_t i = 0, j = n - 1; i < n; j = i++)
    {
      const double lo = std::min(p[i][1], p[j][1]) - widen;
      const double hi = std::max(p[i][1], p[j][1]) + widen;
      span[i] = {std::clamp(strip(lo), 0, _n - 1),
                 std::clamp(strip(hi), 0, _n - 1)};
      for (int k = span[i].first; k <= span[i].second; ++k)
        ++count[k + 1];
    }
    for (int k = 0; k < _n; ++k)
      count[k + 1] += count[k];
    start = count;
    list.resize(count[_n]);
    for (std::size_t i = 0; i < n; ++i)
      for (int k = span[i].first; k <= span[i].second; ++k)
        list[count[k]++] = int(i);
  };
  fill(0.0, _cross_start, _cross);
  fill(reach * (1 + 1e-9), _near_start, _near);
}

int fsai::glottis::PolygonIndex::strip(double y) const
{
  const double k = std::floor((y - _y0) / _h);
  return k < 0 ? -1 : (k >= _n ? _n : int(k));
}

bool fsai::glottis::PolygonIndex::contains(const std::array<double, 2>& X) const
{
  const int k = strip(X[1]);
  if (k < 0 or k >= _n)
    return false;
  const std::size_t n = _p.size();
  bool in = false;
  for (int e = _cross_start[k]; e < _cross_start[k + 1]; ++e)
  {
    const std::size_t i = _cross[e], j = i == 0 ? n - 1 : i - 1;
    if (ray_crosses(_p[i], _p[j], X))
      in = !in;
  }
  return in;
}

double fsai::glottis::PolygonIndex::signed_distance(
    const std::array<double, 2>& X) const
{
  const bool in = contains(X);
  const int k = strip(X[1]);
  double d2 = std::numeric_limits<double>::infinity();
  if (k >= 0 and k < _n)
  {
    const std::size_t n = _p.size();
    for (int e = _near_start[k]; e < _near_start[k + 1]; ++e)
    {
      const std::size_t i = _near[e], j = i == 0 ? n - 1 : i - 1;
      d2 = std::min(d2, distance2(_p[i], _p[j], X));
    }
  }
  // No edge within reach: the distance is at least reach
  const double d = std::isinf(d2) ? std::max(_reach, 0.0) : std::sqrt(d2);
  return in ? d : -d;
}

std::array<double, 2>
fsai::glottis::RigidMotion::displacement(const std::array<double, 2>& X) const
{
  const double c = _c, s = _s;
  const double rx = X[0] - axis[0], ry = X[1] - axis[1];
  return {(c - 1) * rx - s * ry, -h + s * rx + (c - 1) * ry};
}

std::array<std::array<double, 2>, 2>
fsai::glottis::RigidMotion::derivatives(const std::array<double, 2>& X) const
{
  const double c = _c, s = _s;
  const double rx = X[0] - axis[0], ry = X[1] - axis[1];
  return {{{0.0, -1.0}, {-s * rx - c * ry, c * rx - s * ry}}};
}

std::array<double, 2>
fsai::glottis::RigidMotion::reference_of(const std::array<double, 2>& x) const
{
  const double c = _c, s = _s;
  const double rx = x[0] - axis[0], ry = x[1] + h - axis[1];
  return {axis[0] + c * rx + s * ry, axis[1] - s * rx + c * ry};
}
