// Copyright (C) 2026 fsai developers
#include "voice_measures.h"
#include <acoustics/sound.h>
#include <algorithm>
#include <cmath>
#include <common/errors.h>
#include <complex>
#include <numeric>

namespace
{
double mean(const std::vector<double>& v)
{
  return v.empty()
             ? NAN
             : std::accumulate(v.begin(), v.end(), 0.0) / double(v.size());
}

/// mean |v_{i+1} − v_i| / mean v, in percent
double local_perturbation(const std::vector<double>& v)
{
  if (v.size() < 2)
    return NAN;
  double d = 0;
  for (std::size_t i = 0; i + 1 < v.size(); ++i)
    d += std::abs(v[i + 1] - v[i]);
  return 100 * d / double(v.size() - 1) / mean(v);
}

/// Time where x crosses level c between samples i and i + 1
double crossing(const std::vector<double>& x, double dt, std::size_t i,
                double c)
{
  const double d = x[i + 1] - x[i];
  return dt * (double(i) + (d != 0 ? (c - x[i]) / d : 0.0));
}

/// The component of x at `bins` cycles per window [t0, t0 + L], the
/// window Hann-weighted: for a signal periodic in the window's length the
/// components at other whole bins, two or more bins away, vanish
std::complex<double> hann_component(const std::vector<double>& x, double dt,
                                    double t0, double L, double bins)
{
  std::complex<double> c = 0;
  const std::size_t i0 = std::size_t(std::ceil(t0 / dt));
  for (std::size_t i = i0; i < x.size() and dt * double(i) <= t0 + L; ++i)
  {
    const double s = (dt * double(i) - t0) / L;
    const double w = 0.5 - 0.5 * std::cos(2 * M_PI * s);
    c += w * x[i] * std::polar(1.0, -2 * M_PI * bins * s);
  }
  return c;
}
} // namespace

//-----------------------------------------------------------------------------
double fsai::voice::subharmonic_ratio(const std::vector<double>& x, double dt,
                                      const std::vector<double>& boundaries,
                                      double f_max)
{
  fsai::require_positive("sampling interval", dt);
  fsai::require_positive("subharmonic ratio: f_max", f_max);
  if (x.size() < 2)
    return NAN;
  const double t_end = dt * double(x.size() - 1);
  std::size_t n = 0; // boundaries within x
  while (n < boundaries.size() and boundaries[n] <= t_end)
    ++n;
  // An even number 2M of whole cycles, M >= 2: the subharmonics
  // (k − ½) 2M bins lie M bins from the harmonics k 2M, outside the Hann
  // window's main lobe
  const std::size_t M = n > 0 ? (n - 1) / 2 : 0;
  if (M < 2)
    return NAN;
  const double t0 = boundaries.front(), L = boundaries[2 * M] - t0;
  const double f_pulse = double(2 * M) / L;
  double harmonics = 0, subharmonics = 0;
  for (int k = 1; k == 1 or k * f_pulse <= f_max; ++k)
  {
    harmonics += std::abs(hann_component(x, dt, t0, L, double(2 * M * k)));
    subharmonics
        += std::abs(hann_component(x, dt, t0, L, double(2 * M * k - M)));
  }
  return harmonics > 0 ? subharmonics / harmonics : NAN;
}

//-----------------------------------------------------------------------------
fsai::voice::GlottalFlowMeasures
fsai::voice::glottal_flow_measures(const std::vector<double>& Q, double dt)
{
  fsai::require_positive("sampling interval", dt);
  GlottalFlowMeasures out;
  if (Q.size() < 4)
    return out;
  const auto [lo, hi] = std::minmax_element(Q.begin(), Q.end());
  const double q_min = *lo, q_ac = *hi - *lo;
  if (!(q_ac > 0))
    return out;
  const double mid = q_min + 0.5 * q_ac, thr = q_min + 0.1 * q_ac;
  // Sample before each upward mid-crossing that follows a dip below a
  // quarter of the amplitude (a wiggle of Q across the mid-level inside
  // one pulse does not start a cycle)
  std::vector<std::size_t> up;
  bool armed = false;
  for (std::size_t i = 0; i + 1 < Q.size(); ++i)
  {
    armed |= Q[i] < q_min + 0.25 * q_ac;
    if (armed and Q[i] < mid and Q[i + 1] >= mid)
    {
      up.push_back(i);
      armed = false;
    }
  }
  if (up.size() < 3)
    return out;
  std::vector<double> T, peak, ac, open, opening, closing, mfdr, qmean;
  for (std::size_t c = 0; c + 1 < up.size(); ++c)
  {
    const double t0 = crossing(Q, dt, up[c], mid);
    const double t1 = crossing(Q, dt, up[c + 1], mid);
    out.boundaries.push_back(t0);
    T.push_back(t1 - t0);
    // The cycle's samples: from the crossing to the next one
    const std::size_t a = up[c] + 1, b = up[c + 1] + 1;
    const auto pk = std::max_element(Q.begin() + a, Q.begin() + b);
    const std::size_t ip = std::size_t(pk - Q.begin());
    peak.push_back(*pk);
    ac.push_back(*pk - *std::min_element(Q.begin() + a, Q.begin() + b));
    double s = 0, rate = 0;
    for (std::size_t i = a; i < b; ++i)
      s += Q[i];
    qmean.push_back(s / double(b - a));
    for (std::size_t i = a; i < b and i + 1 < Q.size(); ++i)
      rate = std::max(rate, -(Q[i + 1] - Q[i]) / dt);
    mfdr.push_back(rate);
    // The pulse: its closing after the peak, its opening before the
    // crossing that starts the cycle (the last upward threshold crossing)
    double t_close = NAN, t_open = NAN;
    for (std::size_t i = ip; i + 1 < Q.size(); ++i)
      if (Q[i] > thr and Q[i + 1] <= thr)
      {
        t_close = crossing(Q, dt, i, thr);
        break;
      }
    for (std::size_t i = up[c] + 1; i-- > 0;)
      if (Q[i] <= thr and Q[i + 1] > thr)
      {
        t_open = crossing(Q, dt, i, thr);
        break;
      }
    const double t_peak = dt * double(ip);
    if (std::isfinite(t_open) and std::isfinite(t_close))
    {
      opening.push_back(t_peak - t_open);
      closing.push_back(t_close - t_peak);
      open.push_back((t_close - t_open) / T.back());
    }
    else if (!std::isfinite(t_close) or Q[a] > thr)
    {
      // A glottis that never closes below the threshold: open throughout
      open.push_back(1.0);
    }
  }
  out.boundaries.push_back(crossing(Q, dt, up.back(), mid));
  // Closed phases: runs within 2 % of the AC amplitude above the minimum,
  // 0.5 ms or longer
  const double shut = q_min + 0.02 * q_ac;
  for (std::size_t i = 0; i < Q.size();)
  {
    if (Q[i] > shut)
    {
      ++i;
      continue;
    }
    std::size_t j = i;
    while (j + 1 < Q.size() and Q[j + 1] <= shut)
      ++j;
    if (i > 0 and j + 1 < Q.size() and dt * double(j - i) >= 0.5e-3)
      out.closed.push_back({dt * double(i), dt * double(j)});
    i = j + 1;
  }
  out.cycles = int(T.size());
  const double T0 = mean(T);
  out.f0_hz = 1 / T0;
  out.jitter_pct = local_perturbation(T);
  out.q_peak = mean(peak);
  out.q_ac = mean(ac);
  out.q_mean = mean(qmean);
  out.open_quotient = std::min(1.0, mean(open));
  out.closed_quotient = 1 - out.open_quotient;
  double sq = 0;
  for (std::size_t i = 0; i < opening.size(); ++i)
    sq += opening[i] / closing[i] / double(opening.size());
  out.speed_quotient = opening.empty() ? NAN : sq;
  out.mfdr = mean(mfdr);
  out.naq = out.q_ac / (out.mfdr * T0);
  out.shr = subharmonic_ratio(Q, dt, out.boundaries);
  return out;
}
//-----------------------------------------------------------------------------
fsai::voice::SoundMeasures
fsai::voice::sound_measures(const std::vector<double>& p, double dt,
                            const std::vector<double>& boundaries,
                            const std::vector<std::array<double, 2>>& closed,
                            double delay)
{
  namespace ac = fsai::acoustics;
  SoundMeasures out;
  out.spl_db = ac::spl_db(p);
  if (boundaries.size() < 3 or p.size() < 4)
    return out;
  const double t_end = dt * double(p.size() - 1);
  std::vector<double> b;
  for (double t : boundaries)
    if (t <= t_end)
      b.push_back(t);
  const std::size_t N = b.size() - 1;
  if (b.size() < 3)
    return out;
  // Shimmer: peak-to-peak amplitude per cycle
  std::vector<double> amp;
  for (std::size_t c = 0; c < N; ++c)
  {
    const std::size_t i0 = std::size_t(std::ceil(b[c] / dt)),
                      i1 = std::min(p.size(), std::size_t(b[c + 1] / dt) + 1);
    const auto [lo, hi] = std::minmax_element(p.begin() + i0, p.begin() + i1);
    amp.push_back(*hi - *lo);
  }
  out.shimmer_pct = local_perturbation(amp);
  // HNR: the cycles aligned at their starts, not stretched (a resonance
  // rings at its own frequency whatever the period), over the shortest
  // cycle's n samples; their mean is the harmonic part
  double shortest = 1e300;
  for (std::size_t c = 0; c < N; ++c)
    shortest = std::min(shortest, b[c + 1] - b[c]);
  const std::size_t n = std::max<std::size_t>(8, std::size_t(shortest / dt));
  // Each cycle's n samples once (cycle c at [c n, (c + 1) n)), their mean
  // removed
  std::vector<double> cyc(N * n);
  for (std::size_t c = 0; c < N; ++c)
    for (std::size_t j = 0; j < n; ++j)
      cyc[c * n + j] = ac::sample_at(p, dt, b[c] + dt * double(j));
  const double mu = mean(cyc);
  std::vector<double> m(n, 0.0);
  double E = 0;
  for (std::size_t c = 0; c < N; ++c)
    for (std::size_t j = 0; j < n; ++j)
    {
      const double v = cyc[c * n + j] - mu;
      m[j] += v / double(N);
      E += v * v;
    }
  const double S = std::inner_product(m.begin(), m.end(), m.begin(), 0.0);
  const double H = (double(N) * S - E / double(N)) / double(N - 1);
  const double noise = E / double(N) - H;
  out.hnr_db = 10 * std::log10(std::max(H, 1e-300) / std::max(noise, 1e-300));
  // H1–H2: the window's whole cycles, Hann-weighted, projected on f0 and
  // 2 f0 (integer cycles: the other harmonics fall on the window's zeros)
  {
    const double t0 = b.front(), L = b.back() - b.front();
    out.h1_h2_db
        = 20
          * std::log10(std::abs(hann_component(p, dt, t0, L, double(N)))
                       / std::abs(hann_component(p, dt, t0, L, double(2 * N))));
  }
  out.shr = subharmonic_ratio(p, dt, b);
  // Formants: closed-phase covariance LPC, or LPC of the periodic part
  // repeated (A8)
  std::vector<std::array<double, 2>> free_decay;
  for (const auto& c : closed)
    free_decay.push_back({c[0] + delay, c[1] + delay});
  auto res = ac::closed_phase_resonances(p, dt, free_decay);
  out.formant_method = "closed-phase";
  if (res.empty())
  {
    // The periodic part: every cycle of the flow resampled to the mean
    // period's n_T samples and averaged, repeated: a cycle that ends where
    // it began. (HNR's cycles above are cut to the shortest one; repeated,
    // such a cut cycle jumps at every joint, a click train whose broadband
    // spectrum took LPC's poles from F1 once the cycles' lengths varied.)
    const std::size_t nT = std::max<std::size_t>(
        8, std::size_t(std::lround((b.back() - b.front()) / double(N) / dt)));
    std::vector<double> cycle(nT, 0.0);
    for (std::size_t c = 0; c < N; ++c)
      for (std::size_t j = 0; j < nT; ++j)
        cycle[j]
            += ac::sample_at(p, dt,
                             b[c] + (b[c + 1] - b[c]) * double(j) / double(nT))
               / double(N);
    std::vector<double> voiced;
    while (voiced.size() < std::max(p.size(), 2 * nT))
      voiced.insert(voiced.end(), cycle.begin(), cycle.end());
    res = ac::lpc_resonances(voiced, dt);
    out.formant_method = "periodic-part";
  }
  for (const auto& r : res)
  {
    out.formants_hz.push_back(r.f);
    out.bandwidths_hz.push_back(r.bandwidth);
  }
  return out;
}
//-----------------------------------------------------------------------------
nlohmann::json fsai::voice::voice_json(const GlottalFlowMeasures& f,
                                       const SoundMeasures& s,
                                       double mic_distance)
{
  // NaN is not JSON: a measure that could not be taken is null
  auto num = [](double v) -> nlohmann::json
  { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(nullptr); };
  return {{"f0_hz", num(f.f0_hz)},
          {"cycles", f.cycles},
          {"jitter_pct", num(f.jitter_pct)},
          {"shimmer_pct", num(s.shimmer_pct)},
          {"hnr_db", num(s.hnr_db)},
          {"q_peak_ls", num(1e3 * f.q_peak)},
          {"q_mean_ls", num(1e3 * f.q_mean)},
          {"q_ac_ls", num(1e3 * f.q_ac)},
          {"open_quotient", num(f.open_quotient)},
          {"closed_quotient", num(f.closed_quotient)},
          {"speed_quotient", num(f.speed_quotient)},
          {"mfdr_ls2", num(1e3 * f.mfdr)},
          {"naq", num(f.naq)},
          {"h1_h2_db", num(s.h1_h2_db)},
          {"shr", num(s.shr)},
          {"shr_flow", num(f.shr)},
          {"spl_db", num(s.spl_db)},
          {"mic_distance_m", mic_distance},
          {"formants_hz", s.formants_hz},
          {"bandwidths_hz", s.bandwidths_hz},
          {"formant_method", s.formant_method}};
}
