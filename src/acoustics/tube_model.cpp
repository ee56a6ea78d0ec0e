// Copyright (C) 2026 fsai developers
#include "tube_model.h"
#include "../common/errors.h"
#include "spectrum.h"
#include <algorithm>
#include <array>
#include <cmath>

using cplx = std::complex<double>;
using Chain = std::array<cplx, 4>; // row-major 2x2

namespace
{
Chain multiply(const Chain& a, const Chain& b)
{
  return {a[0] * b[0] + a[1] * b[2], a[0] * b[1] + a[1] * b[3],
          a[2] * b[0] + a[3] * b[2], a[2] * b[1] + a[3] * b[3]};
}
} // namespace

//-----------------------------------------------------------------------------
fsai::acoustics::LipEnd
fsai::acoustics::lip_end_from_string(const std::string& s)
{
  if (s == "pressure-release")
    return LipEnd::pressure_release;
  if (s == "unflanged")
    return LipEnd::unflanged;
  if (s == "flanged")
    return LipEnd::flanged;
  throw fsai::InputError("lip end must be pressure-release, unflanged or "
                         "flanged (got '"
                         + s + "')");
}
//-----------------------------------------------------------------------------
fsai::acoustics::TubeResponse fsai::acoustics::tube_response(
    const fsai::mesh::AreaFunction& af, double f, double c0, double rho0,
    LipEnd end, double x_obs, const TubeWall& wall, const GlottalBranch& branch)
{
  const cplx j(0.0, 1.0);
  const double k = 2.0 * M_PI * f / c0;
  const double omega = 2.0 * M_PI * f;
  const cplx Zw = wall.rigid() ? cplx(0.0)
                               : wall.resistance + j * omega * wall.mass
                                     + wall.stiffness / (j * omega);
  const double L = af.length();
  if (x_obs < 0.0)
    x_obs = L;
  // K = chain glottis -> lips; Kb = chain x_obs -> lips
  Chain K = {1.0, 0.0, 0.0, 1.0}, Kb = K;
  for (std::size_t s = 0; s < af.size(); ++s)
  {
    const double A = af.area[s];
    const double Z = rho0 * c0 / A;
    auto section = [&](double l) -> Chain
    {
      if (wall.rigid())
      {
        const double ck = std::cos(k * l), sk = std::sin(k * l);
        return {ck, j * Z * sk, j * sk / Z, ck};
      }
      const double P
          = wall.depth > 0.0 ? 2.0 * wall.depth : 2.0 * std::sqrt(M_PI * A);
      const cplx z = j * omega * rho0 / A;
      const cplx y = j * omega * A / (rho0 * c0 * c0) + P / Zw;
      cplx g = std::sqrt(z * y);
      if (g.real() < 0.0)
        g = -g;
      const cplx Zc = z / g;
      const cplx ch = std::cosh(g * l), sh = std::sinh(g * l);
      return {ch, Zc * sh, sh / Zc, ch};
    };
    K = multiply(K, section(af.x_end[s] - af.x_start(s)));
    const double lb = af.x_end[s] - std::max(af.x_start(s), x_obs);
    if (lb > 0.0)
      Kb = multiply(Kb, section(lb));
  }
  const double AL = af.area.back();
  const double ka = k * std::sqrt(AL / M_PI);
  const double ZL0 = rho0 * c0 / AL;
  cplx ZL = 0.0;
  if (end == LipEnd::unflanged)
    ZL = ZL0 * (0.25 * ka * ka + j * 0.6133 * ka);
  else if (end == LipEnd::flanged)
    ZL = ZL0 * (0.5 * ka * ka + j * 0.8216 * ka);
  // [P_g; U_g] = K [Z_L U_L; U_L], [P_x; U_x] = Kb [Z_L U_L; U_L]
  const cplx Pg = K[0] * ZL + K[1];
  cplx Ug = K[2] * ZL + K[3];
  if (!branch.closed())
  {
    // Upstream branch (rigid walls): [p_far; U_far] = Kup [p_g; U_g'] with
    // U in +x; at the far end p = −(ρ0c0/A) U (a wave leaving towards the
    // lungs) or U = 0. Z_up = p_g / (−U_g'), the flow into the branch.
    Chain Kup = {1.0, 0.0, 0.0, 1.0};
    const auto& up = branch.upstream;
    for (std::size_t s = 0; s < up.size(); ++s)
    {
      const double Z = rho0 * c0 / up.area[s];
      const double l = up.x_end[s] - up.x_start(s);
      const double ck = std::cos(k * l), sk = std::sin(k * l);
      Kup = multiply(Kup, Chain{ck, j * Z * sk, j * sk / Z, ck});
    }
    // Invert the (unimodular) chain: [p_g; U_g'] = Kup⁻¹ [p_far; U_far]
    const cplx det = Kup[0] * Kup[3] - Kup[1] * Kup[2];
    const Chain inv
        = {Kup[3] / det, -Kup[1] / det, -Kup[2] / det, Kup[0] / det};
    const cplx p_far = branch.anechoic ? -rho0 * c0 / up.area.front() : 1.0;
    const cplx U_far = branch.anechoic ? 1.0 : 0.0;
    const cplx p_j = inv[0] * p_far + inv[1] * U_far;
    const cplx U_j = inv[2] * p_far + inv[3] * U_far;
    const cplx Z_up = -p_j / U_j;
    Ug += Pg / Z_up; // the source feeds the tract and the branch
  }
  return {Pg / Ug, ZL / Ug, (Kb[0] * ZL + Kb[1]) / Ug};
}
//-----------------------------------------------------------------------------
double
fsai::acoustics::default_observation_point(const fsai::mesh::AreaFunction& af,
                                           LipEnd end)
{
  const double L = af.length();
  return end == LipEnd::pressure_release ? L - std::min(0.005, 0.25 * L) : L;
}
//-----------------------------------------------------------------------------
std::vector<fsai::acoustics::Resonance> fsai::acoustics::tube_resonances(
    const fsai::mesh::AreaFunction& af, double f_max, double c0, double rho0,
    LipEnd end, double x_obs, const TubeWall& wall, const GlottalBranch& branch)
{
  if (x_obs < 0.0)
    x_obs = default_observation_point(af, end);
  auto scan = [&](double f0, double f1, double df)
  {
    std::vector<double> f, mag;
    for (double fi = f0; fi <= f1; fi += df)
    {
      f.push_back(fi);
      mag.push_back(std::abs(
          tube_response(af, fi, c0, rho0, end, x_obs, wall, branch).h_obs));
    }
    return std::make_pair(f, mag);
  };
  // A 4 Hz scan finds the peaks (a resonance of 1 Hz bandwidth is still a
  // clear maximum there); each is then resolved on a grid of 1/50 of its
  // width (0.01–1 Hz) over twice its width either side, where its
  // frequency and −3 dB bandwidth are read: within 0.1 Hz of a 0.25 Hz
  // scan of the whole range, at a tenth of its cost
  const double df = 4.0;
  const auto [f, mag] = scan(df, f_max + 50.0, df);
  std::vector<Resonance> out;
  for (const Peak& p : find_peaks(f, mag, 0.0, f_max))
  {
    const double width = std::isfinite(p.bandwidth) ? p.bandwidth : 50.0;
    Peak best = p;
    for (double w = 2 * std::max(width, 4.0);; w *= 2)
    {
      const double h = std::clamp(width / 50, 0.01, 1.0);
      const auto [ff, mm] = scan(std::max(p.f - w, 0.5 * h), p.f + w, h);
      const auto fine = find_peaks(ff, mm, p.f - w, p.f + w);
      if (fine.empty())
        break;
      best = *std::min_element(
          fine.begin(), fine.end(),
          [&](const Peak& a, const Peak& b)
          { return std::abs(a.f - p.f) < std::abs(b.f - p.f); });
      // Both −3 dB points inside the window, or the window already spans
      // the coarse width many times over
      if (std::isfinite(best.bandwidth) or w > 8 * width)
        break;
    }
    out.push_back({best.f, best.bandwidth});
  }
  return out;
}
//-----------------------------------------------------------------------------
fsai::acoustics::PistonLoad
fsai::acoustics::flanged_piston(double area, double c0, double rho0)
{
  fsai::require_positive("piston area", area);
  const double a = std::sqrt(area / M_PI);
  return {2 * 0.8216 * 0.8216 * rho0 * c0, 0.8216 * rho0 * a};
}
