// Copyright (C) 2026 fsai developers
//
// Frequency analysis of sampled signals (FFTW): transfer functions by the
// ratio of spectra, peaks (formants) and their -3 dB bandwidths.
#pragma once

#include <complex>
#include <functional>
#include <vector>

namespace fsai::acoustics
{
/// A peak of a magnitude curve: frequency [Hz], level [dB], -3 dB width
/// [Hz] (NaN if a side does not fall 3 dB before the next peak)
struct Peak
{
  double f;
  double level_db;
  double bandwidth;
};

/// Transfer function H(f) = Y(f)/X(f) of two signals sampled every dt,
/// both multiplied by exp(−t/τ) (τ = `decay`, ∞ to disable) and zero-padded
/// to at least `pad` times their length. The exponential window turns the
/// spectrum ratio into H(iω + 1/τ): peak frequencies are unchanged to first
/// order, bandwidths grow by exactly 1/(π τ), which find_peaks' caller
/// subtracts.
struct TransferFunction
{
  std::vector<double> f;
  std::vector<std::complex<double>> h;
  double window_bandwidth = 0.0; ///< 1/(π τ) added to every bandwidth [Hz]
};
TransferFunction transfer_function(const std::vector<double>& x,
                                   const std::vector<double>& y, double dt,
                                   double decay, int pad = 4);

/// One-sided amplitude spectrum of a signal (FFT of length >= `pad` times
/// the signal): frequencies and |X(f)|
std::pair<std::vector<double>, std::vector<double>>
amplitude_spectrum(const std::vector<double>& x, double dt, int pad = 1);

/// Local maxima of |H| in dB between f_min and f_max, located by a
/// parabola through the three samples around each maximum; bandwidths
/// from the -3 dB crossings (linear interpolation in dB). Maxima within
/// `min_separation` Hz of a higher one, or less than `min_prominence` dB
/// above the lower of the two minima around them, are dropped.
std::vector<Peak> find_peaks(const std::vector<double>& f,
                             const std::vector<double>& magnitude, double f_min,
                             double f_max, double min_separation = 100.0,
                             double min_prominence = 3.0);
} // namespace fsai::acoustics
