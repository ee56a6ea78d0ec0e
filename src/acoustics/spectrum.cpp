// Copyright (C) 2026 fsai developers
#include "spectrum.h"
#include "../common/errors.h"
#include <cmath>
#include <fftw3.h>
#include <limits>
#include <memory>

namespace
{
/// Real-to-complex FFT of x zero-padded to n (FFTW, estimate plan)
std::vector<std::complex<double>> rfft(const std::vector<double>& x,
                                       std::size_t n)
{
  std::vector<double> in(n, 0.0);
  std::copy(x.begin(), x.end(), in.begin());
  std::vector<std::complex<double>> out(n / 2 + 1);
  fftw_plan plan = fftw_plan_dft_r2c_1d(
      int(n), in.data(), reinterpret_cast<fftw_complex*>(out.data()),
      FFTW_ESTIMATE);
  fftw_execute(plan);
  fftw_destroy_plan(plan);
  return out;
}

std::size_t padded_length(std::size_t n, int pad)
{
  std::size_t m = 1;
  while (m < n * std::size_t(std::max(pad, 1)))
    m *= 2;
  return m;
}

double db(double m) { return 20.0 * std::log10(std::max(m, 1e-300)); }
} // namespace

//-----------------------------------------------------------------------------
fsai::acoustics::TransferFunction
fsai::acoustics::transfer_function(const std::vector<double>& x,
                                   const std::vector<double>& y, double dt,
                                   double decay, int pad)
{
  fsai::require(x.size() == y.size() and x.size() >= 8, "transfer function",
                "two signals of equal length >= 8", x.size());
  std::vector<double> xw(x), yw(y);
  for (std::size_t i = 0; i < x.size(); ++i)
  {
    const double w
        = std::isfinite(decay) ? std::exp(-double(i) * dt / decay) : 1.0;
    xw[i] *= w;
    yw[i] *= w;
  }
  const std::size_t n = padded_length(x.size(), pad);
  auto X = rfft(xw, n), Y = rfft(yw, n);
  TransferFunction tf;
  tf.window_bandwidth = std::isfinite(decay) ? 1.0 / (M_PI * decay) : 0.0;
  for (std::size_t k = 0; k < X.size(); ++k)
  {
    tf.f.push_back(double(k) / (double(n) * dt));
    tf.h.push_back(std::abs(X[k]) > 0 ? Y[k] / X[k] : 0.0);
  }
  return tf;
}
//-----------------------------------------------------------------------------
std::pair<std::vector<double>, std::vector<double>>
fsai::acoustics::amplitude_spectrum(const std::vector<double>& x, double dt,
                                    int pad)
{
  const std::size_t n = padded_length(x.size(), pad);
  auto X = rfft(x, n);
  std::vector<double> f(X.size()), a(X.size());
  for (std::size_t k = 0; k < X.size(); ++k)
  {
    f[k] = double(k) / (double(n) * dt);
    a[k] = std::abs(X[k]) * 2.0 / double(x.size());
  }
  return {f, a};
}
//-----------------------------------------------------------------------------
std::vector<fsai::acoustics::Peak> fsai::acoustics::find_peaks(
    const std::vector<double>& f, const std::vector<double>& magnitude,
    double f_min, double f_max, double min_separation, double min_prominence)
{
  const std::size_t n = f.size();
  std::vector<double> L(n);
  for (std::size_t i = 0; i < n; ++i)
    L[i] = db(magnitude[i]);

  // Candidate maxima
  std::vector<std::size_t> idx;
  for (std::size_t i = 1; i + 1 < n; ++i)
  {
    if (f[i] < f_min or f[i] > f_max)
      continue;
    if (L[i] > L[i - 1] and L[i] >= L[i + 1])
      idx.push_back(i);
  }

  // Prominence: height above the higher of the two minima that separate
  // the maximum from higher ground on either side
  auto prominence = [&](std::size_t i)
  {
    double left = L[i], right = L[i];
    for (std::size_t j = i; j-- > 0;)
    {
      if (L[j] > L[i])
        break;
      left = std::min(left, L[j]);
    }
    for (std::size_t j = i + 1; j < n; ++j)
    {
      if (L[j] > L[i])
        break;
      right = std::min(right, L[j]);
    }
    return L[i] - std::max(left, right);
  };

  std::vector<Peak> peaks;
  for (std::size_t i : idx)
  {
    if (prominence(i) < min_prominence)
      continue;
    // Parabola through (i-1, i, i+1) in dB
    const double a = L[i - 1], b = L[i], c = L[i + 1];
    const double denom = a - 2.0 * b + c;
    const double shift = denom < 0.0 ? 0.5 * (a - c) / denom : 0.0;
    const double df = f[i + 1] - f[i];
    const double fp = f[i] + shift * df;
    const double Lp = b - 0.25 * (a - c) * shift;

    // -3 dB crossings
    auto crossing = [&](int dir) -> double
    {
      for (std::ptrdiff_t j = std::ptrdiff_t(i);
           j + dir >= 0 and j + dir < std::ptrdiff_t(n); j += dir)
      {
        const double l0 = L[j], l1 = L[j + dir];
        if (l1 > l0 + 1e-12 and j != std::ptrdiff_t(i))
          return std::numeric_limits<double>::quiet_NaN(); // rising again
        if (l1 <= Lp - 3.0)
        {
          const double s = (Lp - 3.0 - l0) / (l1 - l0);
          return f[j] + s * (f[j + dir] - f[j]);
        }
      }
      return std::numeric_limits<double>::quiet_NaN();
    };
    const double fl = crossing(-1), fr = crossing(+1);
    peaks.push_back({fp, Lp, fr - fl});
  }

  // Drop maxima within min_separation of a higher one
  std::vector<Peak> kept;
  for (const Peak& p : peaks)
  {
    bool dominated = false;
    for (const Peak& q : peaks)
      if (&p != &q and std::abs(p.f - q.f) < min_separation
          and q.level_db > p.level_db)
        dominated = true;
    if (!dominated)
      kept.push_back(p);
  }
  return kept;
}
//-----------------------------------------------------------------------------
