// Copyright (C) 2026 fsai developers
//
// fsai_demo: the voice — airflow, self-oscillating vocal folds that close
// the glottis, and the sound that forms in the vocal tract (docs/model.md
// §4–§5), at three fidelities (docs/voice.md):
//   full     --flow fe --acoustics fe (default): the glottis scene with the
//            FE flow (glottis::FlowGlottis: ALE Navier–Stokes, 2-DOF fold,
//            closure, Hertz contact) drives, one way, the acoustic wave
//            equation (E14, E21) on a fixed domain that contains the flow
//            domain and continues it by the vowel's tract to the lips and a
//            radiation region (sources: voice::VoiceSource);
//   mixed    --flow bernoulli --acoustics fe: the quasi-steady flow, its Q
//            and the fold's motion as the sound's sources;
//   reduced  --flow bernoulli --acoustics 1d: the vowel's tract as a 1D
//            transmission line (A9), 0.1 s of voice in well under a second.
// Each step: the glottis's step, then one step of the sound with the same
// Δt (voice::VoiceAcoustics). --fold elastic puts the plane-strain FE fold
// in the glottis, in the FE flow on the glottis preset's settings
// (glottis::apply_elastic_fe_defaults).
//
// Sample runs:
//   mpirun -n 2 ./fsai_demo --vowel u        # 0.1 s of voice
//   ./fsai_demo --quick                      # short coarse run
//   ./fsai_demo --flow bernoulli --acoustics 1d --vowel a
//   ./fsai_demo --flow bernoulli --acoustics 1d --fold elastic
//   mpirun -n 2 ./fsai_demo --fold elastic --vowel u --p-sub 800
//   ./fsai_demo --vowel a --radiation pml
//   ./fsai_demo --tract tube                 # a short straight tube
//
// Outputs in --output (default results/fsai_demo): series.csv, sound.wav
// (microphone, 44.1 kHz), spectrum.csv, report.png, flow.xdmf,
// acoustic.xdmf, summary.json (vowel, f0_hz, formants_from_sound_hz,
// tract_formants_hz, spl_db, the voice measures as "voice", …).
// Checkpoints and restarts as fsai_glottis.

#include <common/Parameters.h>
#include <common/Runtime.h>
#include <common/log.h>
#include <common/timer.h>
#include <glottis/FlowOutput.h>
#include <io/RunLoop.h>
#include <io/RunSummary.h>
#include <io/csv_columns.h>
#include <io/output_dir.h>
#include <voice/VoiceAcoustics.h>
#include <voice/VoiceScene.h>

#include <chrono>
#include <cmath>
#include <fmt/format.h>

int main(int argc, char* argv[])
{
  return fsai::common::run_main(
      argc, argv,
      [](fsai::common::Runtime& rt)
      {
        namespace io = fsai::io;
        const auto wall0 = std::chrono::steady_clock::now();
        // 1. Options
        fsai::voice::VoiceScene scene;
        const auto& vp = scene.voice;
        const auto& gs = scene.glottis;
        fsai::common::Parameters params(rt.program(),
                                        "The voice: flow, folds and sound");
        scene.bind(params);
        scene.apply_quick(rt.app_args());
        params.parse(rt.app_args());
        scene.validate(params);
        params.print();
        io::prepare_output_dir(rt.comm(), vp.output);
        io::RunSummary summary(rt.comm(), rt.program());
        summary.set_parameters(params.to_json());
        io::RunLoop loop(rt.comm(), vp.output, params.to_json(), vp.run);

        // 2. The tract, the glottis and the sound
        const fsai::glottis::FoldProfile profile(gs.geometry);
        const auto tract = fsai::voice::make_tract(scene, profile);
        if (vp.reanalyse)
        {
          const auto c = io::read_csv_columns(
              vp.output + "/series.csv", {"t_s", "gap_m", "Q_m3s", "p_mic_pa"});
          fsai::voice::analyse_voice(rt.comm(), scene, tract, c[0], c[1], c[2],
                                     c[3], summary);
          summary.write(vp.output + "/reanalysis.json");
          return;
        }
        auto glottis = scene.make_glottis(rt.comm(), profile, loop.rows_kept());
        auto sound = fsai::voice::make_acoustics(rt.comm(), scene, profile,
                                                 tract, *glottis);
        glottis->describe(summary);
        summary.set("fidelity", fmt::format("flow {}, acoustics {}, fold {}",
                                            vp.flow, vp.acoustics, vp.fold));
        summary.set("acoustic_dofs", sound->dofs());
        summary.set("tract_length_m", tract.area.length());
        summary.set("vowel", tract.label);
        summary.set("tract_formants_hz", tract.formants);
        summary.set("tract_bandwidths_hz", tract.bandwidths);
        summary.set("domain_formants_hz", tract.domain_formants);
        std::unique_ptr<io::TimeSeriesWriter> sound_xdmf;
        if (vp.write_every > 0 and !sound->fields().empty())
        {
          sound_xdmf = std::make_unique<io::TimeSeriesWriter>(
              vp.output + "/acoustic.xdmf", sound->fields(),
              loop.restart_time());
        }

        // 3. Time loop: glottis step, then one step of the sound
        if (loop.restarting())
        {
          glottis->restore(loop.checkpoint(), loop.fields());
          sound->restore(loop.checkpoint(), loop.fields());
        }
        // A remeshed flow (--fe.remesh_quality) continues in a new file
        fsai::glottis::FlowOutput flow_xdmf(vp.output, *glottis,
                                            loop.restart_time());
        const long n = std::lround(vp.duration / vp.dt);
        std::vector<double> t, g, Q, p_mic;
        long its = 0;
        for (const auto& r : loop.open_series(
                 vp.output + "/series.csv",
                 {"t_s", "gap_m", "Q_m3s", "h_m", "phi_rad", "contact_force_N",
                  "p_lips_pa", "p_mic_pa", "iterations"},
                 summary))
        {
          t.push_back(r[0]);
          g.push_back(r[1]);
          Q.push_back(r[2]);
          p_mic.push_back(r[7]);
          its += long(r[8]);
        }
        sound->start(*glottis, Q.empty() ? 0.0 : Q.back());
        fsai::glottis::Sample s;
        io::RunHooks hooks;
        hooks.step = [&](long k)
        {
          s = glottis->step();
          sound->step(*glottis, s);
          const double pl = sound->p_lips(), pm = sound->p_mic();
          if (!std::isfinite(pl) or !std::isfinite(pm))
          {
            throw std::runtime_error(fmt::format(
                "acoustic pressure is not finite at t = {:.6f} s (step {})",
                s.t, k));
          }
          loop.row({s.t, s.gap, s.Q, s.h, s.phi, s.contact_force, pl, pm,
                    double(s.iterations)});
          t.push_back(s.t);
          g.push_back(s.gap);
          Q.push_back(s.Q);
          p_mic.push_back(pm);
          its += s.iterations;
          if (k % std::max(vp.write_every, 1) == 0)
          {
            if (vp.write_every > 0)
              flow_xdmf.write(s.t);
            if (sound_xdmf)
              sound_xdmf->write(s.t);
          }
          return io::StepReport{s.t, s.converged};
        };
        hooks.save = [&](auto& scalars, auto& fields)
        {
          glottis->checkpoint(scalars, fields);
          sound->checkpoint(scalars, fields);
        };
        hooks.last_good = [&](const std::string& path)
        { return glottis->write_last_good(path); };
        hooks.progress = [&]
        {
          return fmt::format(
              "t = {:.5f} g = {:+.3e} Q = {:.3e} p_mic = {:+.3e}", s.t, s.gap,
              s.Q, sound->p_mic());
        };
        const double loop_wall = loop.run(n, hooks);

        // 4. The fold's cycle and the sound's analysis, summary and chart
        fsai::common::ScopedTimer analysis("demo: analysis");
        const auto measures = fsai::voice::analyse_voice(
            rt.comm(), scene, tract, t, g, Q, p_mic, summary);
        glottis->report(summary);
        summary.set("steps", n);
        summary.set("coupling_iterations_mean", double(its) / double(n));
        summary.set("coupling_unconverged_steps", loop.unconverged_steps());
        summary.set("loop_wall_s", loop_wall);
        summary.set("wall_per_sim_s", loop_wall / vp.duration);
        summary.write(vp.output + "/summary.json");
        fsai::log::info("time loop {:.1f} s ({:.3g} s per simulated s); total "
                        "{:.1f} s; wrote {}/sound.wav",
                        loop_wall, loop_wall / vp.duration,
                        std::chrono::duration<double>(
                            std::chrono::steady_clock::now() - wall0)
                            .count(),
                        vp.output);
        fsai::voice::check_voice(scene, measures);
        if (vp.report)
          io::draw_chart(rt.comm(), "plot_voice.py", vp.output);
      });
}
