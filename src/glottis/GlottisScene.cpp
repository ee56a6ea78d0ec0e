// Copyright (C) 2026 fsai developers
#include "GlottisScene.h"
#include "ElasticBernoulliGlottis.h"
#include "ElasticFlowGlottis.h"
#include "waveform.h"
#include <cmath>
#include <common/Parameters.h>
#include <common/errors.h>
#include <common/log.h>
#include <io/CsvWriter.h>
#include <io/RunSummary.h>
#include <io/csv_columns.h>
#include <limits>
#include <utility>

namespace
{
// Drift of the per-cycle peak flow or period (later half of the statistics
// window's cycles against the earlier half) above which the summary warns
// that the cycle has not settled: the Bernoulli default (t ≥ 0.15 s) and
// the FE default over [0.07, 0.14] s drift by 0.07 % or less, the FE
// closing cycle by −2.1 % over [0.05, 0.1] s and −1.1 % over [0.1, 0.2] s
// (docs/glottis.md, "The limit cycle")
constexpr double settled_tolerance = 0.01;
} // namespace

//-----------------------------------------------------------------------------
void fsai::glottis::GlottisSceneParameters::bind(fsai::common::Parameters& p)
{
  p.add("output", output, "output folder");
  p.add_choice("flow", flow, {"fe", "bernoulli"},
               "flow model: fe (ALE Navier-Stokes) or bernoulli "
               "(quasi-steady 1D)");
  p.add_choice("fold", fold, {"2dof", "static", "elastic"},
               std::string("vocal-fold model: 2dof, static (the 2-DOF profile "
                           "held at h = --vf.h0: steady glottal flow) or "
                           "elastic (plane-strain FE fold, --elastic.*)")
                   + elastic_fe_defaults_help());
  p.add("ramp", ramp,
        "--fold elastic --flow bernoulli: p_sub ramps up smoothly over "
        "this time (--flow fe: --fe.ramp) [s]");
  p.add("p-sub", p_sub, "subglottal pressure [Pa]");
  p.add("duration", duration, "simulated time [s]");
  p.add("dt", dt, "time step [s]");
  bernoulli.bind(p);
  p.add("stats_from", stats_from,
        "limit-cycle statistics over t >= stats_from * duration");
  p.add("write_every", write_every, "fe: XDMF output every N steps (0: none)");
  p.add("surface_every", surface_every,
        "--fold elastic: the fold's surface displacement every N steps "
        "(fold_surface.csv) and its in-vacuo modes there (modes_surface.csv) "
        "for bench/glottis_pod.py (0: none)");
  p.add("onset_sweep", onset_sweep,
        "bernoulli: linear stability of the static equilibrium at these "
        "p_sub [Pa] (printed, onset.csv) instead of a time run");
  p.add("replay", replay,
        "fe: move the mesh through the fold states (t_s, h_m, phi_rad) of "
        "this series.csv, no flow, and report the mesh quality (tests the "
        "--ale and --closure settings on a computed trajectory)");
  run.bind(p);
}
//-----------------------------------------------------------------------------
void fsai::glottis::GlottisSceneParameters::validate() const
{
  fsai::require_positive("--p-sub", p_sub);
  fsai::require_positive("--duration", duration);
  fsai::require_positive("--dt", dt);
  fsai::require(dt <= duration, "--dt", "<= --duration", dt);
  bernoulli.validate();
  fsai::require_range("--stats_from", stats_from, 0.0, 0.95);
  run.validate();
  fsai::require(replay.empty() or flow == "fe", "--replay",
                "used with --flow fe", replay);
  fsai::require(ramp >= 0, "--ramp", ">= 0", ramp);
  fsai::require(surface_every >= 0, "--surface_every", ">= 0", surface_every);
  fsai::require(surface_every == 0 or fold == "elastic", "--surface_every",
                "used with --fold elastic", surface_every);
}
//-----------------------------------------------------------------------------
void fsai::glottis::GlottisScene::bind(fsai::common::Parameters& p)
{
  scene.bind(p);
  setup.bind(p);
  elastic.bind(p);
}
//-----------------------------------------------------------------------------
void fsai::glottis::GlottisScene::validate(const fsai::common::Parameters& p)
{
  if (scene.fold == "elastic" and scene.flow == "fe")
    apply_elastic_fe_defaults(p);
  scene.validate();
  // Each flow model has its own ramp option: refuse the other one, which
  // would be silently ignored
  fsai::require(!p.given("ramp")
                    or (scene.fold == "elastic" and scene.flow == "bernoulli"),
                "--ramp",
                "used with --fold elastic --flow bernoulli (the FE flow's "
                "ramp is --fe.ramp; the 2-DOF Bernoulli scene has none)",
                scene.ramp);
  fsai::require(!p.given("fe.ramp") or scene.flow == "fe", "--fe.ramp",
                "used with --flow fe (--fold elastic --flow bernoulli: "
                "--ramp)",
                setup.fe.ramp);
  if (!scene.run.restart.empty())
    scene.output = scene.run.restart; // continue in the run's own folder
  setup.validate(scene.p_sub, scene.dt);
  elastic.validate();
  setup.fold.held = scene.fold == "static";
  if (setup.fold.held)
  {
    fsai::require(setup.fold.h0 < setup.geometry.rest_gap - setup.fe.g_min,
                  "--vf.h0",
                  "< rest gap - g_min with --fold static (an open glottis)",
                  setup.fold.h0);
  }
}
//-----------------------------------------------------------------------------
namespace
{
/// apply_elastic_fe_defaults's settings, as typed on the command line
const std::vector<std::pair<std::string, std::string>> elastic_fe_presets = {
    // The elastic fold closes the glottis faster than the 2-DOF fold (6.4x
    // its MFDR in the voice): at 800 Pa its mean cycle peak at Δt 2e−5 is
    // 5–10 % above Δt 1e−5's (two pairs of runs), and Δt 5e−6 moves it by
    // −1.2 % (docs/glottis.md, "The elastic fold in the FE flow"); the
    // voice's --quick keeps its own coarse step
    {"dt", "1e-5"},
    // At 800 Pa the mean cycle peak rises as the gap cells shrink (h_gap
    // 0.05 → 0.035 → 0.025 mm: +8.7 %, +4.3 %) and settles at 0.025 mm
    // (0.018 mm: −1.5 %, f0 −0.08 %; docs/glottis.md, the mesh/Δt check);
    // 26k flow unknowns against 16k, 1.9x the time in the voice
    {"fe.h_gap", "0.025e-3"},
    // A fold held only at its lateral attachment (plane strain) does not
    // close every cycle at 800 Pa; held at its anterior and posterior ends
    // it does
    {"elastic.clamped_ends", "true"},
    // In a nearly closed glottis the squeezed air film damps the surface so
    // strongly that the trapezoidal rule rings from step to step and the
    // coupling diverges in the closed phase; generalised-α (E18a) damps
    // that ringing and stays second order (Newmark γ 0.6 damps it too but
    // is first order: its Δt check misses)
    {"elastic.rho_inf", "0.8"},
    // The cell-wise porous switch makes the coupling's map discontinuous at
    // closure (unconverged steps); the geometric ramp over 20 µm (about
    // half a gap cell of this mesh) makes it continuous (G4)
    {"closure.porous_ramp", "2e-5"},
    // With the whole fold surface lifted above g_min by its lowest point's
    // lift, the contact point's motion in the closed phase moves the whole
    // fluid boundary and the coupling diverges (35 ms at 800 Pa); lifted
    // only around the points below 2 g_min it passes
    {"closure.lift", "local"},
    // The soft fold shears the fluid mesh: the channel is meshed again
    // around the fold (an open glottis), and at an inverted cell as a last
    // resort (E13a). (closure.wedge_angle keeps its default 30°: the fluid
    // boundary is kept out of the wedge where the fold's superior surface
    // meets the wall, G3a)
    {"fe.remesh_quality", "0.1"},
    // A step whose coupling does not converge, or whose mesh move inverts
    // a cell, is taken again as two (then four) shorter steps (E13b, on the
    // variable-step BDF2 E19)
    {"fe.step_cuts", "2"},
    // τ_m's transient term held at Δt 2e−5 (E20): a halved or cut step then
    // changes the time discretisation only; with τ_m following Δt, halving
    // Δt moves the peak flow by twice as much
    {"fluid.tau_step", "2e-5"},
    // IQN-ILS: 2–3 coupling iterations per step where Aitken takes 3–5
    // (with the porous ramp; without it IQN-ILS stalled at the first
    // near-closure)
    {"coupling.method", "iqn-ils"},
};
} // namespace

void fsai::glottis::apply_elastic_fe_defaults(const fsai::common::Parameters& p)
{
  for (const auto& [key, text] : elastic_fe_presets)
    p.preset(key, text);
}
//-----------------------------------------------------------------------------
std::string fsai::glottis::elastic_fe_defaults_help()
{
  std::string out
      = "; with --flow fe the elastic fold's own defaults unless given:";
  std::string sep = " --";
  for (const auto& [key, text] : elastic_fe_presets)
  {
    out += sep + key + " " + text;
    sep = ", --";
  }
  return out;
}
//-----------------------------------------------------------------------------
fsai::glottis::BernoulliGlottisParameters
fsai::glottis::GlottisScene::bernoulli() const
{
  BernoulliGlottisParameters bp = scene.bernoulli;
  bp.p_sub = scene.p_sub;
  bp.dt = scene.dt;
  return bp;
}
//-----------------------------------------------------------------------------
std::unique_ptr<fsai::glottis::GlottisModel>
fsai::glottis::GlottisScene::make_model(MPI_Comm comm,
                                        const FoldProfile& profile,
                                        std::size_t rows_kept) const
{
  return make_glottis(comm, profile, scene.flow, scene.fold, setup, elastic,
                      bernoulli(), scene.ramp, scene.output + "/coupling.csv",
                      rows_kept);
}
//-----------------------------------------------------------------------------
std::unique_ptr<fsai::glottis::GlottisModel> fsai::glottis::make_glottis(
    MPI_Comm comm, const FoldProfile& profile, const std::string& flow,
    const std::string& fold, const FlowGlottisSetup& setup,
    const ElasticFoldParameters& elastic, const BernoulliGlottisParameters& bp,
    double ramp, const std::string& log, std::size_t rows_kept)
{
  const bool fe = flow == "fe";
  if (fold == "elastic" and fe)
  {
    return std::make_unique<ElasticFlowGlottis>(
        comm, profile, elastic, setup.contact, setup.fe, setup.fluid, setup.ale,
        setup.coupling, log, rows_kept);
  }
  if (fold == "elastic")
  {
    return std::make_unique<ElasticBernoulliGlottis>(
        comm, profile, elastic, setup.contact, bp, ramp, setup.coupling, log,
        rows_kept);
  }
  if (fe)
  {
    fsai::require(setup.fe.remesh_quality == 0, "--fe.remesh_quality",
                  "0 with the 2-DOF fold (remeshing is for --fold elastic)",
                  setup.fe.remesh_quality);
    fsai::require(setup.fe.step_cuts == 0, "--fe.step_cuts",
                  "0 with the 2-DOF fold (step cuts are for --fold elastic)",
                  setup.fe.step_cuts);
    fsai::require(setup.fe.lift == "uniform", "--closure.lift",
                  "uniform with the 2-DOF fold (local is for --fold elastic)",
                  setup.fe.lift);
    return std::make_unique<FlowGlottis>(
        comm, profile, setup.fold, setup.contact, setup.fe, setup.fluid,
        setup.ale, setup.coupling, log, rows_kept);
  }
  return std::make_unique<BernoulliGlottis>(profile, setup.fold, setup.contact,
                                            bp);
}
//-----------------------------------------------------------------------------
void fsai::glottis::onset_sweep(MPI_Comm comm, const GlottisScene& s,
                                const FoldProfile& profile)
{
  io::CsvWriter onset(comm, s.scene.output + "/onset.csv",
                      {"p_sub_Pa", "gap_static_m", "growth_rate_1_per_s",
                       "frequency_hz", "growth_rate_2_per_s",
                       "frequency_2_hz"});
  auto bp = s.bernoulli();
  for (double ps : s.scene.onset_sweep)
  {
    bp.p_sub = ps;
    const auto r = linear_stability(profile, s.setup.fold, bp);
    if (r.closed or r.growth_rate.size() < 2)
    {
      fsai::log::info("p_sub {:8.1f} Pa: static equilibrium closed or "
                      "overdamped",
                      ps);
      continue;
    }
    fsai::log::info("p_sub {:8.1f} Pa: static gap {:.3e} m, modes {:+9.2f} "
                    "1/s at {:7.2f} Hz, {:+9.2f} 1/s at {:7.2f} Hz",
                    ps, r.gap_static, r.growth_rate[0], r.frequency_hz[0],
                    r.growth_rate[1], r.frequency_hz[1]);
    onset.row({ps, r.gap_static, r.growth_rate[0], r.frequency_hz[0],
               r.growth_rate[1], r.frequency_hz[1]});
  }
}
//-----------------------------------------------------------------------------
void fsai::glottis::replay_mesh_motion(FlowGlottis& fem,
                                       const std::string& path,
                                       io::RunSummary& summary)
{
  const auto c = io::read_csv_columns(path, {"t_s", "h_m", "phi_rad"});
  ale::MeshQuality worst{std::numeric_limits<double>::infinity(), {}};
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
//-----------------------------------------------------------------------------
void fsai::glottis::report_limit_cycle(const GlottisScene& s,
                                       const std::vector<double>& t,
                                       const std::vector<double>& g,
                                       const std::vector<double>& Q,
                                       double max_penetration, double loop_wall,
                                       io::RunSummary& summary)
{
  const auto& sp = s.scene;
  const double t0 = sp.stats_from * sp.duration;
  // Closed: the fold at or across the axis, g ≤ 0 (both models; in the FE
  // model the gap is then porous from the fluid boundary, held above g_min,
  // down to the axis, G4). The approach 0 < g ≤ g_min is reported
  // separately: the flow is still falling there
  const auto cs = cycle_stats(t, g, Q, t0, 0.0);
  const auto cs_gmin = cycle_stats(t, g, Q, t0, s.setup.fe.g_min);
  fsai::log::info(
      "limit cycle (t >= {:.3f} s): {} cycles, f0 = {:.2f} Hz, open quotient "
      "{:.3f}, peak flow {:.3e} m³/s, closed in every cycle: {}, closed-phase "
      "leakage {:.2e} of the peak, gap amplitude {:.3e} m, cycle-to-cycle "
      "variation of the period {:.1f} % and of the peak flow {:.1f} %; max "
      "penetration over the whole run (start-up included) {:.3e} m; time "
      "loop {:.2f} s wall = {:.3g} s per simulated s",
      t0, cs.cycles, cs.f0_hz, cs.open_quotient, cs.q_peak,
      cs.closes_every_cycle ? "yes" : "no", cs.closed_leakage, cs.gap_amplitude,
      100 * cs.period_cv, 100 * cs.q_peak_cv, max_penetration, loop_wall,
      loop_wall / sp.duration);
  summary.set("f0_hz", cs.f0_hz);
  summary.set("open_quotient", cs.open_quotient);
  summary.set("q_peak_m3s", cs.q_peak);
  summary.set("closed_leakage", cs.closed_leakage);
  summary.set("leakage_below_g_min", cs_gmin.closed_leakage);
  summary.set("max_penetration_m", max_penetration);
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
    fsai::log::warn("the cycle has not settled: from the earlier to the "
                    "later half of the {} cycles after t = {:.3f} s the mean "
                    "peak flow changes by {:+.2f} % and the mean period by "
                    "{:+.2f} %; the statistics above are of a transient (run "
                    "longer, or raise --stats_from)",
                    cs.cycles, t0, 100 * cs.q_peak_drift,
                    100 * cs.period_drift);
  }
  // Wall time of the time loop per simulated second (the real-time factor:
  // < 1 is faster than real time)
  summary.set("wall_per_sim_s", loop_wall / sp.duration);
}
