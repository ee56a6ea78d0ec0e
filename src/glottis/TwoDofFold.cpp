// Copyright (C) 2026 fsai developers
#include "TwoDofFold.h"
#include <cmath>
#include <common/Parameters.h>
#include <common/errors.h>

void fsai::glottis::TwoDofParameters::bind(fsai::common::Parameters& p)
{
  p.add("vf.density", density, "tissue density [kg/m^3]");
  p.add("vf.f1", f1, "first in-vacuo eigenfrequency [Hz]");
  p.add("vf.f2", f2, "second in-vacuo eigenfrequency [Hz]");
  p.add("vf.zeta1", zeta1, "modal damping ratio of mode 1");
  p.add("vf.zeta2", zeta2, "modal damping ratio of mode 2");
  p.add("vf.axis_dx", axis_dx,
        "elastic axis x relative to the profile centroid [m]");
  p.add("vf.axis_dy", axis_dy,
        "elastic axis y relative to the profile centroid [m]");
  p.add_choice("vf.first_mode", first_mode, {"translation", "rotation"},
               "motion of the lower eigenfrequency f1");
  p.add("vf.h0", h0, "initial displacement h (perturbation) [m]");
}

void fsai::glottis::TwoDofParameters::validate() const
{
  fsai::require_positive("--vf.density", density);
  fsai::require_positive("--vf.f1", f1);
  fsai::require(f2 > f1, "--vf.f2", "> --vf.f1", f2);
  fsai::require_range("--vf.zeta1", zeta1, 0.0, 1.0);
  fsai::require_range("--vf.zeta2", zeta2, 0.0, 1.0);
}

fsai::glottis::Vec2 fsai::glottis::solve2(const Mat2& A, const Vec2& b)
{
  const double det = A[0][0] * A[1][1] - A[0][1] * A[1][0];
  return {(b[0] * A[1][1] - A[0][1] * b[1]) / det,
          (A[0][0] * b[1] - A[1][0] * b[0]) / det};
}

fsai::glottis::Modes2 fsai::glottis::modes(const Mat2& K, const Mat2& M)
{
  // A = M⁻¹K (similar to a symmetric matrix: real eigenvalues)
  const Vec2 c0 = solve2(M, {K[0][0], K[1][0]});
  const Vec2 c1 = solve2(M, {K[0][1], K[1][1]});
  const Mat2 A = {{{c0[0], c1[0]}, {c0[1], c1[1]}}};
  const double tr = A[0][0] + A[1][1];
  const double det = A[0][0] * A[1][1] - A[0][1] * A[1][0];
  const double disc = std::sqrt(std::max(0.0, tr * tr / 4 - det));
  Modes2 m;
  const Vec2 lam = {tr / 2 - disc, tr / 2 + disc};
  for (int k = 0; k < 2; ++k)
  {
    // Eigenvector from a row of A − λI that is not zero (A diagonal: the
    // unit vector of the nearer diagonal entry)
    Vec2 x;
    if (A[0][1] != 0)
      x = {A[0][1], lam[k] - A[0][0]};
    else if (A[1][0] != 0)
      x = {lam[k] - A[1][1], A[1][0]};
    else if (std::abs(lam[k] - A[0][0]) <= std::abs(lam[k] - A[1][1])
             and k == 0)
      x = {1, 0};
    else if (k == 0)
      x = {0, 1};
    else
      x = m.shape[0][0] != 0 ? Vec2{0, 1} : Vec2{1, 0};
    const double n = std::sqrt(x[0] * (M[0][0] * x[0] + M[0][1] * x[1])
                               + x[1] * (M[1][0] * x[0] + M[1][1] * x[1]));
    m.shape[k] = {x[0] / n, x[1] / n};
    m.frequency_hz[k] = std::sqrt(std::max(0.0, lam[k])) / (2 * M_PI);
  }
  return m;
}

fsai::glottis::TwoDofFold::TwoDofFold(const FoldProfile& profile,
                                      const TwoDofParameters& p)
{
  p.validate();
  const MassProperties mp = profile.mass_properties(p.density);
  _axis = {mp.centroid[0] + p.axis_dx, mp.centroid[1] + p.axis_dy};
  const double m = mp.mass;
  const double dx = mp.centroid[0] - _axis[0];
  // Kinetic energy of u = (0, −h) + (R(φ) − I)(X − X_EA) at φ = 0:
  // M_hh = m, M_hφ = −∫ρ (x − x_EA) = −m dx, M_φφ = I_EA (parallel axes)
  const double S = -m * dx;
  const double I
      = mp.inertia_centroid
        + m
              * (dx * dx
                 + (mp.centroid[1] - _axis[1]) * (mp.centroid[1] - _axis[1]));
  _M = {{{m, S}, {S, I}}};
  // K = diag(k_h, k_φ) with eigenfrequencies ω1, ω2 of K x = ω² M x:
  // tr(M⁻¹K) = ω1² + ω2², det(M⁻¹K) = ω1² ω2², i.e. with a = k_h,
  // I a² − (ω1² + ω2²) det(M) a + ω1² ω2² det(M) m = 0. The smaller root
  // makes the lower mode the translation-dominated one.
  const double w1 = 2 * M_PI * p.f1, w2 = 2 * M_PI * p.f2;
  const double detM = m * I - S * S;
  const double P = w1 * w1 * w2 * w2 * detM;
  const double Q = (w1 * w1 + w2 * w2) * detM;
  const double disc = Q * Q - 4 * I * P * m;
  if (disc < 0)
  {
    throw fsai::InputError(fmt::format(
        "--vf.f1/--vf.f2: {} and {} Hz cannot both be in-vacuo frequencies "
        "with the mass coupling S = {:.3e} kg m of --vf.axis_dx = {} (move the "
        "elastic axis towards the centroid or separate the frequencies)",
        p.f1, p.f2, S, p.axis_dx));
  }
  const double kh = p.first_mode == "translation"
                        ? (Q - std::sqrt(disc)) / (2 * I)
                        : (Q + std::sqrt(disc)) / (2 * I);
  const double kphi = P / kh;
  _K = {{{kh, 0.0}, {0.0, kphi}}};
  // Modal damping: D = M Φ diag(2 ζ_k ω_k) Φᵀ M with ΦᵀMΦ = I
  const Modes2 md = modes(_K, _M);
  const Vec2 zeta = {p.zeta1, p.zeta2};
  _D = {};
  for (int k = 0; k < 2; ++k)
  {
    const auto& x = md.shape[k];
    const Vec2 Mx = {_M[0][0] * x[0] + _M[0][1] * x[1],
                     _M[1][0] * x[0] + _M[1][1] * x[1]};
    const double c = 2 * zeta[k] * 2 * M_PI * md.frequency_hz[k];
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2; ++j)
        _D[i][j] += c * Mx[i] * Mx[j];
  }
  _q0 = _q = {p.h0, 0.0};
  _held = p.held;
}

void fsai::glottis::TwoDofFold::initialise(const Vec2& Q)
{
  Vec2 r;
  for (int i = 0; i < 2; ++i)
  {
    r[i] = Q[i] - _D[i][0] * _v0[0] - _D[i][1] * _v0[1] - _K[i][0] * _q0[0]
           - _K[i][1] * _q0[1];
  }
  _a0 = _a = _held ? Vec2{0, 0} : solve2(_M, r);
}

void fsai::glottis::TwoDofFold::step(double dt, const Vec2& Q)
{
  // Newmark β = ¼, γ = ½: q = q0 + dt v0 + dt²/4 (a0 + a), v = v0 + dt/2
  // (a0 + a); solve (M + dt/2 D + dt²/4 K) a = Q − D v* − K q*
  if (_held)
    return; // q = q0, v = a = 0 (initialise)
  const double b = 0.25, g = 0.5;
  Vec2 qs, vs;
  for (int i = 0; i < 2; ++i)
  {
    qs[i] = _q0[i] + dt * _v0[i] + dt * dt * (0.5 - b) * _a0[i];
    vs[i] = _v0[i] + dt * (1 - g) * _a0[i];
  }
  Mat2 A;
  Vec2 r;
  for (int i = 0; i < 2; ++i)
  {
    for (int j = 0; j < 2; ++j)
      A[i][j] = _M[i][j] + g * dt * _D[i][j] + b * dt * dt * _K[i][j];
    r[i] = Q[i] - _D[i][0] * vs[0] - _D[i][1] * vs[1] - _K[i][0] * qs[0]
           - _K[i][1] * qs[1];
  }
  _a = solve2(A, r);
  for (int i = 0; i < 2; ++i)
  {
    _q[i] = qs[i] + b * dt * dt * _a[i];
    _v[i] = vs[i] + g * dt * _a[i];
  }
}

void fsai::glottis::TwoDofFold::accept()
{
  _q0 = _q;
  _v0 = _v;
  _a0 = _a;
}

double fsai::glottis::TwoDofFold::energy() const
{
  double e = 0;
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j)
      e += 0.5 * (_v[i] * _M[i][j] * _v[j] + _q[i] * _K[i][j] * _q[j]);
  return e;
}
