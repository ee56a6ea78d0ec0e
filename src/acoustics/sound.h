// Copyright (C) 2026 fsai developers
//
// Analysis and output of a computed sound signal (the microphone pressure
// of the voice scene): resampling, 16-bit WAV (libsndfile), fundamental
// frequency by autocorrelation, formants by linear prediction, SPL.
#pragma once
#include "tube_model.h"
#include <array>
#include <string>
#include <vector>

namespace fsai::acoustics
{
/// x (sampled every dt) low-passed at f_cut: a zero-phase Blackman-windowed
/// sinc FIR whose transition band is f_width wide (about f_cut − f_width/2
/// to f_cut + f_width/2; stop band below −74 dB), x mirrored beyond its
/// ends
std::vector<double> lowpass(const std::vector<double>& x, double dt,
                            double f_cut, double f_width);

/// x (at least two samples, every dt from t = 0) at time t in
/// [0, dt (size − 1)], linear between samples
double sample_at(const std::vector<double>& x, double dt, double t);

/// x sampled every dt, read at `rate` Hz by linear interpolation; when
/// that is a lower rate, x is first low-passed at 0.45 rate (transition
/// 0.1 rate wide: anti-aliasing). Linear interpolation changes a component
/// at f by at most (π f dt)²/2 of its amplitude
std::vector<double> resample(const std::vector<double>& x, double dt,
                             double rate);

/// Write x as a mono 16-bit PCM WAV at `rate` Hz, mean removed, scaled so
/// the peak is `peak` of full scale, 10 ms fade-in and -out (no clicks).
/// Returns the scale factor applied [1/Pa]. InputError when the file cannot
/// be written.
double write_wav(const std::string& path, const std::vector<double>& x,
                 int rate, double peak = 0.9);

/// Fundamental frequency [Hz] of x (sampled every dt) from the unbiased
/// autocorrelation of x low-passed by two boxcars of length
/// 1/(2 f_lowpass) (zeros at 2 f_lowpass and its multiples: the harmonics
/// up to ~f_lowpass stay, higher resonances and flow noise go): the first
/// maximum within `periodicity` of the largest one for periods in
/// [1/f_max, 1/f_min] (so a period, not a multiple of it), refined by a
/// parabola; NaN if x is silent. A low-pass near f0 would leave too few
/// odd harmonics to tell T0 from T0/2 when the tract amplifies h2 (default
/// [u]: h1 20 dB below h2); with 0.9 instead of 0.95, a sub-period whose
/// autocorrelation reaches 92 % of r(T0) (odd harmonics ~4 % of the energy,
/// the same run) would pass for the period.
double fundamental_frequency(const std::vector<double>& x, double dt,
                             double f_min = 60.0, double f_max = 400.0,
                             double f_lowpass = 1000.0,
                             double periodicity = 0.95);

/// Formants of a voiced signal by linear prediction (autocorrelation
/// method): resampled to 2 f_max (anti-aliased), pre-emphasis 1 − 0.97 z⁻¹,
/// Hamming window, predictor of `order` by Levinson–Durbin, roots of the
/// predictor polynomial (eigenvalues of its companion matrix); formants are the
/// root angles with bandwidth < `max_bandwidth` Hz and frequency > 90 Hz, in
/// ascending order.
std::vector<double> lpc_formants(const std::vector<double>& x, double dt,
                                 double f_max = 5000.0, int order = 12,
                                 double max_bandwidth = 500.0);
/// The same with each formant's bandwidth −ln|z| fs/π [Hz], and the
/// pre-emphasis coefficient as an option (0: none, for a signal without
/// the voice's spectral tilt)
std::vector<Resonance> lpc_resonances(const std::vector<double>& x, double dt,
                                      double f_max = 5000.0, int order = 12,
                                      double max_bandwidth = 500.0,
                                      double pre_emphasis = 0.97);

/// The periodic part of a voiced signal: x (sampled every dt) cut into its
/// whole periods T = 1/f0 from the start, each resampled to round(T/dt)
/// points (linear interpolation) and averaged (pitch-synchronous
/// averaging). What is not periodic at f0 — the free ringing of lightly
/// damped resonances after a transient, flow noise — averages out; the
/// harmonics stay. Returns one mean period (empty if x holds fewer than two
/// periods or f0 is not finite); `fraction` (optional) receives the share
/// of x's energy (mean removed) the periodic part carries.
std::vector<double> periodic_part(const std::vector<double>& x, double dt,
                                  double f0, double* fraction = nullptr);

/// Resonances of the predictor 1 + a1 z⁻¹ + … + ap z⁻ᵖ (a[0] = 1) at the
/// sample rate fs: roots (companion-matrix eigenvalues) inside the unit
/// circle with frequency in (90, f_max − 100) Hz and bandwidth
/// −ln|z| fs/π below max_bandwidth, in ascending order; roots outside the
/// circle are dropped, or with `reflect_unstable` mirrored to 1/z*
std::vector<Resonance> predictor_resonances(const std::vector<double>& a,
                                            double fs, double f_max,
                                            double max_bandwidth,
                                            bool reflect_unstable = false);

/// Formants by closed-phase covariance LPC (A10): x (sampled every dt from
/// t = 0) resampled to 2 f_max, and the predictor of `order` fitted by least
/// squares to the samples inside the `intervals` (times [s]) only, where
/// the glottis is closed and the tract rings freely, from `guard` [s] after
/// each interval's start (the closing excitation, spread by the
/// anti-aliasing filter); the regressors may precede the interval, so a
/// closed phase shorter than `order` samples still gives equations. Its
/// poles are the tract's, without the bias of the harmonics that the
/// autocorrelation method has (no window, no pre-emphasis: the free decay
/// has no source tilt); unstable roots are mirrored into the unit circle.
/// Empty if the intervals hold fewer than 3 × order equations.
std::vector<Resonance>
closed_phase_resonances(const std::vector<double>& x, double dt,
                        const std::vector<std::array<double, 2>>& intervals,
                        double f_max = 5000.0, int order = 12,
                        double max_bandwidth = 500.0, double guard = 0.3e-3);

/// Sound pressure level 20 log10(p_rms / 20 µPa) of x (mean removed)
double spl_db(const std::vector<double>& x);
} // namespace fsai::acoustics
