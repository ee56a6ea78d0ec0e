// Copyright (C) 2026 fsai developers
//
// fsai_demo: the voice — airflow, self-oscillating vocal folds that close
// the glottis, and the sound that forms in the vocal tract (docs/model.md
// §4–§5). The glottis scene with the FE flow (glottis::FlowGlottis: ALE
// Navier–Stokes, 2-DOF fold, closure, Hertz contact) drives, one way, the
// acoustic wave equation (E14, E21) on a fixed domain that contains the
// flow domain and continues it by the vowel's vocal tract to the lips and
// a radiation region. Each step: the coupled flow step, then the sound's
// sources from it (voice::VoiceSource: Lighthill, fold surface, ±Q
// monopole, slit law) and one acoustic Newmark step with the same Δt.
//
// Sample runs:
//   mpirun -n 2 ./fsai_demo --vowel u        # 0.1 s of voice
//   ./fsai_demo --quick                      # short coarse run
//   ./fsai_demo --vowel a --radiation pml
//   ./fsai_demo --tract tube                 # a short straight tube
//
// Outputs in --output (default results/fsai_demo): series.csv, sound.wav
// (microphone, 44.1 kHz), spectrum.csv, voice.png, flow.xdmf, acoustic.xdmf,
// summary.json (vowel, f0_hz, formants_from_sound_hz, tract_formants_hz,
// spl_db, sim_time_s, wav, …). Checkpoints and restarts as fsai_glottis.

#include <common/Parameters.h>
#include <common/Runtime.h>
#include <common/log.h>
#include <common/timer.h>
#include <io/PointProbes.h>
#include <io/RunLoop.h>
#include <io/RunSummary.h>
#include <io/output_dir.h>
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
        scene.validate();
        params.print();
        io::prepare_output_dir(rt.comm(), vp.output);
        io::RunSummary summary(rt.comm(), rt.program());
        summary.set_parameters(params.to_json());
        io::RunLoop loop(rt.comm(), vp.output, params.to_json(), vp.run);

        // 2. The tract, the flow (the glottis scene) and the sound
        const fsai::glottis::FoldProfile profile(gs.geometry);
        const auto tract = fsai::voice::make_tract(scene, profile);
        auto flow = std::make_unique<fsai::glottis::FlowGlottis>(
            rt.comm(), profile, gs.fold, gs.contact, gs.fe, gs.fluid, gs.ale,
            gs.coupling, vp.output + "/coupling.csv", loop.rows_kept());
        auto sound = fsai::voice::make_sound(rt.comm(), scene, profile, tract);
        auto& wave = *sound.solver;
        fsai::voice::VoiceSource source(rt.comm(), scene.source, gs, profile,
                                        *flow, sound.mesh, wave, vp.dt);
        fsai::log::info("FE flow: {} cells, {} dofs; acoustics: {} cells, {} "
                        "dofs",
                        flow->channel().cells(), flow->channel().flow().dofs(),
                        sound.mesh.mesh->topology().index_map(2)->size_global(),
                        wave.dofs());
        summary.set("flow_dofs", flow->channel().flow().dofs());
        summary.set("acoustic_dofs", wave.dofs());
        summary.set("tract_length_m", tract.area.length());
        summary.set("vowel", tract.label);
        summary.set("tract_formants_hz", tract.formants);
        summary.set("tract_bandwidths_hz", tract.bandwidths);
        summary.set("domain_formants_hz", tract.domain_formants);
        io::PointProbes probes(sound.mesh.mesh,
                               {{sound.x_lips, 0.0, 0.0},
                                {sound.x_lips + vp.mic_distance, 0.0, 0.0}});
        std::unique_ptr<io::TimeSeriesWriter> flow_xdmf, sound_xdmf;
        if (vp.write_every > 0)
        {
          flow_xdmf = std::make_unique<io::TimeSeriesWriter>(
              vp.output + "/flow.xdmf", flow->flow_fields(),
              loop.restart_time());
          sound_xdmf = std::make_unique<io::TimeSeriesWriter>(
              vp.output + "/acoustic.xdmf",
              std::vector<io::TimeSeriesWriter::Field>{wave.pressure()},
              loop.restart_time());
        }

        // 3. Time loop: flow step (coupled), then one acoustic step
        if (loop.restarting())
        {
          flow->load(loop.fields());
          wave.load(loop.fields(), "sound.");
          source.load(loop.fields());
        }
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
        source.start(*flow, Q.empty() ? 0.0 : Q.back());
        fsai::glottis::Sample s;
        std::vector<double> p{0, 0};
        io::RunHooks hooks;
        hooks.step = [&](long k)
        {
          s = flow->step();
          {
            fsai::common::ScopedTimer timer("demo: sound step");
            source.apply(*flow, s);
            wave.step();
          }
          p = probes.values(*wave.pressure());
          if (!std::isfinite(p[0]) or !std::isfinite(p[1]))
          {
            throw std::runtime_error(fmt::format(
                "acoustic pressure is not finite at t = {:.6f} s (step {})",
                s.t, k));
          }
          loop.row({s.t, s.gap, s.Q, s.h, s.phi, s.contact_force, p[0], p[1],
                    double(s.iterations)});
          t.push_back(s.t);
          g.push_back(s.gap);
          Q.push_back(s.Q);
          p_mic.push_back(p[1]);
          its += s.iterations;
          if (flow_xdmf and k % vp.write_every == 0)
          {
            flow_xdmf->write(s.t);
            sound_xdmf->write(s.t);
          }
          return io::StepReport{s.t, s.converged};
        };
        hooks.save = [&](auto&, auto& fields)
        {
          fields = flow->save();
          wave.save(*fields, "sound.");
          source.save(*fields);
        };
        hooks.last_good = [&](const std::string& path)
        { return flow->write_last_good(path); };
        hooks.progress = [&]
        {
          return fmt::format(
              "t = {:.5f} g = {:+.3e} Q = {:.3e} p_mic = {:+.3e}", s.t, s.gap,
              s.Q, p[1]);
        };
        const double loop_wall = loop.run(n, hooks);

        // 4. The fold's cycle and the sound's analysis, summary and chart
        const auto measures = fsai::voice::analyse_voice(
            rt.comm(), scene, tract, t, g, Q, p_mic, summary);
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
        io::draw_chart(rt.comm(), "plot_voice.py", vp.output);
      });
}
