// Copyright (C) 2026 fsai developers
//
// fsai_glottis: self-oscillating vocal folds that close the glottis
// (docs/model.md §5). A 2D symmetric half-channel with an M5-like fold
// profile, Hertz impact on the symmetry axis, driven by the subglottal
// pressure. Four variants behind one interface (glottis::GlottisModel):
//   --flow bernoulli | fe   quasi-steady 1D flow, or ALE Navier–Stokes
//   --fold 2dof | elastic   rigid 2-DOF profile, or plane-strain FE fold
//   --fold static           the 2-DOF profile held (steady glottal flow)
//
// Sample runs:
//   ./fsai_glottis --flow bernoulli --p-sub 1200 --duration 0.3
//   mpirun -n 2 ./fsai_glottis --config demos/glottis/closing_cycle.toml
//   ./fsai_glottis --flow fe --fold elastic --p-sub 400 --duration 0.1
//
// Outputs in --output (default results/fsai_glottis): series.csv (t, g, Q,
// h, φ, forces, contact, closed flag, iterations), glottis.png,
// summary.json (f0_hz, open_quotient, q_peak_m3s, closed_leakage, …);
// fe: coupling.csv, flow.xdmf; elastic: fold.xdmf. Checkpoints and
// restarts: --checkpoint-every N, --restart DIR (io::RunLoop).

#include <common/Parameters.h>
#include <common/Runtime.h>
#include <common/timer.h>
#include <glottis/FlowOutput.h>
#include <glottis/FoldSurfaceRecord.h>
#include <glottis/GlottisScene.h>
#include <io/RunLoop.h>
#include <io/RunSummary.h>
#include <io/output_dir.h>

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
        fsai::glottis::GlottisScene scene;
        const auto& sp = scene.scene;
        fsai::common::Parameters params(rt.program(),
                                        "Self-oscillating vocal folds that "
                                        "close the glottis");
        scene.bind(params);
        params.parse(rt.app_args());
        scene.validate(params);
        params.print();
        io::prepare_output_dir(rt.comm(), sp.output);
        io::RunSummary summary(rt.comm(), rt.program());
        summary.set_parameters(params.to_json());
        const fsai::glottis::FoldProfile profile(scene.setup.geometry);
        if (!sp.onset_sweep.empty())
        {
          fsai::glottis::onset_sweep(rt.comm(), scene, profile);
          return;
        }

        // 2. The chosen variant, restored from a checkpoint if restarting
        io::RunLoop loop(rt.comm(), sp.output, params.to_json(), sp.run);
        auto model = scene.make_model(rt.comm(), profile, loop.rows_kept());
        model->describe(summary);
        if (!sp.replay.empty())
        {
          fsai::glottis::replay_mesh_motion(
              dynamic_cast<fsai::glottis::FlowGlottis&>(*model), sp.replay,
              summary);
          summary.write(sp.output + "/summary.json");
          return;
        }
        if (loop.restarting())
          model->restore(loop.checkpoint(), loop.fields());
        // A remeshed flow (--fe.remesh_quality) continues in a new file
        fsai::glottis::FlowOutput flow_xdmf(sp.output, *model,
                                            loop.restart_time());
        std::unique_ptr<io::TimeSeriesWriter> fold_xdmf;
        if (sp.write_every > 0 and !model->fold_fields().empty())
          fold_xdmf = std::make_unique<io::TimeSeriesWriter>(
              sp.output + "/fold.xdmf", model->fold_fields(),
              loop.restart_time());
        std::unique_ptr<fsai::glottis::FoldSurfaceRecord> surface;
        if (sp.surface_every > 0)
          surface = std::make_unique<fsai::glottis::FoldSurfaceRecord>(
              *model->elastic_fold(), sp.output, sp.surface_every, 6,
              loop.first_step());

        // 3. Time loop (the series' kept rows rebuild the statistics)
        const long n = std::lround(sp.duration / sp.dt);
        std::vector<double> t, g, Q;
        double max_pen = 0;
        long its = 0;
        int its_max = 0;
        auto record = [&](double ti, double gi, double Qi, double pen, int it)
        {
          t.push_back(ti);
          g.push_back(gi);
          Q.push_back(Qi);
          max_pen = std::max(max_pen, pen);
          its += it;
          its_max = std::max(its_max, it);
        };
        for (const auto& r : loop.open_series(
                 sp.output + "/series.csv",
                 {"t_s", "gap_m", "Q_m3s", "h_m", "phi_rad", "lift_N", "drag_N",
                  "moment_Nm", "contact_force_N", "penetration_m", "closed",
                  "iterations", "Q_inlet_m3s"},
                 summary))
          record(r[0], r[1], r[2], r[9], int(r[11]));
        fsai::glottis::Sample s;
        io::RunHooks hooks;
        hooks.step = [&](long k)
        {
          s = model->step();
          if (sp.write_every > 0 and k % sp.write_every == 0)
            flow_xdmf.write(s.t);
          if (fold_xdmf and k % sp.write_every == 0)
            fold_xdmf->write(s.t);
          if (surface)
            surface->step(k, s.t);
          loop.row({s.t, s.gap, s.Q, s.h, s.phi, s.lift, s.drag, s.moment,
                    s.contact_force, s.penetration, double(s.gap <= 0),
                    double(s.iterations), s.Q_inlet});
          record(s.t, s.gap, s.Q, s.penetration, s.iterations);
          return io::StepReport{s.t, s.converged};
        };
        hooks.save = [&](auto& scalars, auto& fields)
        { model->checkpoint(scalars, fields); };
        hooks.last_good = [&](const std::string& path)
        { return model->write_last_good(path); };
        hooks.progress = [&]
        {
          return fmt::format("t = {:.5f} g = {:+.3e} Q = {:.3e} its = {}", s.t,
                             s.gap, s.Q, s.iterations);
        };
        double wall = 0;
        {
          fsai::common::ScopedTimer timer("glottis: time loop");
          wall = loop.run(n, hooks);
        }

        // 4. Limit-cycle statistics, summary and chart
        fsai::glottis::report_limit_cycle(scene, t, g, Q, max_pen, wall,
                                          summary);
        model->report(summary);
        summary.set("coupling_iterations_mean", double(its) / double(n));
        summary.set("coupling_iterations_max", its_max);
        summary.set("coupling_unconverged_steps", loop.unconverged_steps());
        summary.write(sp.output + "/summary.json");
        io::draw_chart(rt.comm(), "plot_glottis.py", sp.output);
      });
}
