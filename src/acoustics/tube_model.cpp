// Copyright (C) 2026 fsai developers
#include "tube_model.h"
#include "../common/errors.h"
#include "spectrum.h"
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
fsai::acoustics::TubeResponse
fsai::acoustics::tube_response(const fsai::mesh::AreaFunction& af, double f,
                               double c0, double rho0, LipEnd end, double x_obs)
{
  const cplx j(0.0, 1.0);
  const double k = 2.0 * M_PI * f / c0;
  const double L = af.length();
  if (x_obs < 0.0)
    x_obs = L;
  // K = chain glottis -> lips; Kb = chain x_obs -> lips
  Chain K = {1.0, 0.0, 0.0, 1.0}, Kb = K;
  for (std::size_t s = 0; s < af.size(); ++s)
  {
    const double Z = rho0 * c0 / af.area[s];
    auto section = [&](double l) -> Chain
    {
      const double ck = std::cos(k * l), sk = std::sin(k * l);
      return {ck, j * Z * sk, j * sk / Z, ck};
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
  const cplx Ug = K[2] * ZL + K[3];
  return {(K[0] * ZL + K[1]) / Ug, ZL / Ug, (Kb[0] * ZL + Kb[1]) / Ug};
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
std::vector<fsai::acoustics::Resonance>
fsai::acoustics::tube_resonances(const fsai::mesh::AreaFunction& af,
                                 double f_max, double c0, double rho0,
                                 LipEnd end, double x_obs)
{
  if (x_obs < 0.0)
    x_obs = default_observation_point(af, end);
  const double df = 0.25;
  std::vector<double> f, mag;
  for (double fi = df; fi <= f_max + 50.0; fi += df)
  {
    TubeResponse r = tube_response(af, fi, c0, rho0, end, x_obs);
    f.push_back(fi);
    mag.push_back(std::abs(r.h_obs));
  }
  std::vector<Resonance> out;
  for (const Peak& p : find_peaks(f, mag, 0.0, f_max))
    out.push_back({p.f, p.bandwidth});
  return out;
}
//-----------------------------------------------------------------------------
