// Copyright (C) 2026 fsai developers
//
// fsai_glottis: self-oscillating vocal folds that close the glottis
// (shared/DESIGN.md §2 "Glottis closure", paper §2.5). A 2D symmetric
// half-channel with an M5-like fold profile (src/glottis/FoldProfile) on
// the 2-DOF model (TwoDofFold), Hertz impact on the symmetry axis, driven by
// the subglottal pressure.
//
//   --flow bernoulli: quasi-steady 1D Bernoulli flow with separation
//     (BernoulliFlow), the reduced model.
//   --fold elastic: the fold as a plane-strain elastic body (ElasticFold,
//     E 8 kPa, ν 0.4) with penalty contact on the axis, instead of the
//     rigid 2-DOF profile; with --flow bernoulli (ElasticBernoulliGlottis)
//     or --flow fe (ElasticFlowGlottis: the same closure model, the fluid
//     boundary following the deformed surface).
//     Its h_m is the medial surface centre's displacement towards the axis,
//     phi_rad the medial surface's tilt (> 0 divergent), moment_Nm 0.
//
// Sample runs:
//   ./fsai_glottis --flow bernoulli --p-sub 1200 --duration 0.3
//   ./fsai_glottis --flow fe --fold elastic --p-sub 400 --duration 0.1
//
// Outputs in --output (default results/fsai_glottis): series.csv (t, g, Q,
// h, φ, forces, contact force, penetration, closed flag, iterations),
// glottis.png (g, Q and the spectrum of Q; matplotlib), summary.json (f0_hz,
// open_quotient, q_peak_m3s, closed_leakage, max_penetration_m (over the
// whole run; the others over t >= stats_from × duration), sim_time_s,
// coupling_iterations_mean, ...); fe: coupling.csv, flow.xdmf.
//
// Checkpoints (--checkpoint-every N): checkpoint.json (step, time,
// parameters; bernoulli: the state) and, for fe, checkpoint_<step>.r<rank>.bin
// with each rank's fields by mesh node (flow and BDF history, mesh motion,
// fold, IQN-ILS columns). --restart DIR continues in DIR, on any number of
// ranks: series.csv and coupling.csv keep their rows up to the checkpoint,
// flow.xdmf its steps up to the checkpoint's time. A failed FE step writes
// the last good step's fields to last_good.xdmf.

#include <common/Parameters.h>
#include <common/Runtime.h>
#include <common/errors.h>
#include <common/log.h>
#include <common/timer.h>
#include <glottis/BernoulliGlottis.h>
#include <glottis/ElasticBernoulliGlottis.h>
#include <glottis/ElasticFlowGlottis.h>
#include <glottis/FlowGlottis.h>
#include <glottis/waveform.h>
#include <io/Checkpointer.h>
#include <io/CsvWriter.h>
#include <io/Progress.h>
#include <io/RunSummary.h>
#include <io/TimeSeriesWriter.h>
#include <io/csv_columns.h>
#include <io/output_dir.h>
#include <structure/modal.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <limits>

namespace
{
// Drift of the per-cycle peak flow or period (later half of the statistics
// window's cycles against the earlier half) above which the summary warns
// that the cycle has not settled: the Bernoulli default (t ≥ 0.15 s) and
// the FE default over [0.07, 0.14] s drift by 0.07 % or less, the FE
// closing cycle by −2.1 % over [0.05, 0.1] s and −1.1 % over [0.1, 0.2] s
// (stop 35)
constexpr double settled_tolerance = 0.01;

struct SceneParameters
{
  std::string output = "results/fsai_glottis";
  std::string flow = "bernoulli";
  std::string fold = "2dof";
  double p_sub = 1200;    // [Pa]: normal-to-loud speech (0.5–2 kPa)
  double duration = 0.25; // [s]
  double dt = 2e-5;       // [s]
  double rho = 1.2;       // [kg/m³]
  double separation_ratio = 1.2;
  double viscosity = 1.8e-5; // [Pa s]
  double y_floor = 0.2e-6;   // [m]
  double y_sep_min = 20e-6;  // [m]
  double stats_from = 0.5;   // statistics over t ≥ stats_from · duration
  int write_every = 50;      // fe: XDMF every N steps (0: none)
  std::vector<double> onset_sweep; // p_sub values for the stability sweep
  std::string replay; // fe: a series.csv whose fold states move the mesh
  double ramp = 5e-3; // elastic: p_sub ramp [s]
  fsai::io::RestartOptions run; // checkpoints and restarts

  void bind(fsai::common::Parameters& p)
  {
    p.add("output", output, "output folder");
    p.add_choice("flow", flow, {"fe", "bernoulli"},
                 "flow model: fe (ALE Navier-Stokes) or bernoulli "
                 "(quasi-steady 1D)");
    p.add_choice("fold", fold, {"2dof", "static", "elastic"},
                 "vocal-fold model: 2dof, static (the 2-DOF profile held "
                 "at h = --vf.h0: steady glottal flow) or elastic (plane-"
                 "strain FE fold, --elastic.*)");
    p.add("ramp", ramp,
          "--fold elastic --flow bernoulli: p_sub ramps up smoothly over "
          "this time (--flow fe: --fe.ramp) [s]");
    p.add("p-sub", p_sub, "subglottal pressure [Pa]");
    p.add("duration", duration, "simulated time [s]");
    p.add("dt", dt, "time step [s]");
    p.add("rho", rho, "air density [kg/m^3]");
    p.add("bernoulli.separation_ratio", separation_ratio,
          "flow separates where the gap reaches this multiple of its minimum");
    p.add("bernoulli.viscosity", viscosity,
          "--fold elastic: air viscosity of the Poiseuille loss [Pa s]");
    p.add("bernoulli.y_floor", y_floor,
          "--fold elastic: smallest gap the flow sees [m]");
    p.add("bernoulli.separation_min_gap", y_sep_min,
          "--fold elastic: the flow separates at separation_ratio times the "
          "smallest gap or this gap, the larger [m]");
    p.add("stats_from", stats_from,
          "limit-cycle statistics over t >= stats_from * duration");
    p.add("write_every", write_every,
          "fe: XDMF output every N steps (0: none)");
    p.add("onset_sweep", onset_sweep,
          "bernoulli: linear stability of the static equilibrium at these "
          "p_sub [Pa] (printed, onset.csv) instead of a time run");
    p.add("replay", replay,
          "fe: move the mesh through the fold states (t_s, h_m, phi_rad) of "
          "this series.csv, no flow, and report the mesh quality (tests the "
          "--ale and --closure settings on a computed trajectory)");
    run.bind(p);
  }
  void validate() const
  {
    fsai::require_positive("--p-sub", p_sub);
    fsai::require_positive("--duration", duration);
    fsai::require_positive("--dt", dt);
    fsai::require(dt <= duration, "--dt", "<= --duration", dt);
    fsai::require_positive("--rho", rho);
    fsai::require(separation_ratio >= 1, "--bernoulli.separation_ratio", ">= 1",
                  separation_ratio);
    fsai::require_positive("--bernoulli.viscosity", viscosity);
    fsai::require_positive("--bernoulli.y_floor", y_floor);
    fsai::require(y_sep_min >= 0, "--bernoulli.separation_min_gap", ">= 0",
                  y_sep_min);
    fsai::require_range("--stats_from", stats_from, 0.0, 0.95);
    run.validate();
    fsai::require(replay.empty() or flow == "fe", "--replay",
                  "used with --flow fe", replay);
    fsai::require(ramp >= 0, "--ramp", ">= 0", ramp);
  }
};

/// --replay: the mesh through a run's fold states, its quality per state
void replay_mesh_motion(fsai::glottis::FlowGlottis& fem,
                        const std::string& path, fsai::io::RunSummary& summary)
{
  const auto c = fsai::io::read_csv_columns(path, {"t_s", "h_m", "phi_rad"});
  fsai::ale::MeshQuality worst{std::numeric_limits<double>::infinity(), {}};
  double t_worst = NAN;
  for (std::size_t i = 0; i < c[0].size(); ++i)
  {
    const auto q = fem.move_mesh(c[0][i], {c[1][i], c[2][i]});
    if (q.min_scaled_jacobian < worst.min_scaled_jacobian)
    {
      worst = q;
      t_worst = c[0][i];
    }
    if ((i + 1) % 1000 == 0 or i + 1 == c[0].size())
      fsai::log::info("replay: {} of {} states, t = {:.5f} s, min scaled "
                      "Jacobian so far {:.3e} at t = {:.5f} s near ({:.4e}, "
                      "{:.4e}) m",
                      i + 1, c[0].size(), c[0][i], worst.min_scaled_jacobian,
                      t_worst, worst.where[0], worst.where[1]);
  }
  summary.set("replay_states", long(c[0].size()));
  summary.set("replay_min_scaled_jacobian", worst.min_scaled_jacobian);
  summary.set("replay_worst_t_s", t_worst);
}
} // namespace

int main(int argc, char* argv[])
{
  return fsai::common::run_main(
      argc, argv,
      [](fsai::common::Runtime& rt)
      {
        SceneParameters sp;
        fsai::glottis::FlowGlottisSetup setup;
        auto& geo = setup.geometry;
        auto& vf = setup.fold;
        auto& cp = setup.contact;
        auto& fe = setup.fe;
        fsai::common::Parameters params(rt.program(),
                                        "Self-oscillating vocal folds that "
                                        "close the glottis");
        sp.bind(params);
        setup.bind(params);
        fsai::glottis::ElasticFoldParameters ep;
        ep.bind(params);
        params.parse(rt.app_args());
        // The elastic fold in the FE flow: Aitken relaxation unless chosen.
        // IQN-ILS stalled at the first near-closure (p_sub 400 Pa, g 25 µm,
        // t = 9.9 ms, 50 iterations) and the next step inverted a gap cell;
        // Aitken went through it (6 stalled steps in 20 ms, none inverted)
        if (sp.fold == "elastic" and sp.flow == "fe"
            and !params.given("coupling.method"))
          setup.coupling.accelerator.method = "aitken";
        sp.validate();
        // Each flow model has its own ramp option: refuse the other one,
        // which would be silently ignored
        fsai::require(!params.given("ramp")
                          or (sp.fold == "elastic" and sp.flow == "bernoulli"),
                      "--ramp",
                      "used with --fold elastic --flow bernoulli (the FE "
                      "flow's ramp is --fe.ramp; the 2-DOF Bernoulli scene "
                      "has none)",
                      sp.ramp);
        fsai::require(!params.given("fe.ramp") or sp.flow == "fe", "--fe.ramp",
                      "used with --flow fe (--fold elastic --flow bernoulli: "
                      "--ramp)",
                      fe.ramp);
        if (!sp.run.restart.empty())
          sp.output = sp.run.restart; // continue in the run's own folder
        setup.validate(sp.p_sub, sp.dt);
        ep.validate();
        vf.held = sp.fold == "static";
        if (vf.held)
        {
          fsai::require(
              vf.h0 < geo.rest_gap - fe.g_min, "--vf.h0",
              "< rest gap - g_min with --fold static (an open glottis)", vf.h0);
        }
        params.print();
        fsai::io::prepare_output_dir(rt.comm(), sp.output);
        fsai::io::RunSummary summary(rt.comm(), rt.program());
        summary.set_parameters(params.to_json());

        // 1. The fold and its in-vacuo modes
        const fsai::glottis::FoldProfile profile(geo);
        const auto mp = profile.mass_properties(vf.density);
        fsai::glottis::BernoulliGlottisParameters bp;
        bp.p_sub = sp.p_sub;
        bp.rho = sp.rho;
        bp.separation_ratio = sp.separation_ratio;
        bp.viscosity = sp.viscosity;
        bp.y_floor = sp.y_floor;
        bp.y_sep_min = sp.y_sep_min;
        bp.dt = sp.dt;
        if (!sp.onset_sweep.empty())
        {
          fsai::io::CsvWriter onset(rt.comm(), sp.output + "/onset.csv",
                                    {"p_sub_Pa", "gap_static_m",
                                     "growth_rate_1_per_s", "frequency_hz",
                                     "growth_rate_2_per_s", "frequency_2_hz"});
          for (double ps : sp.onset_sweep)
          {
            bp.p_sub = ps;
            const auto r = fsai::glottis::linear_stability(profile, vf, bp);
            if (r.closed or r.growth_rate.size() < 2)
            {
              fsai::log::info("p_sub {:8.1f} Pa: static equilibrium closed "
                              "or overdamped",
                              ps);
              continue;
            }
            fsai::log::info("p_sub {:8.1f} Pa: static gap {:.3e} m, modes "
                            "{:+9.2f} 1/s at {:7.2f} Hz, {:+9.2f} 1/s at "
                            "{:7.2f} Hz",
                            ps, r.gap_static, r.growth_rate[0],
                            r.frequency_hz[0], r.growth_rate[1],
                            r.frequency_hz[1]);
            onset.row({ps, r.gap_static, r.growth_rate[0], r.frequency_hz[0],
                       r.growth_rate[1], r.frequency_hz[1]});
          }
          return;
        }
        // A restart continues from the checkpoint's step (read before the
        // FE scene is built: its coupling log keeps the rows up to there)
        fsai::io::Checkpointer ckpt(rt.comm(), sp.output, params.to_json());
        if (!sp.run.restart.empty())
          ckpt.read();
        const long k0 = ckpt.step();
        // The XDMF steps after the checkpoint's time are replaced
        const double t_restart = sp.run.restart.empty()
                                     ? std::numeric_limits<double>::quiet_NaN()
                                     : ckpt.meta().at("t").get<double>();
        const std::size_t rows_kept
            = sp.run.restart.empty() ? std::string::npos : std::size_t(k0);
        std::unique_ptr<fsai::glottis::BernoulliGlottis> reduced;
        std::unique_ptr<fsai::glottis::FlowGlottis> fem;
        std::unique_ptr<fsai::glottis::ElasticBernoulliGlottis> elastic;
        std::unique_ptr<fsai::io::TimeSeriesWriter> xdmf;
        std::unique_ptr<fsai::glottis::ElasticFlowGlottis> elastic_fe;
        std::unique_ptr<fsai::io::TimeSeriesWriter> xdmf_fold;
        if (sp.fold == "elastic")
        {
          fsai::glottis::ElasticFold* ef = nullptr;
          if (sp.flow == "bernoulli")
          {
            elastic = std::make_unique<fsai::glottis::ElasticBernoulliGlottis>(
                rt.comm(), profile, ep, cp, bp, sp.ramp, setup.coupling,
                sp.output + "/coupling.csv", rows_kept);
            ef = &elastic->fold();
          }
          else
          {
            elastic_fe = std::make_unique<fsai::glottis::ElasticFlowGlottis>(
                rt.comm(), profile, ep, cp, fe, setup.fluid, setup.ale,
                setup.coupling, sp.output + "/coupling.csv", rows_kept);
            ef = &elastic_fe->fold();
            const auto& channel = elastic_fe->channel();
            summary.set("flow_dofs", channel.describe());
            if (sp.write_every > 0)
              xdmf = std::make_unique<fsai::io::TimeSeriesWriter>(
                  sp.output + "/flow.xdmf", channel.fields(), t_restart);
          }
          std::vector<double> f;
          for (const auto& m : fsai::structure::modal_analysis(ef->solver(), 3))
            f.push_back(m.frequency_hz);
          fsai::log::info("elastic fold: {} dofs, {} surface points; "
                          "in-vacuo modes {:.1f} / {:.1f} / {:.1f} Hz",
                          ef->dofs(), ef->surface_size(), f.at(0), f.at(1),
                          f.at(2));
          summary.set("fold_dofs", ef->dofs());
          summary.set("invacuo_frequencies_hz", f);
          if (sp.write_every > 0)
            xdmf_fold = std::make_unique<fsai::io::TimeSeriesWriter>(
                sp.output + "/fold.xdmf",
                std::vector<fsai::io::TimeSeriesWriter::Field>{
                    ef->solver().displacement(), ef->solver().velocity()},
                t_restart);
        }
        else if (sp.flow == "bernoulli")
          reduced = std::make_unique<fsai::glottis::BernoulliGlottis>(
              profile, vf, cp, bp);
        else
        {
          fem = std::make_unique<fsai::glottis::FlowGlottis>(
              rt.comm(), profile, vf, cp, fe, setup.fluid, setup.ale,
              setup.coupling, sp.output + "/coupling.csv", rows_kept);
          summary.set("flow_dofs", fem->channel().describe());
          if (!sp.replay.empty())
          {
            replay_mesh_motion(*fem, sp.replay, summary);
            summary.write(sp.output + "/summary.json");
            return;
          }
          if (sp.write_every > 0)
            xdmf = std::make_unique<fsai::io::TimeSeriesWriter>(
                sp.output + "/flow.xdmf", fem->channel().fields(), t_restart);
        }
        if (sp.fold != "elastic")
        {
          const auto& fold = reduced ? reduced->fold() : fem->fold();
          const auto md = fsai::glottis::modes(fold.stiffness(), fold.mass());
          fsai::log::info(
              "fold: area {:.2f} mm², centroid ({:.3f}, {:.3f}) mm, mass "
              "{:.3f} "
              "g, I_EA {:.3e} kg m², "
              "k_h {:.1f} N/m, k_phi {:.3e} N m; in-vacuo {:.1f} / {:.1f} Hz; "
              "Hertz k_H {:.3e} N/m^1.5",
              mp.area * 1e6, mp.centroid[0] * 1e3, mp.centroid[1] * 1e3,
              fold.mass()[0][0] * 1e3, fold.mass()[1][1],
              fold.stiffness()[0][0], fold.stiffness()[1][1],
              md.frequency_hz[0], md.frequency_hz[1],
              fsai::glottis::hertz_stiffness(cp, geo.medial_radius));
          summary.set("fold_mass_kg", fold.mass()[0][0]);
          summary.set(
              "invacuo_frequencies_hz",
              std::vector<double>{md.frequency_hz[0], md.frequency_hz[1]});
        }

        // 2. Time loop
        const std::vector<std::string> columns
            = {"t_s",           "gap_m",     "Q_m3s",
               "h_m",           "phi_rad",   "lift_N",
               "drag_N",        "moment_Nm", "contact_force_N",
               "penetration_m", "closed",    "iterations",
               "Q_inlet_m3s"};
        const long n = std::lround(sp.duration / sp.dt);
        std::vector<double> t, g, Q;
        t.reserve(n);
        g.reserve(n);
        Q.reserve(n);
        double max_pen = 0;
        long its = 0;
        int its_max = 0;
        int unconverged = 0;
        double loop_wall = 0;
        // The series up to the checkpoint's step (later rows are dropped)
        // and the statistics rebuilt from those rows
        std::unique_ptr<fsai::io::CsvWriter> csv;
        if (!sp.run.restart.empty())
        {
          const auto& ck = ckpt.meta();
          if (reduced)
          {
            const auto& st = ck.at("state");
            reduced->set_state(
                {st.at("t").get<double>(),
                 st.at("fold").get<std::array<std::array<double, 2>, 3>>(),
                 st.at("load").get<std::array<double, 2>>()});
          }
          else if (elastic)
            elastic->load(ckpt.fields());
          else if (elastic_fe)
            elastic_fe->load(ckpt.fields());
          else
            fem->load(ckpt.fields());
          unconverged = ck.value("coupling_unconverged_steps", 0);
          csv = std::make_unique<fsai::io::CsvWriter>(
              rt.comm(), sp.output + "/series.csv", columns, std::size_t(k0));
          for (const auto& r : csv->kept_rows())
          {
            t.push_back(r[0]);
            g.push_back(r[1]);
            Q.push_back(r[2]);
            max_pen = std::max(max_pen, r[9]);
            its += long(r[11]);
            its_max = std::max(its_max, int(r[11]));
          }
          fsai::log::info("restart from step {} (t = {:.6g} s) of {}", k0,
                          ck.at("t").get<double>(), sp.output);
          summary.set("restarted_from_step", k0);
        }
        else
        {
          csv = std::make_unique<fsai::io::CsvWriter>(
              rt.comm(), sp.output + "/series.csv", columns);
        }
        fsai::io::Progress progress("step", double(n), 5.0, double(k0));
        {
          fsai::common::ScopedTimer timer("glottis: time loop");
          const auto loop0 = std::chrono::steady_clock::now();
          for (long k = k0 + 1; k <= n; ++k)
          {
            fsai::glottis::Sample s;
            try
            {
              s = elastic      ? elastic->step()
                  : elastic_fe ? elastic_fe->step()
                  : reduced    ? reduced->step()
                               : fem->step();
            }
            catch (const std::exception& e)
            {
              // A failed FE step (coupling not converged, inverted cell,
              // solver failure): the fields of the last good step are
              // written for inspection before the error ends the run
              if (fem or elastic_fe)
              {
                const double t_good = fem ? fem->time() : elastic_fe->time();
                if (fem)
                  fem->write_last_good(sp.output + "/last_good.xdmf");
                else
                  elastic_fe->write_last_good(sp.output + "/last_good.xdmf");
                throw std::runtime_error(fmt::format(
                    "{} [step {} failed; the last good state (step {}, t = "
                    "{:.6g} s) is in {}/last_good.xdmf{}]",
                    e.what(), k, k - 1, t_good, sp.output,
                    ckpt.last_checkpoint_note()));
              }
              throw;
            }
            if (xdmf and k % sp.write_every == 0)
              xdmf->write(s.t);
            if (xdmf_fold and k % sp.write_every == 0)
              xdmf_fold->write(s.t);
            csv->row({s.t, s.gap, s.Q, s.h, s.phi, s.lift, s.drag, s.moment,
                      s.contact_force, s.penetration, double(s.gap <= 0),
                      double(s.iterations), s.Q_inlet});
            t.push_back(s.t);
            g.push_back(s.gap);
            Q.push_back(s.Q);
            max_pen = std::max(max_pen, s.penetration);
            its += s.iterations;
            its_max = std::max(its_max, s.iterations);
            unconverged += !s.converged;
            if (sp.run.checkpoint_due(k))
            {
              nlohmann::json scalars{
                  {"coupling_unconverged_steps", unconverged}};
              if (reduced)
              {
                const auto st = reduced->state();
                scalars["state"]
                    = {{"t", st.t}, {"fold", st.fold}, {"load", st.load}};
                ckpt.write(k, s.t, scalars, nullptr);
              }
              else
              {
                const auto fields = elastic      ? elastic->save()
                                    : elastic_fe ? elastic_fe->save()
                                                 : fem->save();
                ckpt.write(k, s.t, scalars, &fields);
              }
            }
            sp.run.kill_if_requested(k);
            progress.update(double(k),
                            fmt::format("t = {:.5f} g = {:+.3e} Q = {:.3e} "
                                        "its = {}",
                                        s.t, s.gap, s.Q, s.iterations));
          }
          loop_wall = std::chrono::duration<double>(
                          std::chrono::steady_clock::now() - loop0)
                          .count();
        }
        const double wall = loop_wall;

        // 3. Limit-cycle statistics
        // Closed: the fold at or across the axis, g ≤ 0 (both models; in
        // the FE model the gap is then porous from the fluid boundary, held
        // above g_min, down to the axis). The approach 0 < g ≤ g_min is
        // reported separately: the flow is still falling there
        const auto cs = fsai::glottis::cycle_stats(
            t, g, Q, sp.stats_from * sp.duration, 0.0);
        const auto cs_gmin = fsai::glottis::cycle_stats(
            t, g, Q, sp.stats_from * sp.duration, fe.g_min);
        fsai::log::info(
            "limit cycle (t >= {:.3f} s): {} cycles, f0 = {:.2f} Hz, open "
            "quotient {:.3f}, peak flow {:.3e} m³/s, closed in every cycle: "
            "{}, closed-phase leakage {:.2e} of the peak, gap amplitude "
            "{:.3e} m, cycle-to-cycle variation of the period {:.1f} % and "
            "of the peak flow {:.1f} %; max penetration over the whole run "
            "(start-up included) {:.3e} m; time loop {:.2f} s wall = {:.3g} "
            "s per simulated s",
            sp.stats_from * sp.duration, cs.cycles, cs.f0_hz, cs.open_quotient,
            cs.q_peak, cs.closes_every_cycle ? "yes" : "no", cs.closed_leakage,
            cs.gap_amplitude, 100 * cs.period_cv, 100 * cs.q_peak_cv, max_pen,
            wall, wall / sp.duration);
        summary.set("f0_hz", cs.f0_hz);
        summary.set("open_quotient", cs.open_quotient);
        summary.set("q_peak_m3s", cs.q_peak);
        summary.set("closed_leakage", cs.closed_leakage);
        summary.set("leakage_below_g_min", cs_gmin.closed_leakage);
        summary.set("max_penetration_m", max_pen);
        summary.set("sim_time_s", sp.duration);
        summary.set("cycles", cs.cycles);
        summary.set("closes_every_cycle", cs.closes_every_cycle);
        summary.set("gap_amplitude_m", cs.gap_amplitude);
        // Cycle-to-cycle regularity (0 on a limit cycle)
        summary.set("period_cv", cs.period_cv);
        summary.set("q_peak_cycle_cv", cs.q_peak_cv);
        summary.set("q_peak_cycle_mean_m3s", cs.q_peak_mean);
        // Settled? (later half of the cycles against the earlier half)
        summary.set("q_peak_drift", cs.q_peak_drift);
        summary.set("period_drift", cs.period_drift);
        if (std::abs(cs.q_peak_drift) > settled_tolerance
            or std::abs(cs.period_drift) > settled_tolerance)
        {
          fsai::log::warn(
              "the cycle has not settled: from the earlier to the later "
              "half of the {} cycles after t = {:.3f} s the mean peak flow "
              "changes by {:+.2f} % and the mean period by {:+.2f} %; the "
              "statistics above are of a transient (run longer, or raise "
              "--stats_from)",
              cs.cycles, sp.stats_from * sp.duration, 100 * cs.q_peak_drift,
              100 * cs.period_drift);
        }
        summary.set("coupling_iterations_mean", double(its) / double(n));
        summary.set("coupling_iterations_max", its_max);
        summary.set("coupling_unconverged_steps", unconverged);
        // wall time of the time loop per simulated second (the real-time
        // factor: < 1 is faster than real time)
        summary.set("wall_per_sim_s", wall / sp.duration);
        summary.write(sp.output + "/summary.json");

        // 4. Chart (optional: a missing matplotlib only warns)
        if (rt.rank() == 0)
        {
          const std::string cmd = std::string(FSAI_PYTHON) + " "
                                  + FSAI_SCRIPTS_DIR + "/plot_glottis.py "
                                  + sp.output + " > /dev/null 2>&1";
          if (std::system(cmd.c_str()) != 0)
            fsai::log::warn("could not draw glottis.png ({})", cmd);
        }
      });
}
