// Copyright (C) 2026 fsai developers
//
// The measures a voice scientist reads (docs/model.md A10), from the
// glottal flow Q(t) and the sound p(t) at the microphone, both sampled
// every dt over the analysis window:
//  - cycles: Q's upward crossings of its mid-level (Q_min + Q_max)/2,
//    each after a dip below a quarter of the amplitude;
//    periods T_i, f0 = 1/mean T_i, jitter = mean |T_{i+1} − T_i| / mean T;
//  - each glottal pulse: open while Q > Q_min + 10 % of the window's AC
//    amplitude (Q_max − Q_min); open quotient OQ = open time / T, CQ =
//    1 − OQ, speed quotient SQ = opening time (open → peak) / closing time
//    (peak → closed); MFDR = the largest −dQ/dt (forward differences);
//    NAQ = AC / (MFDR T0) (Alku et al. 2002);
//  - the sound: shimmer = mean |A_{i+1} − A_i| / mean A of its peak-to-peak
//    amplitude per cycle; HNR from pitch-synchronous averaging of the N
//    whole cycles, aligned at their starts over the shortest one's length:
//    the harmonic energy H = (N S − E/N)/(N − 1) (S the energy of the mean
//    cycle, E/N that of a cycle on average), the noise E/N − H, unbiased
//    for white noise; H1–H2 from the amplitudes at f0
//    and 2 f0 of the Hann-windowed whole cycles; SPL re 20 µPa;
//    the subharmonic ratio (of the sound and of the flow, below); formants and
//    bandwidths by closed-phase covariance LPC over the closed phases
//    (Q within 2 % of the window's AC amplitude above Q_min, at least
//    0.5 ms; sound.h, closed_phase_resonances), shifted by the sound's
//    delay from the glottis to the microphone, when the caller passes them
//    (a sound without sources in the closed phase); otherwise, or if they
//    hold too few samples, by autocorrelation LPC of the periodic part
//    (sound.h), whose poles the harmonics bias.
// Each measure is the mean over the window's cycles.
#pragma once
#include <array>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace fsai::voice
{
struct GlottalFlowMeasures
{
  int cycles = 0;
  double f0_hz = NAN, jitter_pct = NAN;
  double q_peak = NAN, q_mean = NAN, q_ac = NAN; ///< [m³/s]
  double open_quotient = NAN, closed_quotient = NAN, speed_quotient = NAN;
  double mfdr = NAN; ///< [m³/s²]
  double naq = NAN;
  double shr = NAN; ///< the flow's subharmonic ratio (subharmonic_ratio)
  /// Start time of each cycle (the mid-level crossings, from the window's
  /// first sample), cycles + 1 entries
  std::vector<double> boundaries;
  /// The closed phases [start, end] (times from the window's first sample)
  std::vector<std::array<double, 2>> closed;
};
/// Cycle measures of the glottal flow Q (sampled every dt from t = 0);
/// cycles = 0 and NaN measures if Q has fewer than two whole cycles
GlottalFlowMeasures glottal_flow_measures(const std::vector<double>& Q,
                                          double dt);

struct SoundMeasures
{
  double shimmer_pct = NAN, hnr_db = NAN, h1_h2_db = NAN, spl_db = NAN;
  double shr = NAN; ///< subharmonic ratio over the flow's cycles
  std::vector<double> formants_hz, bandwidths_hz;
  std::string formant_method; ///< "closed-phase" or "periodic-part"
};
/// Measures of the sound p (sampled every dt from t = 0) over the cycles
/// `boundaries` (times, from glottal_flow_measures); formants over the
/// glottis's `closed` phases delayed by `delay` (the sound's travel time
/// from the glottis to the microphone [s])
SoundMeasures sound_measures(const std::vector<double>& p, double dt,
                             const std::vector<double>& boundaries,
                             const std::vector<std::array<double, 2>>& closed
                             = {},
                             double delay = 0.0);

/// Subharmonic-to-harmonic ratio (Sun 2002) of x (sampled every dt from
/// t = 0) over the largest even number 2M of the whole cycles
/// `boundaries` (times; M >= 2, else NaN): SHR = Σ_k |X((k − ½) f_p)| /
/// Σ_k |X(k f_p)| for the harmonics k f_p ≤ f_max of the pulse rate f_p =
/// 2M / window, X the Hann-weighted window's components. 0 for cycles that
/// repeat; a cycle that alternates (period doubling: long/short,
/// strong/weak) puts energy at the half-integer multiples of f_p, where an
/// f0 estimator then finds f_p / 2 (docs/model.md A10)
double subharmonic_ratio(const std::vector<double>& x, double dt,
                         const std::vector<double>& boundaries,
                         double f_max = 1000.0);

/// The summary's "voice" object (l/s² for the MFDR)
nlohmann::json voice_json(const GlottalFlowMeasures& flow,
                          const SoundMeasures& sound, double mic_distance);
} // namespace fsai::voice
