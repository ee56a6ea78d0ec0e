// Copyright (C) 2026 fsai developers
//
// fsai_fold3d: the 3D vocal fold (St.Venant–Kirchhoff, the fold of
// fsai_modal) in 3D ALE flow, driven by the subglottal pressure
// (glottis::Fold3dPhonation; docs/fold3d.md). The mid-sagittal plane is a
// symmetry plane; the glottis stays open (no closure model in 3D).
//
// Sample runs:
//   ./fsai_fold3d --quick
//   mpirun -n 2 ./fsai_fold3d --p-sub 800 --duration 0.03
//
// Outputs in --output (default results/fsai_fold3d): series.csv (t, Q,
// smallest half-gap, medial displacement, coupling iterations, the fold's
// coordinates in its first --modes in-vacuo modes),
// coupling.csv, flow.xdmf and fold.xdmf, summary.json (f0_hz, q_peak_m3s,
// flow_dofs, solid_dofs, krylov_iterations_mean, coupling_iterations_mean,
// wall_per_sim_s, mode_hz, mode_shares). Checkpoints and restarts:
// --checkpoint-every N, --restart DIR (io::RunLoop).

#include <common/Parameters.h>
#include <common/Runtime.h>
#include <common/log.h>
#include <common/timer.h>
#include <glottis/Fold3d.h>
#include <glottis/waveform.h>
#include <io/RunLoop.h>
#include <io/RunSummary.h>
#include <io/TimeSeriesWriter.h>
#include <io/output_dir.h>
#include <structure/ModalProjection.h>

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

int main(int argc, char* argv[])
{
  return fsai::common::run_main(
      argc, argv,
      [](fsai::common::Runtime& rt)
      {
        namespace io = fsai::io;
        // 1. Options
        fsai::glottis::Fold3dSetup setup;
        const auto& sp = setup.scene;
        fsai::common::Parameters params(
            rt.program(), "The 3D vocal fold in 3D flow (self-oscillation)");
        setup.bind(params);
        params.parse(rt.app_args());
        setup.configure(params);
        params.print();
        io::prepare_output_dir(rt.comm(), sp.output);
        io::RunSummary summary(rt.comm(), rt.program());
        summary.set_parameters(params.to_json());

        // 2. The scene, restored from a checkpoint if restarting
        io::RunLoop loop(rt.comm(), sp.output, params.to_json(), sp.run);
        fsai::glottis::Fold3dPhonation scene(rt.comm(), setup,
                                             loop.rows_kept());
        scene.describe(summary);
        if (loop.restarting())
          scene.restore(loop.checkpoint(), loop.fields());
        std::unique_ptr<io::TimeSeriesWriter> flow_xdmf, fold_xdmf;
        if (sp.write_every > 0)
        {
          flow_xdmf = std::make_unique<io::TimeSeriesWriter>(
              sp.output + "/flow.xdmf", scene.flow_fields(),
              loop.restart_time());
          fold_xdmf = std::make_unique<io::TimeSeriesWriter>(
              sp.output + "/fold.xdmf", scene.fold_fields(),
              loop.restart_time());
        }

        // 3. Time loop (the series' kept rows rebuild the statistics)
        const long n = std::lround(sp.duration / sp.dt);
        std::vector<std::string> columns
            = {"t_s",         "Q_m3s",       "gap_m",
               "ux_medial_m", "uy_medial_m", "iterations"};
        for (int k = 1; k <= sp.modes; ++k)
          columns.push_back(fmt::format("q{}_m", k));
        if (sp.modes > 0)
          columns.push_back("modal_rest"); // share the modes leave out
        std::vector<double> t, gap, Q;
        std::vector<std::vector<double>> modal; // q_1..q_n, rest share
        long its = 0;
        for (const auto& r :
             loop.open_series(sp.output + "/series.csv", columns, summary))
        {
          t.push_back(r[0]);
          Q.push_back(r[1]);
          gap.push_back(r[2]);
          its += long(r[5]);
          modal.emplace_back(r.begin() + 6, r.end());
        }
        fsai::glottis::Fold3dSample s;
        io::RunHooks hooks;
        hooks.step = [&](long k)
        {
          s = scene.step();
          if (flow_xdmf and k % sp.write_every == 0)
          {
            flow_xdmf->write(s.t);
            fold_xdmf->write(s.t);
          }
          std::vector<double> row
              = {s.t, s.Q, s.gap, s.ux, s.uy, double(s.iterations)};
          row.insert(row.end(), s.modal.begin(), s.modal.end());
          loop.row(row);
          modal.push_back(s.modal);
          t.push_back(s.t);
          Q.push_back(s.Q);
          gap.push_back(s.gap);
          its += s.iterations;
          return io::StepReport{s.t, s.converged};
        };
        hooks.save = [&](auto& scalars, auto& fields)
        { scene.checkpoint(scalars, fields); };
        hooks.progress = [&]
        {
          return fmt::format("t = {:.5f} gap = {:.3e} Q = {:.3e} its = {}", s.t,
                             s.gap, s.Q, s.iterations);
        };
        double wall = 0;
        {
          fsai::common::ScopedTimer timer("fold3d: time loop");
          wall = loop.run(n, hooks);
        }

        // 4. Cycle statistics and summary
        const double from
            = sp.stats_from >= 0 ? sp.stats_from : 0.5 * sp.duration;
        const auto c = fsai::glottis::cycle_stats(t, gap, Q, from);
        double q_mean = 0, gap_min = 1e300;
        int m = 0;
        for (std::size_t i = 0; i < t.size(); ++i)
        {
          gap_min = std::min(gap_min, gap[i]);
          if (t[i] >= from)
          {
            q_mean += Q[i];
            ++m;
          }
        }
        if (const auto* modes = scene.modes())
        {
          // The modes' shares of the oscillation (about its mean) and the
          // mean share of the displacement they leave out, over the window
          const auto first = std::size_t(
              std::lower_bound(t.begin(), t.end(), from) - t.begin());
          summary.set("mode_shares", fsai::structure::modal_shares(
                                         modal, modes->modal_masses(), first));
          double rest = 0;
          for (std::size_t i = first; i < modal.size(); ++i)
            rest += modal[i].back() / double(modal.size() - first);
          summary.set("modal_rest_mean", rest);
        }
        summary.set("cycles", c.cycles);
        summary.set("f0_hz", c.f0_hz);
        summary.set("q_peak_m3s", c.q_peak);
        summary.set("q_mean_m3s", m > 0 ? q_mean / m : 0.0);
        summary.set("gap_amplitude_m", c.gap_amplitude);
        summary.set("gap_min_m", gap_min);
        summary.set("krylov_iterations_mean", scene.krylov_iterations_mean());
        summary.set("coupling_iterations_mean",
                    t.empty() ? 0.0 : double(its) / double(t.size()));
        summary.set("coupling_unconverged_steps", loop.unconverged_steps());
        const double simulated = double(n - loop.first_step()) * sp.dt;
        summary.set("wall_per_sim_s", simulated > 0 ? wall / simulated : 0.0);
        fsai::log::info("3D fold: {} cycles from t = {:.4f} s, f0 = {:.2f} Hz, "
                        "peak flow {:.3e} m³/s, mean {:.3e}, smallest half-gap "
                        "{:.3e} m; {:.1f} coupling and {:.1f} Krylov "
                        "iterations per step; time loop {:.1f} s",
                        c.cycles, from, c.f0_hz, c.q_peak,
                        m > 0 ? q_mean / m : 0.0, gap_min,
                        t.empty() ? 0.0 : double(its) / double(t.size()),
                        scene.krylov_iterations_mean(), wall);
        summary.write(sp.output + "/summary.json");
      });
}
