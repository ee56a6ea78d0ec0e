// Copyright (C) 2026 fsai developers
#include "VoiceScene.h"
#include "voice_measures.h"
#include <acoustics/sound.h>
#include <acoustics/spectrum.h>
#include <acoustics/tube_model.h>
#include <cmath>
#include <common/Parameters.h>
#include <common/errors.h>
#include <common/log.h>
#include <common/timer.h>
#include <fmt/ranges.h>
#include <glottis/GlottisScene.h>
#include <io/CsvWriter.h>
#include <io/RunSummary.h>

namespace ac = fsai::acoustics;

//-----------------------------------------------------------------------------
void fsai::voice::VoiceParameters::bind(fsai::common::Parameters& p)
{
  p.add("output", output, "output folder");
  p.add_choice("flow", flow, {"fe", "bernoulli"},
               "glottal flow: fe (ALE Navier-Stokes, minutes) or bernoulli "
               "(quasi-steady 1D, milliseconds)");
  p.add_choice("acoustics", acoustics, {"fe", "1d"},
               "sound: fe (wave equation on the planar tract and radiation "
               "region) or 1d (the vowel's tract as a transmission line)");
  p.add_choice("fold", fold, {"2dof", "elastic"},
               std::string("vocal fold: 2dof (rigid, two modes) or elastic "
                           "(plane-strain FE fold, --elastic.*)")
                   + glottis::elastic_fe_defaults_help()
                   + " and the glottis scene's flow mesh");
  p.add("ramp", ramp,
        "--fold elastic --flow bernoulli: p_sub ramps up over this time [s]");
  p.add_choice("vowel", vowel, {"u", "a", "i"},
               "vowel of the shipped area functions (meshes/vowel_*.csv)");
  p.add("area-function", area_function,
        "area-function CSV (x_cm,area_cm2); overrides --vowel");
  p.add_choice("tract", tract, {"vowel", "tube"},
               "vocal tract: the vowel's, or a short straight tube");
  p.add_choice("voice.tract_start", tract_start, {"glottis", "outlet"},
               "--acoustics fe: the vowel's area function starts at the "
               "glottis (the acoustic tract is the vowel's, the flow "
               "domain's wide channel overlaps it) or after the flow "
               "domain's outlet channel (which then replaces the tract's "
               "first 40 mm: the vowel's formants move, [a] by -48 % F1)");
  p.add("tube.length", tube_length, "--tract tube: length [m]");
  p.add("tube.area", tube_area, "--tract tube: area [m^2]");
  p.add("p-sub", p_sub, "subglottal pressure [Pa]");
  p.add("duration", duration, "simulated time [s]");
  p.add("dt", dt, "time step of flow and sound [s]");
  p.add("quick", quick,
        "short coarse run for tests (coarser meshes, 0.04 s, dt 5e-5)");
  p.add_choice("radiation", radiation, {"sommerfeld", "pml", "piston"},
               "--acoustics fe: a planar radiation region closed by "
               "Sommerfeld (with the curvature term) or an absorbing layer, "
               "or the tract ending at the lips with a flanged piston's load "
               "and the microphone hearing its monopole (A11)");
  p.add("layer", layer, "absorbing-layer thickness for --radiation pml [m]");
  p.add("voice.yielding_walls", yielding_walls,
        "supraglottal tract walls yield (--wave.wall_*; false: "
        "rigid walls, resonances damped by radiation only)");
  p.add_choice("voice.subglottal", subglottal, {"absorbing", "hard"},
               "subglottal end of the acoustic domain: plane-wave "
               "absorbing (anechoic trachea) or sound-hard");
  p.add("mic_distance", mic_distance,
        "microphone on the axis, this far beyond the lips [m]");
  p.add("stats_from", stats_from,
        "statistics and sound analysis over t >= stats_from * duration");
  p.add("write_every", write_every, "XDMF output every N steps (0: none)");
  p.add("wav_rate", wav_rate, "sample rate of sound.wav [Hz]");
  p.add("reanalyse", reanalyse,
        "no run: analyse the series.csv in --output again with this "
        "build's analysis (summary into reanalysis.json, the run's own "
        "summary.json kept)");
  p.add("report", report,
        "draw report.png (matplotlib, about 1 s; false in sweeps of the "
        "reduced voice)");
  p.add("check-result", check_result,
        "fail unless the sound is finite and audible (SPL > 40 dB), its "
        "f0 matches the fold's within --check.f0_tolerance and the fold "
        "f0 is in the male range 85-155 Hz");
  p.add("check.formant_tolerance", check_formant_tolerance,
        "--check-result: the sound's F1 and F2 (the voice measures') within "
        "this relative tolerance of the tract's (0: not checked)");
  p.add("check.f0_tolerance", check_f0_tolerance,
        "relative tolerance of --check-result on the sound's f0 (0: not "
        "checked)");
  run.bind(p);
}
//-----------------------------------------------------------------------------
void fsai::voice::VoiceParameters::validate() const
{
  fsai::require(ramp >= 0, "--ramp", ">= 0", ramp);
  fsai::require_positive("--p-sub", p_sub);
  fsai::require_positive("--duration", duration);
  fsai::require_positive("--dt", dt);
  fsai::require(dt <= duration / 10, "--dt", "<= --duration / 10", dt);
  fsai::require_positive("--tube.length", tube_length);
  fsai::require_positive("--tube.area", tube_area);
  fsai::require_positive("--layer", layer);
  fsai::require_positive("--mic_distance", mic_distance);
  fsai::require_range("--stats_from", stats_from, 0.0, 0.95);
  fsai::require(check_formant_tolerance >= 0, "--check.formant_tolerance",
                ">= 0", check_formant_tolerance);
  fsai::require(write_every >= 0, "--write_every", ">= 0", write_every);
  fsai::require(wav_rate == 44100 or wav_rate == 48000, "--wav_rate",
                "44100 or 48000", wav_rate);
  run.validate();
}
//-----------------------------------------------------------------------------
fsai::voice::VoiceScene::VoiceScene()
{
  // Numerical damping in the sound's Newmark step (E21): γ = 0.6,
  // β = (γ + ½)²/4. The trapezoidal rule (γ = ½) keeps every mode it is
  // given undamped, and the closure events (the flow's jump when the slit
  // shuts, the fold's impact) feed the ringing near 18 kHz (a few cells of
  // the radiation mesh per wavelength, 2.7 steps per period): with γ = ½
  // it grew at each closure until it was 97 % of the sound and biased the
  // LPC. With γ = 0.6 a component at ωΔt = 2.3 loses 11 % of its amplitude
  // per step; the formants of [u] at Δt 2e−5 gain the bandwidths 1, 16, 47
  // and 125 Hz (F1..F4). Measured: bench/voice.py, u_*_trapezoidal
  wave.newmark_gamma = 0.6;
  wave.newmark_beta = 0.3025;
  // The flow of the converged closing cycle (demos/glottis/closing_cycle.toml,
  // docs/glottis.md): the 0.035 mm mesh, whose glottal forces are converged
  // (the scene's 0.05 mm mesh is 28–37 % low in lift), with the preset's
  // fold (f2 = 155 Hz, ζ = 0.02: it closes in every cycle on this mesh),
  // quadrature degree 2, and the porous ramp (G4). At the voice's Δt 2e−5
  // (jet CFL ≈ 24) the cycle takes half the preset's steps; over [0.05,
  // 0.1] s it is within +0.1 % (f0), −1.5 % (mean cycle peak) and +1 % (OQ)
  // of the preset's Δt 1e−5. Without the ramp that Δt leaves coupling steps
  // unconverged at reopening and the glottal flow jumps there by up to
  // 44 % of its peak in one step, a click in the sound; with it the largest
  // one-step jump is 2.9 % (bench/glottis_speedup.py)
  glottis.fe.sizes.h_gap = 0.035e-3;
  glottis.fe.sizes.h_far = 0.35e-3;
  glottis.fold.f2 = 155;
  glottis.fold.zeta1 = 0.02;
  glottis.fold.zeta2 = 0.02;
  glottis.fluid.quadrature_degree = 2;
  glottis.fe.porous_ramp = 20e-6;
}
//-----------------------------------------------------------------------------
void fsai::voice::VoiceScene::bind(fsai::common::Parameters& p)
{
  voice.bind(p);
  source.bind(p);
  glottis.bind(p);
  bernoulli.bind(p);
  elastic.bind(p);
  wave.bind(p);
  domain.bind(p);
}
//-----------------------------------------------------------------------------
void fsai::voice::VoiceScene::apply_quick(const std::vector<std::string>& args)
{
  for (const auto& arg : args)
    voice.quick |= arg == "--quick" or arg == "--quick=true";
  if (!voice.quick)
    return;
  // Coarse flow and acoustic meshes, a larger step and a larger initial
  // perturbation so the oscillation is under way within 0.04 s (the
  // sound's f0 needs two periods in the window)
  voice.duration = 0.04;
  voice.dt = 5e-5;
  // On this mesh and step the converged flow's fold (ζ 0.02) with the
  // porous ramp leaves coupling steps unconverged and serial and 2-rank
  // runs part ways: the quick look is on the glottis scene's own flow
  glottis = glottis::FlowGlottisSetup();
  glottis.fe.sizes.h_far = 1e-3;
  glottis.fe.sizes.h_gap = 0.1e-3;
  domain.h = 0.008;
  glottis.fold.h0 = 0.15e-3;
  voice.stats_from = 0.4;
  voice.write_every = 0;
}
//-----------------------------------------------------------------------------
void fsai::voice::VoiceScene::validate(const fsai::common::Parameters& p)
{
  if (voice.fold == "elastic" and voice.flow == "fe")
  {
    // --quick's coarse step and mesh (apply_quick) are kept: the quick look
    // stays quick, and its mesh is not the one the preset was checked on
    const double quick_dt = voice.dt;
    const double quick_h_gap = glottis.fe.sizes.h_gap;
    glottis::apply_elastic_fe_defaults(p);
    if (voice.quick)
    {
      p.set_unless_given("dt", voice.dt, quick_dt);
      p.set_unless_given("fe.h_gap", glottis.fe.sizes.h_gap, quick_h_gap);
    }
    // Otherwise the elastic fold's flow is that of its validation
    // (docs/glottis.md): the preset's gap cells, with the glottis scene's
    // far cells; on the voice's own mesh (0.035 / 0.35 mm, set above for
    // the 2-DOF fold) the elastic voice took 1.6x the time of the scene's
    // 0.05 / 0.5 mm mesh. The voice's quadrature degree 2 is kept: at
    // 800 Pa it moves the glottis scene's elastic cycle by less than the
    // mesh check's tolerance and makes the step's assembly 35 % cheaper
    // (docs/glottis.md, the mesh/Δt check)
    else
    {
      const glottis::FlowGlottisSetup scene;
      p.set_unless_given("fe.h_far", glottis.fe.sizes.h_far,
                         scene.fe.sizes.h_far);
    }
  }
  voice.validate();
  source.validate();
  glottis.validate(voice.p_sub, voice.dt);
  bernoulli.validate();
  bernoulli.p_sub = voice.p_sub;
  bernoulli.dt = voice.dt;
  elastic.validate();
  wave.validate();
  domain.layer = voice.radiation == "pml" ? voice.layer : 0.0;
  domain.radiation_region = voice.radiation != "piston";
  domain.channel
      = voice.tract_start == "outlet" ? glottis.geometry.outlet_length : 0.0;
  domain.validate();
  fsai::require(voice.acoustics == "1d" or !domain.radiation_region
                    or voice.mic_distance < domain.radius,
                "--mic_distance",
                "inside the radiation region (< --voice.radius) with "
                "--acoustics fe",
                voice.mic_distance);
  if (!voice.run.restart.empty())
    voice.output = voice.run.restart; // continue in the run's own folder
}
//-----------------------------------------------------------------------------
std::unique_ptr<fsai::glottis::GlottisModel>
fsai::voice::VoiceScene::make_glottis(MPI_Comm comm,
                                      const glottis::FoldProfile& profile,
                                      std::size_t rows_kept) const
{
  return fsai::glottis::make_glottis(comm, profile, voice.flow, voice.fold,
                                     glottis, elastic, bernoulli, voice.ramp,
                                     voice.output + "/coupling.csv", rows_kept);
}
//-----------------------------------------------------------------------------
fsai::voice::VoiceTract
fsai::voice::make_tract(const VoiceScene& s,
                        const glottis::FoldProfile& profile)
{
  const auto& vp = s.voice;
  const auto& geo = s.glottis.geometry;
  const auto& wave = s.wave;
  VoiceTract out;
  out.label = vp.tract == "tube"
                  ? "tube"
                  : (vp.area_function.empty() ? vp.vowel : vp.area_function);
  const mesh::AreaFunction vowel
      = vp.tract == "tube"
            ? mesh::uniform_tube(geo.outlet_length + vp.tube_length,
                                 vp.tube_area)
            : mesh::read_area_function(vp.area_function.empty()
                                           ? mesh::vowel_file(vp.vowel)
                                           : vp.area_function);
  // The 1D acoustics sound in the vowel's own tract; the FE acoustics in
  // the flow domain's channel continued by the vowel's tract
  out.area = vp.acoustics == "1d" or vp.tract_start == "glottis"
                 ? vowel
                 : mesh::voice_tract(vowel, profile);
  // Same walls as the FE model: the planar model's two walls of depth L_g
  // per unit length
  ac::TubeWall wall1d;
  if (vp.yielding_walls)
  {
    wall1d = {wave.wall_mass, wave.wall_resistance, wave.wall_stiffness,
              geo.depth};
  }
  out.wall = wall1d;
  fsai::common::ScopedTimer timer("demo: tract formants (1D)");
  const mesh::AreaFunction tract1d = mesh::resample(out.area, true, 5e-4);
  for (const auto& r : ac::tube_resonances(tract1d, 5000.0, wave.c0, wave.rho0,
                                           ac::LipEnd::flanged, -1.0, wall1d))
  {
    if (out.formants.size() < 4)
    {
      out.formants.push_back(r.f);
      out.bandwidths.push_back(r.bandwidth);
    }
  }
  // The same 1D model of the acoustic domain as built: its glottis stays
  // open at the rest gap and leads to the subglottal duct and its end,
  // which raises F1 above the closed-glottis value
  ac::GlottalBranch branch{mesh::voice_subglottal(profile),
                           vp.subglottal == "absorbing"};
  for (double f = 10.0; f <= 5000.0; f += 10.0)
  {
    const auto r = ac::tube_response(tract1d, f, wave.c0, wave.rho0,
                                     ac::LipEnd::flanged, -1.0, wall1d);
    out.response_f.push_back(f);
    out.response_db.push_back(20 * std::log10(std::abs(r.h_lips)));
  }
  if (vp.acoustics == "1d") // the line's glottal end is the flow source
    out.domain_formants = out.formants;
  else
  {
    for (const auto& r :
         ac::tube_resonances(tract1d, 5000.0, wave.c0, wave.rho0,
                             ac::LipEnd::flanged, -1.0, wall1d, branch))
    {
      if (out.domain_formants.size() < 4)
        out.domain_formants.push_back(r.f);
    }
  }
  fsai::log::info("tract: {} ({:.2f} cm, {} walls); transfer-function "
                  "formants (1D, flanged lips) {::.0f} Hz, bandwidths "
                  "{::.0f} Hz; with the acoustic domain's open rest glottis "
                  "and {} subglottal end: {::.0f} Hz",
                  out.area.source, 100 * out.area.length(),
                  vp.yielding_walls ? "yielding" : "rigid", out.formants,
                  out.bandwidths, vp.subglottal, out.domain_formants);
  return out;
}
//-----------------------------------------------------------------------------
fsai::voice::Sound fsai::voice::make_sound(MPI_Comm comm, const VoiceScene& s,
                                           const glottis::FoldProfile& profile,
                                           const VoiceTract& tract)
{
  const auto& vp = s.voice;
  const auto& geo = s.glottis.geometry;
  const auto& vg = s.domain;
  Sound out;
  {
    fsai::common::ScopedTimer t("demo: acoustic mesh");
    out.mesh = mesh::voice_domain(comm, profile, tract.area, vg);
  }
  const auto& am = out.mesh;
  auto facets = [&](const char* name)
  { return am.facet_tags->find(am.facet_tag(name)); };
  ac::WaveBoundaries wb;
  // Subglottal end: absorbing by default (an anechoic trachea, A4). A
  // sound-hard end closes a 20 mm cavity that the rest glottis (the
  // acoustic domain is fixed, the gap stays open) joins to the tract as a
  // Helmholtz resonator (measured: a 770 Hz peak that dominated the sound,
  // and F1 lowered by the cavity's compliance)
  if (vp.subglottal == "absorbing")
    wb.absorbing = facets("inlet");
  if (vp.yielding_walls)
  {
    // The tract's walls from the fold's superior attachment to the lips,
    // as in the 1D model (not the subglottal duct, the baffle or the step
    // where the channel meets the vowel's tract), A3
    const double x0 = geo.fold_length, x_step = geo.fold_length + vg.channel,
                 x_end = geo.fold_length + tract.area.length();
    wb.yielding = am.facets_where("wall",
                                  [&](const double* x)
                                  {
                                    return x[0] > x0 and x[0] < x_end - 1e-9
                                           and std::abs(x[0] - x_step) > 1e-9;
                                  });
  }
  if (vg.radiation_region)
  {
    wb.radiation = facets("radiation");
    wb.radiation_beta = 0.5 / (vg.radius + vg.layer); // planar: 1/(2R)
  }
  else
  {
    // The lips' opening, A11: its area as the mesh's (the smooth reading)
    wb.piston = facets("lips");
    wb.piston_area = tract.area.area_at(tract.area.length(), true);
  }
  wb.vibrating = facets("fold");
  std::shared_ptr<dolfinx::fem::Function<double>> sigma;
  out.x_lips = geo.fold_length + tract.area.length();
  if (vp.radiation == "pml")
  {
    sigma = ac::absorbing_layer(
        am.mesh, am.cell_tags->find(am.cell_tag("layer")),
        {out.x_lips, 0.0, 0.0}, vg.radius, vg.layer, s.wave.c0, 1e-3);
  }
  out.solver = std::make_unique<ac::WaveSolver>(am.mesh, 1, false, s.wave, wb,
                                                vp.dt, sigma, true);
  return out;
}
//-----------------------------------------------------------------------------
fsai::voice::VoiceMeasures fsai::voice::analyse_voice(
    MPI_Comm comm, const VoiceScene& s, const VoiceTract& tract,
    const std::vector<double>& t, const std::vector<double>& g,
    const std::vector<double>& Q, const std::vector<double>& p_mic,
    io::RunSummary& summary)
{
  const auto& vp = s.voice;
  const double t0 = vp.stats_from * vp.duration;
  const auto cs = glottis::cycle_stats(t, g, Q, t0, 0.0);
  // The statistics window of the sound and of the glottal flow
  std::vector<double> mic, q_window;
  for (std::size_t i = 0; i < t.size(); ++i)
    if (t[i] >= t0)
    {
      mic.push_back(p_mic[i]);
      q_window.push_back(Q[i]);
    }
  // f0 search down to 60 Hz, or to two periods in a short window
  const double f0 = ac::fundamental_frequency(
      mic, vp.dt, std::max(60.0, 2.6 / (vp.dt * double(mic.size()))));
  if (!std::isfinite(f0))
  {
    fsai::log::warn("the sound's f0 could not be estimated (window {:.4f} s: "
                    "too short or silent)",
                    vp.dt * double(mic.size()));
  }
  // Formants of the voice: LPC of its periodic part (pitch-synchronous
  // average over the window's whole periods at the sound's own f0,
  // repeated over the window's length, A8). Transients — an impact, the
  // start-up — leave the lightly damped upper resonances ringing at their
  // own frequencies for longer than the run; LPC of the raw window puts
  // poles on those lines (kept as formants_lpc_window_hz for comparison)
  double periodic_fraction = NAN;
  const std::vector<double> cycle
      = ac::periodic_part(mic, vp.dt, f0, &periodic_fraction);
  const std::vector<double> formants_window = ac::lpc_formants(mic, vp.dt);
  std::vector<double> formants = formants_window;
  if (!cycle.empty())
  {
    std::vector<double> voiced;
    while (voiced.size() + cycle.size()
           <= std::max(mic.size(), 2 * cycle.size()))
      voiced.insert(voiced.end(), cycle.begin(), cycle.end());
    formants = ac::lpc_formants(voiced, vp.dt);
  }
  // The measures a voice scientist reads (A10), over the same window
  const auto fm = glottal_flow_measures(q_window, vp.dt);
  // The sound leaves the glottis and reaches the microphone after the
  // tract's length and the microphone's distance
  const double delay = (tract.area.length() + vp.mic_distance) / s.wave.c0;
  // Closed-phase analysis (A10): over the closed phases the tract rings
  // freely. The FE sound's closed phase holds the fold wall's motion (A2)
  // and the slit at g_min (A5); once the wall's velocity, not its
  // acceleration, was faded it is free enough at the mixed level (F1/F2
  // within 3.4 % of the tract's for [u], [a], [i]; the periodic part:
  // [a] +15 / −12 %, [u] at 1200 Pa F1 +22 %, docs/voice.md). The FE
  // flow's closed phases (about 1.2 ms, fewer samples than the predictor's
  // order) give equations because the regressors may precede them
  const auto sm = sound_measures(mic, vp.dt, fm.boundaries, fm.closed, delay);
  summary.set("voice", voice_json(fm, sm, vp.mic_distance));
  const double spl = sm.spl_db;
  fsai::log::info("voice: f0 {:.2f} Hz, jitter {:.3f} %, shimmer {:.3f} %, "
                  "HNR {:.1f} dB; flow peak {:.3f} l/s, mean {:.3f} l/s, OQ "
                  "{:.3f}, SQ {:.2f}, MFDR {:.0f} l/s², NAQ {:.3f}; H1-H2 "
                  "{:.1f} dB, subharmonic ratio {:.2f} (flow {:.2f}), SPL "
                  "{:.1f} dB at {:.2f} m; formants ({}) "
                  "{::.0f} Hz, bandwidths {::.0f} Hz",
                  fm.f0_hz, fm.jitter_pct, sm.shimmer_pct, sm.hnr_db,
                  1e3 * fm.q_peak, 1e3 * fm.q_mean, fm.open_quotient,
                  fm.speed_quotient, 1e3 * fm.mfdr, fm.naq, sm.h1_h2_db, sm.shr,
                  fm.shr, sm.spl_db, vp.mic_distance, sm.formant_method,
                  sm.formants_hz, sm.bandwidths_hz);
  auto errors = [&](const std::vector<double>& ref)
  {
    std::vector<double> e;
    for (std::size_t k = 0; k < 2 and k < formants.size() and k < ref.size();
         ++k)
      e.push_back(100.0 * (formants[k] - ref[k]) / ref[k]);
    return e;
  };
  fsai::log::info(
      "fold: {} cycles, f0 {:.2f} Hz, open quotient {:.3f}, peak flow {:.3e} "
      "m³/s, closes every cycle: {}; sound at the microphone: f0 {:.2f} Hz "
      "({:+.2f} %), SPL {:.1f} dB, periodic part {:.1f} % of the energy, its "
      "LPC formants {::.0f} Hz (whole window: {::.0f} Hz) vs tract {::.0f} "
      "Hz (closed glottis), {::.0f} Hz (as modelled)",
      cs.cycles, cs.f0_hz, cs.open_quotient, cs.q_peak,
      cs.closes_every_cycle ? "yes" : "no", f0,
      100 * (f0 - cs.f0_hz) / cs.f0_hz, spl, 100 * periodic_fraction, formants,
      formants_window, tract.formants, tract.domain_formants);
  // Period doubling: cycles alternating long/short or strong/weak repeat
  // every two glottal cycles, and so does the sound (A10)
  if (std::abs(2 * f0 - cs.f0_hz) < 0.03 * cs.f0_hz)
    fsai::log::warn("the sound repeats every two glottal cycles (f0 {:.2f} Hz "
                    "= {:.2f} Hz / 2: period doubling; subharmonic ratio "
                    "{:.2f}, of the glottal flow {:.2f})",
                    f0, cs.f0_hz, sm.shr, fm.shr);

  // Spectrum of the sound (Hann window) for the chart
  {
    std::vector<double> w(mic.size());
    for (std::size_t i = 0; i < mic.size(); ++i)
      w[i] = mic[i] * (0.5 - 0.5 * std::cos(2 * M_PI * i / double(mic.size())));
    const auto [f, A] = ac::amplitude_spectrum(w, vp.dt, 4);
    io::CsvWriter sc(comm, vp.output + "/spectrum.csv", {"f_hz", "level_db"});
    for (std::size_t i = 1; i < f.size() and f[i] <= 5000.0; ++i)
      sc.row({f[i], 20 * std::log10(std::max(A[i], 1e-30) / 20e-6)});
  }
  {
    io::CsvWriter tc(comm, vp.output + "/tract_response.csv",
                     {"f_hz", "level_db"});
    for (std::size_t i = 0; i < tract.response_f.size(); ++i)
      tc.row({tract.response_f[i], tract.response_db[i]});
  }
  const std::string wav = vp.output + "/sound.wav";
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  if (rank == 0)
    ac::write_wav(wav, ac::resample(p_mic, vp.dt, vp.wav_rate), vp.wav_rate);

  summary.set("f0_hz", f0);
  summary.set("f0_fold_hz", cs.f0_hz);
  summary.set("formants_from_sound_hz", formants);
  summary.set("formants_lpc_window_hz", formants_window);
  summary.set("periodic_fraction", periodic_fraction);
  summary.set("formant_errors_percent", errors(tract.formants));
  summary.set("domain_formant_errors_percent", errors(tract.domain_formants));
  summary.set("spl_db", spl);
  summary.set("sim_time_s", vp.duration);
  summary.set("wav", wav);
  summary.set("open_quotient", cs.open_quotient);
  summary.set("q_peak_m3s", cs.q_peak);
  summary.set("cycles", cs.cycles);
  summary.set("closes_every_cycle", cs.closes_every_cycle);

  return {f0, cs.f0_hz, spl, sm.formants_hz, tract.formants};
}
//-----------------------------------------------------------------------------
void fsai::voice::check_voice(const VoiceScene& s, const VoiceMeasures& m)
{
  const auto& vp = s.voice;
  if (!vp.check_result)
    return;
  auto fail = [](const std::string& what)
  { throw std::runtime_error("check failed: " + what); };
  if (!(std::isfinite(m.spl_db) and m.spl_db > 40.0))
    fail(fmt::format("sound level {} dB (want finite, > 40 dB)", m.spl_db));
  if (!(m.f0_fold_hz >= 85.0 and m.f0_fold_hz <= 155.0))
    fail(fmt::format("fold f0 {} Hz outside 85-155 Hz", m.f0_fold_hz));
  if (vp.check_f0_tolerance > 0
      and !(std::abs(m.f0_hz - m.f0_fold_hz)
            <= vp.check_f0_tolerance * m.f0_fold_hz))
  {
    fail(fmt::format("sound f0 {} Hz vs fold f0 {} Hz (tolerance {} %)",
                     m.f0_hz, m.f0_fold_hz, 100 * vp.check_f0_tolerance));
  }
  for (std::size_t k = 0; vp.check_formant_tolerance > 0 and k < 2; ++k)
  {
    if (k >= m.formants_hz.size() or k >= m.tract_formants_hz.size()
        or !(std::abs(m.formants_hz[k] - m.tract_formants_hz[k])
             <= vp.check_formant_tolerance * m.tract_formants_hz[k]))
    {
      fail(fmt::format("sound formants {} Hz vs the tract's {} Hz: F{} "
                       "not within {} %",
                       m.formants_hz, m.tract_formants_hz, k + 1,
                       100 * vp.check_formant_tolerance));
    }
  }
}
