// Copyright (C) 2026 fsai developers
#include "sound.h"
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <common/errors.h>
#include <complex>
#include <numeric>
#include <sndfile.h>

namespace
{
std::vector<double> demeaned(const std::vector<double>& x)
{
  const double m
      = x.empty() ? 0.0 : std::accumulate(x.begin(), x.end(), 0.0) / x.size();
  std::vector<double> y(x.size());
  std::transform(x.begin(), x.end(), y.begin(),
                 [m](double v) { return v - m; });
  return y;
}
} // namespace

//-----------------------------------------------------------------------------
std::vector<double> fsai::acoustics::lowpass(const std::vector<double>& x,
                                             double dt, double f_cut,
                                             double f_width)
{
  fsai::require_positive("sampling interval", dt);
  fsai::require_positive("low-pass cut-off", f_cut);
  fsai::require_positive("low-pass transition width", f_width);
  fsai::require(f_cut < 0.5 / dt, "low-pass cut-off",
                "below the Nyquist frequency 1/(2 dt)", f_cut);
  // Blackman-windowed sinc: transition ≈ 5.5/(N Δt) wide for N taps,
  // stop band below −74 dB
  const std::size_t half
      = std::size_t(std::ceil(2.75 / (f_width * dt))); // N = 2 half + 1
  std::vector<double> h(2 * half + 1);
  const double wc = 2 * M_PI * f_cut * dt;
  for (std::size_t k = 0; k < h.size(); ++k)
  {
    const double m = double(k) - double(half);
    const double sinc = m == 0 ? wc / M_PI : std::sin(wc * m) / (M_PI * m);
    const double u = double(k) / double(h.size() - 1);
    h[k] = sinc
           * (0.42 - 0.5 * std::cos(2 * M_PI * u)
              + 0.08 * std::cos(4 * M_PI * u));
  }
  const double sum = std::accumulate(h.begin(), h.end(), 0.0);
  for (double& v : h)
    v /= sum; // unit gain at 0 Hz
  // Zero phase (centred); beyond its ends x is mirrored (x[−k] = x[k]), so
  // a constant stays constant and nothing at an end is amplified (rescaling
  // a truncated kernel instead doubled an end sample's weight)
  std::vector<double> y(x.size());
  const std::ptrdiff_t n = std::ptrdiff_t(x.size()), hh = std::ptrdiff_t(half);
  auto at = [&](std::ptrdiff_t j)
  {
    if (j < 0)
      j = -j;
    if (j >= n)
      j = 2 * (n - 1) - j;
    return x[std::clamp<std::ptrdiff_t>(j, 0, n - 1)];
  };
  for (std::ptrdiff_t i = 0; i < n; ++i)
  {
    double acc = 0;
    for (std::ptrdiff_t k = -hh; k <= hh; ++k)
      acc += h[k + hh] * at(i + k);
    y[i] = acc;
  }
  return y;
}
//-----------------------------------------------------------------------------
std::vector<double> fsai::acoustics::resample(const std::vector<double>& x,
                                              double dt, double rate)
{
  fsai::require_positive("sampling interval", dt);
  fsai::require_positive("sample rate", rate);
  if (x.size() < 2)
    return x;
  // Anti-aliasing: what lies above the new Nyquist frequency would fold
  // back into the band (an 18 kHz ringing read at 10 kHz lands at 2 kHz)
  const std::vector<double> z
      = rate < 1 / dt ? lowpass(x, dt, 0.45 * rate, 0.1 * rate) : x;
  const double T = dt * double(z.size() - 1);
  const std::size_t n = std::size_t(std::floor(T * rate)) + 1;
  std::vector<double> y(n);
  for (std::size_t i = 0; i < n; ++i)
    y[i] = sample_at(z, dt, i / rate);
  return y;
}
//-----------------------------------------------------------------------------
double fsai::acoustics::sample_at(const std::vector<double>& x, double dt,
                                  double t)
{
  const double s = t / dt;
  const std::size_t k = std::min(std::size_t(s), x.size() - 2);
  const double w = s - double(k);
  return (1 - w) * x[k] + w * x[k + 1];
}
//-----------------------------------------------------------------------------
double fsai::acoustics::write_wav(const std::string& path,
                                  const std::vector<double>& x, int rate,
                                  double peak)
{
  std::vector<double> y = demeaned(x);
  const std::size_t fade = std::min(y.size() / 2, std::size_t(0.01 * rate));
  for (std::size_t i = 0; i < fade; ++i)
  {
    const double w = 0.5 * (1 - std::cos(M_PI * i / fade));
    y[i] *= w;
    y[y.size() - 1 - i] *= w;
  }
  double m = 0;
  for (double v : y)
    m = std::max(m, std::abs(v));
  const double scale = m > 0 ? peak / m : 0.0;
  std::vector<short> pcm(y.size());
  for (std::size_t i = 0; i < y.size(); ++i)
    pcm[i] = short(std::lround(32767.0 * std::clamp(scale * y[i], -1.0, 1.0)));
  SF_INFO info{};
  info.samplerate = rate;
  info.channels = 1;
  info.format = SF_FORMAT_WAV | SF_FORMAT_PCM_16;
  SNDFILE* f = sf_open(path.c_str(), SFM_WRITE, &info);
  if (!f)
    throw fsai::InputError("cannot write '" + path
                           + "': " + sf_strerror(nullptr));
  const sf_count_t written
      = sf_write_short(f, pcm.data(), sf_count_t(pcm.size()));
  const int err = sf_close(f);
  if (written != sf_count_t(pcm.size()) or err != 0)
    throw fsai::InputError("writing '" + path + "' failed (disk full?)");
  return scale;
}
//-----------------------------------------------------------------------------
double fsai::acoustics::fundamental_frequency(const std::vector<double>& x,
                                              double dt, double f_min,
                                              double f_max, double f_lowpass,
                                              double periodicity)
{
  fsai::require_positive("f0 search: f_min", f_min);
  fsai::require_positive("f0 search: f_max", f_max);
  if (f_min >= f_max) // a signal too short for two periods of f_max
    return NAN;
  fsai::require_positive("f0 low-pass", f_lowpass);
  fsai::require(periodicity > 0 and periodicity <= 1, "f0 periodicity",
                "in (0, 1]", periodicity);
  // Low-pass first (two passes of a boxcar of 1/(2 f_lowpass): zeros at
  // 2 f_lowpass and its multiples), so that higher tract resonances and
  // broadband flow noise do not pull the autocorrelation peak
  std::vector<double> y = demeaned(x);
  const std::size_t m
      = std::max<std::size_t>(1, std::lround(0.5 / (f_lowpass * dt)));
  for (int pass = 0; pass < 2 and y.size() > m; ++pass)
  {
    std::vector<double> z(y.size() - m + 1);
    double acc = std::accumulate(y.begin(), y.begin() + m, 0.0);
    for (std::size_t i = 0; i < z.size(); ++i)
    {
      z[i] = acc / double(m);
      if (i + m < y.size())
        acc += y[i + m] - y[i];
    }
    y = std::move(z);
  }
  const std::size_t l0 = std::size_t(std::floor(1.0 / (f_max * dt)));
  const std::size_t l1 = std::size_t(std::ceil(1.0 / (f_min * dt)));
  if (y.size() < 2 * l1 + 2)
    return NAN;
  const double r0 = std::inner_product(y.begin(), y.end(), y.begin(), 0.0);
  if (!(r0 > 0))
    return NAN;
  std::vector<double> r(l1 + 2, 0.0);
  for (std::size_t l = std::max<std::size_t>(1, l0 - 1); l <= l1 + 1; ++l)
  {
    double s = 0;
    for (std::size_t i = 0; i + l < y.size(); ++i)
      s += y[i] * y[i + l];
    // unbiased: the overlap shrinks with the lag
    r[l] = s / double(y.size() - l);
  }
  double rmax = -1e300;
  for (std::size_t l = l0; l <= l1; ++l)
    rmax = std::max(rmax, r[l]);
  if (!(rmax > 0))
    return NAN;
  for (std::size_t l = std::max<std::size_t>(l0, 2); l <= l1; ++l)
  {
    if (r[l] >= periodicity * rmax and r[l] >= r[l - 1] and r[l] >= r[l + 1])
    {
      const double a = r[l - 1], b = r[l], c = r[l + 1];
      const double den = a - 2 * b + c;
      const double d = den != 0 ? 0.5 * (a - c) / den : 0.0;
      return 1.0 / ((double(l) + d) * dt);
    }
  }
  return NAN;
}
//-----------------------------------------------------------------------------
std::vector<double> fsai::acoustics::lpc_formants(const std::vector<double>& x,
                                                  double dt, double f_max,
                                                  int order,
                                                  double max_bandwidth)
{
  std::vector<double> f;
  for (const auto& r : lpc_resonances(x, dt, f_max, order, max_bandwidth))
    f.push_back(r.f);
  return f;
}
//-----------------------------------------------------------------------------
std::vector<fsai::acoustics::Resonance>
fsai::acoustics::lpc_resonances(const std::vector<double>& x, double dt,
                                double f_max, int order, double max_bandwidth,
                                double pre_emphasis)
{
  const double fs = 2 * f_max;
  std::vector<double> y = resample(demeaned(x), dt, fs);
  if (int(y.size()) < 4 * order)
    return {};
  for (std::size_t i = y.size(); i-- > 1;)
    y[i] -= pre_emphasis * y[i - 1];
  const std::size_t n = y.size();
  for (std::size_t i = 0; i < n; ++i)
    y[i] *= 0.54 - 0.46 * std::cos(2 * M_PI * i / double(n - 1));
  std::vector<double> r(order + 1, 0.0);
  for (int l = 0; l <= order; ++l)
    for (std::size_t i = 0; i + l < n; ++i)
      r[l] += y[i] * y[i + l];
  if (!(r[0] > 0))
    return {};
  // Levinson–Durbin: a[0] = 1, prediction error e
  std::vector<double> a(order + 1, 0.0), tmp;
  a[0] = 1;
  double e = r[0];
  for (int k = 1; k <= order; ++k)
  {
    double acc = r[k];
    for (int j = 1; j < k; ++j)
      acc += a[j] * r[k - j];
    const double kk = -acc / e;
    tmp = a;
    for (int j = 1; j < k; ++j)
      a[j] = tmp[j] + kk * tmp[k - j];
    a[k] = kk;
    e *= 1 - kk * kk;
    if (!(e > 0))
      return {};
  }
  return predictor_resonances(a, fs, f_max, max_bandwidth);
}
//-----------------------------------------------------------------------------
std::vector<fsai::acoustics::Resonance>
fsai::acoustics::predictor_resonances(const std::vector<double>& a, double fs,
                                      double f_max, double max_bandwidth,
                                      bool reflect_unstable)
{
  // Roots of z^p + a1 z^(p-1) + ... + ap: companion matrix eigenvalues
  const int order = int(a.size()) - 1;
  Eigen::MatrixXd C = Eigen::MatrixXd::Zero(order, order);
  for (int j = 0; j < order; ++j)
    C(0, j) = -a[j + 1];
  for (int i = 1; i < order; ++i)
    C(i, i - 1) = 1.0;
  const Eigen::VectorXcd z = C.eigenvalues();
  std::vector<Resonance> f;
  for (int i = 0; i < order; ++i)
  {
    if (z[i].imag() <= 0)
      continue;
    // A root outside the unit circle, mirrored to 1/z*: same frequency,
    // same |ln|z||, the spectrum's magnitude unchanged up to a constant
    const double r = std::abs(z[i]);
    const double ri = reflect_unstable and r > 1 ? 1 / r : r;
    const double fi = std::arg(z[i]) * fs / (2 * M_PI);
    const double bi = -std::log(ri) * fs / M_PI;
    if (fi > 90.0 and bi > 0 and bi < max_bandwidth and fi < f_max - 100.0)
      f.push_back({fi, bi});
  }
  std::sort(f.begin(), f.end(),
            [](const auto& a, const auto& b) { return a.f < b.f; });
  return f;
}
//-----------------------------------------------------------------------------
std::vector<fsai::acoustics::Resonance>
fsai::acoustics::closed_phase_resonances(
    const std::vector<double>& x, double dt,
    const std::vector<std::array<double, 2>>& intervals, double f_max,
    int order, double max_bandwidth, double guard)
{
  const double fs = 2 * f_max;
  const std::vector<double> y = resample(demeaned(x), dt, fs);
  // The rows s(n) + Σ a_k s(n − k) = 0 for n inside every interval from
  // its start + guard on: the predicted sample is source-free, its
  // regressors may lie before the interval (the excitation there is only
  // the past the tract rings from). The guard keeps out the closing
  // excitation that the anti-aliasing filter spreads past the closure.
  // Least squares, no window
  const std::size_t skip = std::size_t(std::ceil(guard * fs - 1e-9));
  std::vector<std::array<std::size_t, 2>> spans;
  std::size_t rows = 0;
  for (const auto& iv : intervals)
  {
    const std::size_t a = std::max<std::size_t>(
        std::size_t(std::ceil(std::max(0.0, iv[0]) * fs)) + skip,
        std::size_t(order));
    const std::size_t b = std::min(
        y.size(), std::size_t(std::floor(std::max(0.0, iv[1]) * fs)) + 1);
    if (b > a)
    {
      spans.push_back({a, b});
      rows += b - a;
    }
  }
  if (rows < std::size_t(3 * order))
    return {};
  Eigen::MatrixXd A(rows, order);
  Eigen::VectorXd rhs(rows);
  std::size_t r = 0;
  for (const auto& [a, b] : spans)
    for (std::size_t n = a; n < b; ++n, ++r)
    {
      rhs(r) = -y[n];
      for (int k = 1; k <= order; ++k)
        A(r, k - 1) = y[n - k];
    }
  const Eigen::VectorXd sol = A.colPivHouseholderQr().solve(rhs);
  std::vector<double> p(order + 1, 1.0);
  for (int k = 1; k <= order; ++k)
    p[k] = sol(k - 1);
  // The covariance method does not guarantee a stable predictor: over a
  // short closed phase a resonance may fit as growing (a closure spread
  // over the first samples); its frequency stands, so it is mirrored
  return predictor_resonances(p, fs, f_max, max_bandwidth, true);
}
//-----------------------------------------------------------------------------
double fsai::acoustics::spl_db(const std::vector<double>& x)
{
  const std::vector<double> y = demeaned(x);
  if (y.empty())
    return NAN;
  const double ms
      = std::inner_product(y.begin(), y.end(), y.begin(), 0.0) / y.size();
  return 10 * std::log10(ms / (20e-6 * 20e-6));
}
//-----------------------------------------------------------------------------
std::vector<double> fsai::acoustics::periodic_part(const std::vector<double>& x,
                                                   double dt, double f0,
                                                   double* fraction)
{
  fsai::require_positive("sampling interval", dt);
  if (fraction)
    *fraction = NAN;
  if (!(std::isfinite(f0) and f0 > 0) or x.size() < 4)
    return {};
  const std::vector<double> y = demeaned(x);
  const double T = 1.0 / f0;
  const std::size_t cycles
      = std::size_t(std::floor(dt * double(y.size() - 1) / T));
  const std::size_t n = std::max<std::size_t>(2, std::lround(T / dt));
  if (cycles < 2)
    return {};
  auto at = [&](double t) { return sample_at(y, dt, t); };
  std::vector<double> mean(n, 0.0);
  for (std::size_t c = 0; c < cycles; ++c)
    for (std::size_t j = 0; j < n; ++j)
      mean[j] += at((double(c) + double(j) / double(n)) * T) / double(cycles);
  if (fraction)
  {
    // energy of the cycles resampled, against that of the mean repeated
    double e_all = 0, e_mean = 0;
    for (std::size_t c = 0; c < cycles; ++c)
      for (std::size_t j = 0; j < n; ++j)
      {
        const double v = at((double(c) + double(j) / double(n)) * T);
        e_all += v * v;
        e_mean += mean[j] * mean[j];
      }
    *fraction = e_all > 0 ? e_mean / e_all : NAN;
  }
  return mean;
}
