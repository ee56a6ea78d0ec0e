// Copyright (C) 2026 fsai developers
//
// fsai_demo: the voice — airflow, self-oscillating vocal folds that close
// the glottis, and the sound that forms in the vocal tract (shared/DESIGN.md
// §2, paper §2.4, §3.3, §3.4). The glottis scene with the FE flow
// (FlowGlottis: ALE Navier–Stokes, 2-DOF fold, closure, Hertz contact)
// drives, one way, the acoustic wave equation (E14, E21, WaveSolver) on a
// fixed domain that contains the flow domain Ω^f_0 and continues it by the
// vowel's vocal tract to the lips and a radiation region
// (mesh::voice_domain). Each flow step: Lighthill's source ρ0 v v from the
// converged flow (FlowSource, reference-configuration interpolation),
// tapered to zero before the flow outlet and at the subglottal inlet; the
// fold surface vibrates (∂p'/∂n = −ρ0 a·n); the glottal flow Q(t) enters as
// a volume-source pair (+Q after the fold, −Q before it: the valve's
// monopole, which incompressible flow does not put into ρ0 v v); the
// acoustic glottis takes the flow's slit law (inertia and resistance of the
// current gap, closed when the folds touch); then one acoustic Newmark step
// with the same Δt.
//
// Sample runs:
//   ./fsai_demo --vowel u                  # 0.1 s, 2 ranks recommended
//   ./fsai_demo --quick                    # short coarse run (tests)
//   ./fsai_demo --vowel a --radiation pml
//   ./fsai_demo --tract tube               # a short straight tube instead
//   ./fsai_demo --voice.taper false        # truncated source (fails)
//
// Outputs in --output (default results/fsai_demo): series.csv (t, g, Q, h,
// φ, p' at the lips and the microphone, ...), sound.wav (microphone, 44.1
// kHz, 16 bit), spectrum.csv, voice.png, flow.xdmf (velocity, pressure,
// porous indicator, mesh displacement), acoustic.xdmf (p'), summary.json
// (vowel, f0_hz, formants_from_sound_hz, tract_formants_hz, spl_db,
// sim_time_s, wav, ...).

#include <acoustics/FlowSource.h>
#include <acoustics/WaveSolver.h>
#include <acoustics/sound.h>
#include <acoustics/spectrum.h>
#include <acoustics/tube_model.h>
#include <common/Parameters.h>
#include <common/Runtime.h>
#include <common/errors.h>
#include <common/log.h>
#include <common/timer.h>
#include <dolfinx/fem/utils.h>
#include <glottis/BernoulliFlow.h>
#include <glottis/FlowGlottis.h>
#include <glottis/waveform.h>
#include <io/Checkpointer.h>
#include <io/CsvWriter.h>
#include <io/PointProbes.h>
#include <io/Progress.h>
#include <io/RunSummary.h>
#include <io/TimeSeriesWriter.h>
#include <io/field_state.h>
#include <io/output_dir.h>
#include <mesh/area_function.h>
#include <mesh/voice_domain.h>

#include <chrono>
#include <cmath>
#include <fmt/ranges.h>
#include <limits>

namespace
{
struct VoiceParameters
{
  std::string output = "results/fsai_demo";
  std::string vowel = "u";
  std::string area_function; // overrides vowel
  std::string tract = "vowel";
  double tube_length = 0.04; // --tract tube [m]
  double tube_area = 3e-4;   // [m²]
  double p_sub = 1200;       // [Pa]
  double duration = 0.1;     // [s]
  double dt = 2e-5;          // [s]
  bool quick = false;
  std::string radiation = "sommerfeld";
  std::string subglottal = "absorbing";
  bool yielding_walls = true;
  double layer = 0.02; // [m]
  bool taper = true;
  bool lighthill = true;      // Lighthill's source on
  bool wall = true;           // vibrating fold surface on
  bool source_average = true; // Lighthill velocity at the step midpoint
  // The glottal volume flow as a volume-source pair (see bind()) and the
  // acoustic glottis following the flow's (the slit law in the cells under
  // the fold): both on, as together they give the tract's F1/F2 (README
  // "Acoustic glottis" has the measured F1/F2 of all four variants)
  bool monopole = true;
  double monopole_length = 0.005; // [m] each source's extent along x
  bool glottal_slit = true;
  bool slit_lighthill = false; // Lighthill's force in the slit's law
  double taper_start = 0.02;   // ramp from here before the flow outlet [m]
  double taper_end = 0.005;    // to zero here before the outlet [m]
  double taper_inlet = 0.005;  // ramp up over this length after the inlet [m]
  double mic_distance = 0.03;  // [m] beyond the lips, on the axis
  double stats_from = 0.5;
  int write_every = 100;
  int wav_rate = 44100;
  bool check_result = false;
  double check_f0_tolerance = 0.01; // relative
  fsai::io::RestartOptions run;     // checkpoints and restarts

  void bind(fsai::common::Parameters& p)
  {
    p.add("output", output, "output folder");
    p.add_choice("vowel", vowel, {"u", "a", "i"},
                 "vowel of the shipped area functions (meshes/vowel_*.csv)");
    p.add("area-function", area_function,
          "area-function CSV (x_cm,area_cm2); overrides --vowel");
    p.add_choice("tract", tract, {"vowel", "tube"},
                 "vocal tract: the vowel's, or a short straight tube");
    p.add("tube.length", tube_length, "--tract tube: length [m]");
    p.add("tube.area", tube_area, "--tract tube: area [m^2]");
    p.add("p-sub", p_sub, "subglottal pressure [Pa]");
    p.add("duration", duration, "simulated time [s]");
    p.add("dt", dt, "time step of flow and sound [s]");
    p.add("quick", quick,
          "short coarse run for tests (coarser meshes, 0.04 s, dt 5e-5)");
    p.add_choice("radiation", radiation, {"sommerfeld", "pml"},
                 "radiation boundary: Sommerfeld (with the curvature term) "
                 "or an absorbing layer");
    p.add("layer", layer, "absorbing-layer thickness for --radiation pml [m]");
    p.add("voice.yielding_walls", yielding_walls,
          "supraglottal tract walls yield (--acoustics.wall_*; false: "
          "rigid walls, resonances damped by radiation only)");
    p.add_choice("voice.subglottal", subglottal, {"absorbing", "hard"},
                 "subglottal end of the acoustic domain: plane-wave "
                 "absorbing (anechoic trachea) or sound-hard");
    p.add("voice.taper", taper,
          "taper Lighthill's source to zero before the flow outlet (false: "
          "truncated source, for the failure study)");
    p.add("voice.lighthill", lighthill,
          "Lighthill's source (false: the fold surface's vibration only)");
    p.add("voice.wall", wall,
          "vibrating fold surface (false: Lighthill's source only)");
    p.add("voice.glottal_slit", glottal_slit,
          "the acoustic glottis (fixed at the rest gap) "
          "follows the flow's: in the cells under the fold the momentum law "
          "of the current slit (inertia g0/g, viscous and jet resistance; "
          "false: air at rest in the rest slit)");
    p.add("voice.slit_lighthill", slit_lighthill,
          "with --voice.glottal_slit: Lighthill's force in the slit's "
          "momentum law (true: 139 dB of spurious sound in --quick) or no "
          "source in the slit cells (false)");
    p.add("voice.source_average", source_average,
          "Lighthill's source from (v_n + v_n+1)/2 (false: v_n+1)");
    p.add("voice.monopole", monopole,
          "the flow's glottal volume flow Q(t) as a volume-source pair, +Q "
          "after the fold and -Q before it (the valve's monopole, which "
          "Lighthill's rho0 v v of the incompressible flow does not carry)");
    p.add("voice.monopole_length", monopole_length,
          "--voice.monopole: extent of each source along the channel [m]");
    p.add("voice.taper_start", taper_start,
          "taper starts this far before the flow outlet [m]");
    p.add("voice.taper_end", taper_end,
          "source is zero from this far before the flow outlet [m]");
    p.add("voice.taper_inlet", taper_inlet,
          "source ramps up over this length after the inlet [m]");
    p.add("mic_distance", mic_distance,
          "microphone on the axis, this far beyond the lips [m]");
    p.add("stats_from", stats_from,
          "statistics and sound analysis over t >= stats_from * duration");
    p.add("write_every", write_every, "XDMF output every N steps (0: none)");
    p.add("wav_rate", wav_rate, "sample rate of sound.wav [Hz]");
    p.add("check-result", check_result,
          "fail unless the sound is finite and audible (SPL > 40 dB), its "
          "f0 matches the fold's within --check.f0_tolerance and the fold "
          "f0 is in the male range 85-155 Hz");
    p.add("check.f0_tolerance", check_f0_tolerance,
          "relative tolerance of --check-result on the sound's f0 (0: not "
          "checked)");
    run.bind(p);
  }
  void validate() const
  {
    fsai::require_positive("--p-sub", p_sub);
    fsai::require_positive("--duration", duration);
    fsai::require_positive("--dt", dt);
    fsai::require(dt <= duration / 10, "--dt", "<= --duration / 10", dt);
    fsai::require_positive("--tube.length", tube_length);
    fsai::require_positive("--tube.area", tube_area);
    fsai::require_positive("--layer", layer);
    fsai::require(taper_start > taper_end and taper_end >= 0,
                  "--voice.taper_start", "> --voice.taper_end >= 0",
                  taper_start);
    fsai::require(taper_inlet >= 0, "--voice.taper_inlet", ">= 0", taper_inlet);
    fsai::require_positive("--voice.monopole_length", monopole_length);
    fsai::require_positive("--mic_distance", mic_distance);
    fsai::require_range("--stats_from", stats_from, 0.0, 0.95);
    fsai::require(write_every >= 0, "--write_every", ">= 0", write_every);
    fsai::require(wav_rate == 44100 or wav_rate == 48000, "--wav_rate",
                  "44100 or 48000", wav_rate);
    run.validate();
  }
};

/// Height of the polyline `surface` (points ordered along x) above x: the
/// lowest crossing of the vertical line at x (+∞ if none)
double surface_height(const std::vector<std::array<double, 2>>& surface,
                      double x)
{
  double y = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i + 1 < surface.size(); ++i)
  {
    const auto& a = surface[i];
    const auto& b = surface[i + 1];
    if ((x - a[0]) * (x - b[0]) > 0 or a[0] == b[0])
      continue;
    y = std::min(y, a[1] + (b[1] - a[1]) * (x - a[0]) / (b[0] - a[0]));
  }
  return y;
}

/// Taper χ of Lighthill's source (P1 nodal values): 1 inside the flow
/// domain, cos² ramps to 0 towards the inlet and before the outlet
double source_taper(double x, double x_in, double x_out,
                    const VoiceParameters& vp)
{
  if (!vp.taper)
    return 1.0;
  auto ramp = [](double s) // 0 → 0, 1 → 1
  {
    s = std::clamp(s, 0.0, 1.0);
    return std::pow(std::sin(0.5 * M_PI * s), 2);
  };
  const double up
      = vp.taper_inlet > 0 ? ramp((x - x_in) / vp.taper_inlet) : 1.0;
  const double a = x_out - vp.taper_start, b = x_out - vp.taper_end;
  return up * (1.0 - ramp((x - a) / (b - a)));
}
} // namespace

int main(int argc, char* argv[])
{
  return fsai::common::run_main(
      argc, argv,
      [](fsai::common::Runtime& rt)
      {
        namespace ac = fsai::acoustics;
        const auto wall0 = std::chrono::steady_clock::now();

        // 1. Parameters: the glottis scene's (FE flow) and the sound's
        VoiceParameters vp;
        fsai::glottis::FlowGlottisSetup setup;
        auto& geo = setup.geometry;
        auto& vf = setup.fold;
        auto& fe = setup.fe;
        ac::WaveParameters wave;
        // Numerical damping in the sound's Newmark step (E21): γ = 0.6,
        // β = (γ + ½)²/4. The trapezoidal rule (γ = ½) keeps every mode it
        // is given undamped, and the closure events (the flow's jump when
        // the slit shuts, the fold's impact) feed the ringing near 18 kHz
        // (a few cells of the radiation mesh per wavelength, 2.7 steps per
        // period): with γ = ½ it grew at each closure until it was 97 % of
        // the sound (medium resolution: 2.5 kPa rms at 90 ms) and biased
        // the LPC. With γ = 0.6 a component at ωΔt = 2.3 loses 11 % of its
        // amplitude per step; the formants of [u] at Δt 2e−5 gain the
        // bandwidths 1, 16, 47 and 125 Hz (F1..F4; the 1D tract's own are
        // 54, 16, 2, 1 Hz). Measured: bench/voice.py, u_*_trapezoidal
        wave.newmark_gamma = 0.6;
        wave.newmark_beta = 0.3025;
        fsai::mesh::VoiceDomainGeometry vg;
        fsai::common::Parameters params(rt.program(),
                                        "The voice: flow, folds and sound");
        vp.bind(params);
        setup.bind(params);
        wave.bind(params);
        vg.bind(params);
        // --quick sets coarse defaults before parsing, so any option given
        // with it still overrides them
        for (const auto& arg : rt.app_args())
          vp.quick |= arg == "--quick" or arg == "--quick=true";
        if (vp.quick)
        {
          // Coarse flow and acoustic meshes, a larger step and a larger
          // initial perturbation so the oscillation is under way within
          // 0.04 s (the sound's f0 needs two periods in the window)
          vp.duration = 0.04;
          vp.dt = 5e-5;
          fe.sizes.h_far = 1e-3;
          fe.sizes.h_gap = 0.1e-3;
          vg.h = 0.008;
          vf.h0 = 0.15e-3;
          vp.stats_from = 0.4;
          vp.write_every = 0;
        }
        params.parse(rt.app_args());
        vp.validate();
        setup.validate(vp.p_sub, vp.dt);
        wave.validate();
        vg.layer = vp.radiation == "pml" ? vp.layer : 0.0;
        vg.validate();
        fsai::require(vp.mic_distance < vg.radius, "--mic_distance",
                      "inside the radiation region (< --voice.radius)",
                      vp.mic_distance);
        if (!vp.run.restart.empty())
          vp.output = vp.run.restart; // continue in the run's own folder
        params.print();
        fsai::io::prepare_output_dir(rt.comm(), vp.output);
        fsai::io::RunSummary summary(rt.comm(), rt.program());
        summary.set_parameters(params.to_json());
        // A restart continues from the checkpoint's step (read before the
        // scene is built: its coupling log keeps the rows up to there)
        fsai::io::Checkpointer ckpt(rt.comm(), vp.output, params.to_json());
        if (!vp.run.restart.empty())
          ckpt.read();
        const long k0 = ckpt.step();
        const double t_restart = vp.run.restart.empty()
                                     ? std::numeric_limits<double>::quiet_NaN()
                                     : ckpt.meta().at("t").get<double>();

        // 2. The tract: the vowel's area function (or a straight tube),
        // its first part replaced by the flow domain's channel, and the 1D
        // transfer-function formants of exactly that tract (baffled lips)
        const fsai::glottis::FoldProfile profile(geo);
        const std::string label
            = vp.tract == "tube"
                  ? "tube"
                  : (vp.area_function.empty() ? vp.vowel : vp.area_function);
        const fsai::mesh::AreaFunction vowel
            = vp.tract == "tube" ? fsai::mesh::uniform_tube(
                  geo.outlet_length + vp.tube_length, vp.tube_area)
                                 : fsai::mesh::read_area_function(
                                     vp.area_function.empty()
                                         ? fsai::mesh::vowel_file(vp.vowel)
                                         : vp.area_function);
        const fsai::mesh::AreaFunction tract
            = fsai::mesh::voice_tract(vowel, profile);
        // Same walls as the FE model: the planar model's two walls of
        // depth L_g per unit length
        ac::TubeWall wall1d;
        if (vp.yielding_walls)
        {
          wall1d = {wave.wall_mass, wave.wall_resistance, wave.wall_stiffness,
                    geo.depth};
        }
        const fsai::mesh::AreaFunction tract1d
            = fsai::mesh::resample(tract, true, 5e-4);
        std::vector<double> tract_formants, tract_bandwidths;
        for (const auto& r :
             ac::tube_resonances(tract1d, 5000.0, wave.c0, wave.rho0,
                                 ac::LipEnd::flanged, -1.0, wall1d))
        {
          if (tract_formants.size() < 4)
          {
            tract_formants.push_back(r.f);
            tract_bandwidths.push_back(r.bandwidth);
          }
        }
        // The same 1D model of the acoustic domain as built: its glottis
        // stays open at the rest gap and leads to the subglottal duct and
        // its end, which raises F1 above the closed-glottis value
        ac::GlottalBranch branch{fsai::mesh::voice_subglottal(profile),
                                 vp.subglottal == "absorbing"};
        std::vector<double> domain_formants;
        for (const auto& r :
             ac::tube_resonances(tract1d, 5000.0, wave.c0, wave.rho0,
                                 ac::LipEnd::flanged, -1.0, wall1d, branch))
        {
          if (domain_formants.size() < 4)
            domain_formants.push_back(r.f);
        }
        fsai::log::info("tract: {} ({:.2f} cm, {} walls); transfer-function "
                        "formants (1D, flanged lips) {::.0f} Hz, bandwidths "
                        "{::.0f} Hz; with the acoustic domain's open rest "
                        "glottis and {} subglottal end: {::.0f} Hz",
                        tract.source, 100 * tract.length(),
                        vp.yielding_walls ? "yielding" : "rigid",
                        tract_formants, tract_bandwidths, vp.subglottal,
                        domain_formants);

        // 3. Flow (the glottis scene) and sound on their own meshes
        auto fem = std::make_unique<fsai::glottis::FlowGlottis>(
            rt.comm(), profile, vf, setup.contact, fe, setup.fluid, setup.ale,
            setup.coupling, vp.output + "/coupling.csv",
            vp.run.restart.empty() ? std::string::npos : std::size_t(k0));
        fsai::mesh::MeshData am = [&]
        {
          fsai::common::ScopedTimer t("demo: acoustic mesh");
          return fsai::mesh::voice_domain(rt.comm(), profile, tract, vg);
        }();
        auto facets = [&](const char* name)
        { return am.facet_tags->find(am.facet_tag(name)); };
        ac::WaveBoundaries wb;
        // Subglottal end: absorbing by default (an anechoic trachea). A
        // sound-hard end closes a 20 mm cavity that the rest glottis (the
        // acoustic domain is fixed, the gap stays open) joins to the tract
        // as a Helmholtz resonator (measured: a 770 Hz peak that dominated
        // the sound, and F1 lowered by the cavity's compliance)
        if (vp.subglottal == "absorbing")
          wb.absorbing = facets("inlet");
        if (vp.yielding_walls)
        {
          // The tract's walls from the fold's superior attachment to the
          // lips, as in the 1D model (not the subglottal duct, the baffle
          // or the step where the channel meets the vowel's tract)
          const double x0 = geo.fold_length,
                       x_step = geo.fold_length + geo.outlet_length,
                       x_end = geo.fold_length + tract.length();
          wb.yielding
              = am.facets_where("wall",
                                [&](const double* x)
                                {
                                  return x[0] > x0 and x[0] < x_end - 1e-9
                                         and std::abs(x[0] - x_step) > 1e-9;
                                });
        }
        // The acoustic domain is fixed with the glottis at rest; in its
        // cells under the fold surface (the glottal slit and the gap beside
        // the fold) the air moves as in the flow's current slit (slit law,
        // forms/acoustics.py): a slit g/g0 as wide as the mesh's has the
        // inertia ρ0 g0/g and the resistance (g0/g) r per unit length, r =
        // 3μ/g² (Poiseuille) + the jet's kinetic loss ρ0 u_jet (Flanagan's
        // ρ0 U/A², spread over the fold's length in proportion to g), with g
        // ≥ g_min as in the flow. So the slit closes acoustically when the
        // fold closes (a g_min slit's resistance is ~500 times the tract's
        // ρ0 c0/A) and is resistive when open, as the jet makes it. Without
        // it the rest slit is an open inertance into the anechoic trachea
        // whatever the fold does, and the domain's F1 is that of a tract
        // open at the glottis.
        std::vector<std::int32_t> section_cells;
        std::vector<double> section_x;  // cell midpoints' x
        std::vector<double> section_g0; // rest height of the fold there
        const auto rest = fsai::glottis::moved_surface(
            profile, fsai::glottis::RigidMotion(0, 0, {0, 0}));
        const double g_min = setup.fe.g_min, mu = setup.fluid.mu,
                     rho = setup.fluid.rho;
        if (vp.glottal_slit)
        {
          const int tdim = am.mesh->topology().dim();
          const std::int32_t nc
              = am.mesh->topology().index_map(tdim)->size_local();
          const auto x = am.mesh->geometry().x();
          const auto& xdofs = am.mesh->geometry().dofmap();
          for (std::int32_t c = 0; c < nc; ++c)
          {
            std::array<double, 2> m{0, 0};
            for (auto v : xdofs.links(c))
              for (int k = 0; k < 2; ++k)
                m[k] += x[3 * v + k] / double(xdofs.links(c).size());
            if (m[0] <= 0 or m[0] >= geo.fold_length)
              continue;
            const double g0 = surface_height(rest, m[0]);
            if (m[1] < g0)
            {
              section_cells.push_back(c);
              section_x.push_back(m[0]);
              section_g0.push_back(g0);
            }
          }
          wb.section_cells = section_cells;
          wb.section_source = vp.slit_lighthill;
        }
        // The fold surface displaces air only while the slit beside it is
        // open: its acceleration enters fully above 2 g_min, not at all
        // below g_min (the flow's boundary stops there too)
        auto open_fraction
            = [&](double x, const std::vector<std::array<double, 2>>& now)
        {
          if (!vp.glottal_slit or x <= 0 or x >= geo.fold_length)
            return 1.0;
          return std::clamp((surface_height(now, x) - g_min) / g_min, 0.0, 1.0);
        };
        wb.radiation = facets("radiation");
        wb.radiation_beta = 0.5 / (vg.radius + vg.layer); // planar: 1/(2R)
        wb.vibrating = facets("fold");
        std::shared_ptr<dolfinx::fem::Function<double>> sigma;
        const double x_lips = geo.fold_length + tract.length();
        if (vp.radiation == "pml")
        {
          sigma = ac::absorbing_layer(
              am.mesh, am.cell_tags->find(am.cell_tag("layer")),
              {x_lips, 0.0, 0.0}, vg.radius, vg.layer, wave.c0, 1e-3);
        }
        ac::WaveSolver sound(am.mesh, 1, false, wave, wb, vp.dt, sigma, true);
        // The valve's monopole pair (--voice.monopole): the glottal flow
        // leaves the subglottal channel and enters the supraglottal one.
        // Incompressible flow carries Q(t) through its whole domain at once,
        // so Lighthill's ρ0 v v (E15) holds no volume source; these two
        // cos² bumps next to the fold (each 2 × monopole_length long, over
        // the channel's width) put +Q and −Q back (E14's right-hand side
        // ρ0 ∂q/∂t, per unit depth of the half model: Q/(2 L_g)).
        std::array<std::size_t, 2> monopole{};
        if (vp.monopole)
        {
          const double l = vp.monopole_length;
          fsai::require(2 * l <= geo.inlet_length
                            and 2 * l <= geo.outlet_length,
                        "--voice.monopole_length",
                        "<= half the sub- and supraglottal channel lengths", l);
          auto bump = [l](double x, double centre)
          {
            const double u = (x - centre) / l;
            return std::abs(u) < 1 ? std::pow(std::cos(0.5 * M_PI * u), 2)
                                   : 0.0;
          };
          monopole[0] = sound.add_volume_source(
              [&](double x, double) { return bump(x, geo.fold_length + l); });
          monopole[1] = sound.add_volume_source([&](double x, double)
                                                { return bump(x, -l); });
        }
        fsai::log::info("FE flow: {} cells, {} dofs; acoustics: {} cells, {} "
                        "dofs",
                        fem->channel().cells(), fem->channel().flow().dofs(),
                        am.mesh->topology().index_map(2)->size_global(),
                        sound.dofs());
        summary.set("flow_dofs", fem->channel().flow().dofs());
        summary.set("acoustic_dofs", sound.dofs());
        summary.set("tract_length_m", tract.length());
        summary.set("vowel", label);
        summary.set("tract_formants_hz", tract_formants);
        summary.set("tract_bandwidths_hz", tract_bandwidths);
        summary.set("domain_formants_hz", domain_formants);

        // Source transfer and taper
        ac::FlowSource source(rt.comm(),
                              *fem->channel().flow().velocity_space(),
                              fem->channel().reference_coordinates(),
                              *sound.flow_velocity().function_space());
        {
          auto& chi = sound.taper();
          const auto X = chi.function_space()->tabulate_dof_coordinates(false);
          auto c = chi.x()->mutable_array();
          const double x_in = -geo.inlet_length,
                       x_out = geo.fold_length + geo.outlet_length;
          for (std::size_t i = 0; i < c.size(); ++i)
          {
            c[i] = source_taper(X[3 * i], x_in, x_out, vp);
          }
        }
        const auto Va = sound.wall_acceleration().function_space();
        const auto fold_dofs
            = dolfinx::fem::locate_dofs_topological(*Va, 1, facets("fold"));
        std::vector<std::array<double, 2>> fold_X;
        {
          const auto X = Va->tabulate_dof_coordinates(false);
          for (auto d : fold_dofs)
            fold_X.push_back({X[3 * d], X[3 * d + 1]});
        }
        fsai::io::PointProbes probes(
            am.mesh,
            {{x_lips, 0.0, 0.0}, {x_lips + vp.mic_distance, 0.0, 0.0}});

        std::unique_ptr<fsai::io::TimeSeriesWriter> flow_xdmf, sound_xdmf;
        if (vp.write_every > 0)
        {
          flow_xdmf = std::make_unique<fsai::io::TimeSeriesWriter>(
              vp.output + "/flow.xdmf", fem->channel().fields(), t_restart);
          sound_xdmf = std::make_unique<fsai::io::TimeSeriesWriter>(
              vp.output + "/acoustic.xdmf",
              std::vector<fsai::io::TimeSeriesWriter::Field>{sound.pressure()},
              t_restart);
        }

        // 4. Time loop: flow step (coupled), then one acoustic step
        const std::vector<std::string> columns
            = {"t_s",       "gap_m",    "Q_m3s",
               "h_m",       "phi_rad",  "contact_force_N",
               "p_lips_pa", "p_mic_pa", "iterations"};
        const long n = std::lround(vp.duration / vp.dt);
        std::vector<double> t, g, Q, p_mic;
        long its = 0;
        int unconverged = 0;
        auto v_new = std::make_shared<dolfinx::fem::Function<double>>(
            sound.flow_velocity().function_space());
        auto v_old = std::make_shared<dolfinx::fem::Function<double>>(
            sound.flow_velocity().function_space());
        const auto v_keys = fsai::io::node_keys(*v_old->function_space());
        const int v_bs = v_old->function_space()->dofmap()->index_map_bs();
        // Restart: the flow, the sound, the source's last velocity and the
        // series up to the checkpoint (later rows dropped)
        std::unique_ptr<fsai::io::CsvWriter> csv;
        if (!vp.run.restart.empty())
        {
          fem->load(ckpt.fields());
          sound.load(ckpt.fields(), "sound.");
          fsai::io::get_blocks(ckpt.fields(), "voice.v_old",
                               v_old->x()->mutable_array(), v_bs, v_keys);
          unconverged = ckpt.meta().value("coupling_unconverged_steps", 0);
          csv = std::make_unique<fsai::io::CsvWriter>(
              rt.comm(), vp.output + "/series.csv", columns, std::size_t(k0));
          for (const auto& r : csv->kept_rows())
          {
            t.push_back(r[0]);
            g.push_back(r[1]);
            Q.push_back(r[2]);
            p_mic.push_back(r[7]);
            its += long(r[8]);
          }
          fsai::log::info("restart from step {} (t = {:.6g} s) of {}", k0,
                          t_restart, vp.output);
          summary.set("restarted_from_step", k0);
        }
        else
        {
          csv = std::make_unique<fsai::io::CsvWriter>(
              rt.comm(), vp.output + "/series.csv", columns);
        }
        fsai::io::Progress progress("step", double(n), 5.0, double(k0));
        std::array<double, 2> qdot_prev = fem->fold().qdot();
        double q_monopole = Q.empty() ? 0.0 : Q.back(); // last converged Q
        std::vector<double> slit_inertia(section_cells.size(), 1.0),
            slit_resistance(section_cells.size(), 0.0);
        const auto loop0 = std::chrono::steady_clock::now();
        for (long k = k0 + 1; k <= n; ++k)
        {
          fsai::glottis::Sample s;
          try
          {
            s = fem->step();
          }
          catch (const std::exception& e)
          {
            // A failed flow step (coupling, inverted cell, solver): the
            // last good flow state is written for inspection
            fem->write_last_good(vp.output + "/last_good.xdmf");
            throw std::runtime_error(fmt::format(
                "{} [step {} failed; the last good flow state (step {}, t = "
                "{:.6g} s) is in {}/last_good.xdmf{}]",
                e.what(), k, k - 1, fem->time(), vp.output,
                ckpt.last_checkpoint_note()));
          }
          {
            fsai::common::ScopedTimer timer("demo: sound step");
            if (vp.lighthill)
            {
              // The source at the step's midpoint, v = (v_n + v_{n+1})/2
              // (the trapezoidal rule's own load): the flow's step-to-step
              // (−1)^n content, which the undamped Newmark scheme would
              // store in unresolved high-frequency modes, is removed
              source.transfer(*fem->channel().flow().velocity(), *v_new);
              auto vs = sound.flow_velocity().x()->mutable_array();
              const auto vn = v_new->x()->array();
              auto vo = v_old->x()->mutable_array();
              for (std::size_t i = 0; i < vs.size(); ++i)
              {
                vs[i] = vp.source_average ? 0.5 * (vn[i] + vo[i]) : vn[i];
                vo[i] = vn[i];
              }
            }
            // Fold surface acceleration: tapered rigid motion (as the flow
            // boundary), a = w (∂u/∂h q̈_h + ∂u/∂φ q̈_φ) with the step's mean
            // acceleration q̈ = (q̇_{n+1} − q̇_n)/Δt = (q̈_n + q̈_{n+1})/2.
            // Newmark's end-of-step q̈ carries an undamped (−1)^n part
            // whenever the load jumps (contact, porous switching); the mean
            // is free of it (the trapezoidal rule's own acceleration)
            const auto& fold = fem->fold();
            const auto m = fold.motion();
            const std::array<double, 2> qdd
                = {(fold.qdot()[0] - qdot_prev[0]) / vp.dt,
                   (fold.qdot()[1] - qdot_prev[1]) / vp.dt};
            qdot_prev = fold.qdot();
            // The slit law of the fold's current position and the flow's
            // jet (u_jet = Q / (2 g L_g) at the narrowest gap)
            std::vector<std::array<double, 2>> now;
            if (vp.glottal_slit)
            {
              now = fsai::glottis::moved_surface(profile, m);
              const double g_n = std::max(s.gap, g_min);
              const double u_jet = std::abs(s.Q) / (2 * g_n * geo.depth);
              for (std::size_t i = 0; i < section_x.size(); ++i)
              {
                const double x = section_x[i];
                const double g = std::max(surface_height(now, x), g_min);
                const double r = 3 * mu / (g * g)
                                 + rho * u_jet * g / (g_n * geo.fold_length);
                const double scale = section_g0[i] / g;
                slit_inertia[i] = scale;
                slit_resistance[i] = scale * r;
              }
              sound.set_slit_law(slit_inertia, slit_resistance);
            }
            if (vp.monopole)
            {
              // dQ/dt over the step (the midpoint rate, as the wall's q̈).
              // A step whose coupling did not converge has a meaningless Q
              // (measured: +0.7 l/s for one step while the glottis closes),
              // and its dQ/dt, an impulse, would ring the tract's lightly
              // damped upper resonances for the rest of the run: Q is held
              // over it (the warning is logged by the coupling)
              const double dQ
                  = s.converged ? (s.Q - q_monopole) / vp.dt / (2 * geo.depth)
                                : 0.0;
              if (s.converged)
                q_monopole = s.Q;
              sound.set_volume_source_rate(monopole[0], dQ);
              sound.set_volume_source_rate(monopole[1], -dQ);
            }
            auto a = sound.wall_acceleration().x()->mutable_array();
            for (std::size_t i = 0; vp.wall and i < fold_dofs.size(); ++i)
            {
              const auto d = m.derivatives(fold_X[i]);
              const double w = profile.weight(fold_X[i])
                               * open_fraction(fold_X[i][0], now);
              for (int c = 0; c < 2; ++c)
                a[2 * fold_dofs[i] + c]
                    = w * (d[0][c] * qdd[0] + d[1][c] * qdd[1]);
            }
            sound.step();
          }
          const auto p = probes.values(*sound.pressure());
          if (!std::isfinite(p[0]) or !std::isfinite(p[1]))
          {
            throw std::runtime_error(fmt::format(
                "acoustic pressure is not finite at t = {:.6f} s (step {})",
                s.t, k));
          }
          csv->row({s.t, s.gap, s.Q, s.h, s.phi, s.contact_force, p[0], p[1],
                    double(s.iterations)});
          t.push_back(s.t);
          g.push_back(s.gap);
          Q.push_back(s.Q);
          p_mic.push_back(p[1]);
          its += s.iterations;
          unconverged += !s.converged;
          if (flow_xdmf and k % vp.write_every == 0)
          {
            flow_xdmf->write(s.t);
            sound_xdmf->write(s.t);
          }
          if (vp.run.checkpoint_due(k))
          {
            auto fields = fem->save();
            sound.save(fields, "sound.");
            fsai::io::put_blocks(
                fields, "voice.v_old", v_old->x()->array(), v_bs, v_keys,
                v_old->function_space()->dofmap()->index_map->size_local());
            ckpt.write(k, s.t, {{"coupling_unconverged_steps", unconverged}},
                       &fields);
          }
          vp.run.kill_if_requested(k);
          progress.update(double(k),
                          fmt::format("t = {:.5f} g = {:+.3e} Q = {:.3e} "
                                      "p_mic = {:+.3e}",
                                      s.t, s.gap, Q.back(), p[1]));
        }
        const double loop_wall = std::chrono::duration<double>(
                                     std::chrono::steady_clock::now() - loop0)
                                     .count();

        // 5. The fold's cycle and the sound's analysis (limit-cycle window)
        const double t0 = vp.stats_from * vp.duration;
        const auto cs = fsai::glottis::cycle_stats(t, g, Q, t0, 0.0);
        std::vector<double> mic;
        for (std::size_t i = 0; i < t.size(); ++i)
          if (t[i] >= t0)
            mic.push_back(p_mic[i]);
        // f0 search down to 60 Hz, or to two periods in a short window
        const double f0 = ac::fundamental_frequency(
            mic, vp.dt, std::max(60.0, 2.6 / (vp.dt * double(mic.size()))));
        if (!std::isfinite(f0))
        {
          fsai::log::warn(
              "the sound's f0 could not be estimated (window {:.4f} "
              "s: too short or silent)",
              vp.dt * double(mic.size()));
        }
        // Formants of the voice: LPC of its periodic part (pitch-synchronous
        // average over the window's whole periods at the sound's own f0,
        // repeated over the window's length). Transients — an impact, the
        // start-up — leave the lightly damped upper resonances ringing at
        // their own frequencies for longer than the run; LPC of the raw
        // window puts poles on those lines (kept as
        // formants_lpc_window_hz for comparison)
        double periodic_fraction = NAN;
        const std::vector<double> cycle
            = ac::periodic_part(mic, vp.dt, f0, &periodic_fraction);
        const std::vector<double> formants_window
            = ac::lpc_formants(mic, vp.dt);
        std::vector<double> formants = formants_window;
        if (!cycle.empty())
        {
          std::vector<double> voiced;
          while (voiced.size() + cycle.size()
                 <= std::max(mic.size(), 2 * cycle.size()))
            voiced.insert(voiced.end(), cycle.begin(), cycle.end());
          formants = ac::lpc_formants(voiced, vp.dt);
        }
        const double spl = ac::spl_db(mic);
        auto errors = [&](const std::vector<double>& ref)
        {
          std::vector<double> e;
          for (std::size_t k = 0;
               k < 2 and k < formants.size() and k < ref.size(); ++k)
            e.push_back(100.0 * (formants[k] - ref[k]) / ref[k]);
          return e;
        };
        const std::vector<double> formant_err = errors(tract_formants);
        const std::vector<double> domain_err = errors(domain_formants);
        fsai::log::info(
            "fold: {} cycles, f0 {:.2f} Hz, open quotient {:.3f}, peak flow "
            "{:.3e} m³/s, closes every cycle: {}; sound at the microphone: "
            "f0 {:.2f} Hz ({:+.2f} %), SPL {:.1f} dB, periodic part {:.1f} % "
            "of the energy, its LPC formants {::.0f} Hz (whole window: "
            "{::.0f} Hz) vs tract {::.0f} Hz (closed glottis), {::.0f} Hz "
            "(as modelled)",
            cs.cycles, cs.f0_hz, cs.open_quotient, cs.q_peak,
            cs.closes_every_cycle ? "yes" : "no", f0,
            100 * (f0 - cs.f0_hz) / cs.f0_hz, spl, 100 * periodic_fraction,
            formants, formants_window, tract_formants, domain_formants);

        // Spectrum of the sound (Hann window) for the chart
        {
          std::vector<double> w(mic.size());
          for (std::size_t i = 0; i < mic.size(); ++i)
          {
            w[i] = mic[i]
                   * (0.5 - 0.5 * std::cos(2 * M_PI * i / double(mic.size())));
          }
          const auto [f, A] = ac::amplitude_spectrum(w, vp.dt, 4);
          fsai::io::CsvWriter sc(rt.comm(), vp.output + "/spectrum.csv",
                                 {"f_hz", "level_db"});
          for (std::size_t i = 1; i < f.size() and f[i] <= 5000.0; ++i)
            sc.row({f[i], 20 * std::log10(std::max(A[i], 1e-30) / 20e-6)});
        }
        const std::string wav = vp.output + "/sound.wav";
        if (rt.rank() == 0)
          ac::write_wav(wav, ac::resample(p_mic, vp.dt, vp.wav_rate),
                        vp.wav_rate);

        summary.set("f0_hz", f0);
        summary.set("f0_fold_hz", cs.f0_hz);
        summary.set("formants_from_sound_hz", formants);
        summary.set("formants_lpc_window_hz", formants_window);
        summary.set("periodic_fraction", periodic_fraction);
        summary.set("formant_errors_percent", formant_err);
        summary.set("domain_formant_errors_percent", domain_err);
        summary.set("spl_db", spl);
        summary.set("sim_time_s", vp.duration);
        summary.set("wav", wav);
        summary.set("open_quotient", cs.open_quotient);
        summary.set("q_peak_m3s", cs.q_peak);
        summary.set("cycles", cs.cycles);
        summary.set("closes_every_cycle", cs.closes_every_cycle);
        summary.set("steps", n);
        summary.set("coupling_iterations_mean", double(its) / double(n));
        summary.set("coupling_unconverged_steps", unconverged);
        summary.set("loop_wall_s", loop_wall);
        summary.set("wall_per_sim_s", loop_wall / vp.duration);
        summary.write(vp.output + "/summary.json");
        fsai::log::info("time loop {:.1f} s ({:.3g} s per simulated s); "
                        "total {:.1f} s; wrote {}",
                        loop_wall, loop_wall / vp.duration,
                        std::chrono::duration<double>(
                            std::chrono::steady_clock::now() - wall0)
                            .count(),
                        wav);

        if (vp.check_result)
        {
          auto fail = [](const std::string& what)
          { throw std::runtime_error("check failed: " + what); };
          if (!(std::isfinite(spl) and spl > 40.0))
            fail(fmt::format("sound level {} dB (want finite, > 40 dB)", spl));
          if (!(cs.f0_hz >= 85.0 and cs.f0_hz <= 155.0))
            fail(fmt::format("fold f0 {} Hz outside 85-155 Hz", cs.f0_hz));
          if (vp.check_f0_tolerance > 0
              and !(std::abs(f0 - cs.f0_hz)
                    <= vp.check_f0_tolerance * cs.f0_hz))
          {
            fail(fmt::format("sound f0 {} Hz vs fold f0 {} Hz (tolerance {} "
                             "%)",
                             f0, cs.f0_hz, 100 * vp.check_f0_tolerance));
          }
        }

        // 6. Chart (optional: a missing matplotlib only warns)
        if (rt.rank() == 0)
        {
          const std::string cmd = std::string(FSAI_PYTHON) + " "
                                  + FSAI_SCRIPTS_DIR + "/plot_voice.py "
                                  + vp.output + " > /dev/null 2>&1";
          if (std::system(cmd.c_str()) != 0)
            fsai::log::warn("could not draw voice.png ({})", cmd);
        }
      });
}
