// Copyright (C) 2026 fsai developers
//
// fsai_formants: resonances (formants) of a vocal tract by the
// transfer-function method (shared/DESIGN.md §2 "Acoustics"). A broadband
// volume-velocity pulse enters at the glottis; the pressure at the lips and
// at a microphone gives H(f) = P(f)/U(f); formants are the peaks of |H|,
// bandwidths their -3 dB widths. Models: "planar" (2D channel of width
// A(x)/L_g), "axisym" (tube of radius sqrt(A/π)), "1d" (chain matrices,
// no FE). Each FE run also prints the 1D model of the same area function
// and lip condition as an independent check.
//
// Sample runs:
//   ./fsai_formants --vowel u
//   ./fsai_formants --vowel a --model axisym --radiation pml
//   ./fsai_formants --area-function my_tract.csv --radiation pressure-release
//   mpirun -n 2 ./fsai_formants --vowel i --h 0.003
//
// Outputs in --output (default results/fsai_formants): transfer_function.csv,
// time_series.csv, pressure.xdmf (p' snapshots), transfer_function.png,
// summary.json (vowel, model, formants_hz, bandwidths_hz, ...).

#include <acoustics/pulse_response.h>
#include <acoustics/spectrum.h>
#include <acoustics/tube_model.h>
#include <common/Parameters.h>
#include <common/Runtime.h>
#include <common/errors.h>
#include <common/log.h>
#include <common/timer.h>
#include <io/CsvWriter.h>
#include <io/Progress.h>
#include <io/RunSummary.h>
#include <io/TimeSeriesWriter.h>
#include <io/output_dir.h>
#include <mesh/area_function.h>
#include <mesh/vocal_tract.h>

#include <chrono>
#include <cmath>
#include <fmt/ranges.h>

namespace
{
/// Parameters of this demo (program-level keys)
struct FormantParameters
{
  std::string output = "results/fsai_formants";
  std::string vowel = "u";
  std::string area_function; // overrides vowel
  std::string model = "planar";
  std::string radiation = "sommerfeld";
  double h = 0.0; // mesh size [m]; 0: from elements_per_wavelength
  double elements_per_wavelength = 10.0;
  double layer = 0.02;        // absorbing-layer thickness for pml [m]
  bool curvature = true;      // Bayliss-Turkel curvature term in Sommerfeld
  double mic_distance = 0.03; // microphone on the axis, beyond the lips [m]
  int formants = 4;
  int snapshots = 100; // p' snapshots in pressure.xdmf (0: none)
  bool check_result = false;
  bool yielding_walls = false;

  void bind(fsai::common::Parameters& p)
  {
    p.add("output", output, "output folder");
    p.add("yielding_walls", yielding_walls,
          "tract walls yield (mass-resistance-spring per unit area, "
          "--acoustics.wall_*), in the FE and the 1D model alike");
    p.add_choice("vowel", vowel, {"u", "a", "i"},
                 "vowel of the shipped area functions (meshes/vowel_*.csv)");
    p.add("area-function", area_function,
          "area-function CSV (x_cm,area_cm2); overrides --vowel");
    p.add_choice("model", model, {"planar", "axisym", "1d"},
                 "planar 2D channel, axisymmetric tube, or 1D chain matrices");
    p.add_choice("radiation", radiation,
                 {"sommerfeld", "pml", "pressure-release"},
                 "lip end: radiation region closed by Sommerfeld or an "
                 "absorbing layer, or p' = 0 at the lips");
    p.add("h", h, "mesh size [m] (0: c0 / (f_max * elements_per_wavelength))");
    p.add("elements_per_wavelength", elements_per_wavelength,
          "elements per wavelength at f_max when --h is 0");
    p.add("layer", layer, "absorbing-layer thickness for --radiation pml [m]");
    p.add("curvature", curvature,
          "curvature term p/R (3D, axisym) or p/2R (planar) in the "
          "radiation condition (false: plain first-order Sommerfeld)");
    p.add("mic_distance", mic_distance,
          "microphone distance from the lips on the axis [m]");
    p.add("formants", formants, "number of formants reported");
    p.add("snapshots", snapshots, "p' snapshots written to pressure.xdmf");
    p.add("check-result", check_result,
          "fail unless FE F1-F3 are within 3% of the 1D model (and B1 within "
          "20% with --yielding_walls)");
  }

  void validate() const
  {
    fsai::require_positive("--elements_per_wavelength",
                           elements_per_wavelength);
    fsai::require(h >= 0, "--h", ">= 0", h);
    fsai::require_positive("--mic_distance", mic_distance);
    fsai::require(formants >= 1 and formants <= 10, "--formants", "in [1, 10]",
                  formants);
    fsai::require(snapshots >= 0, "--snapshots", ">= 0", snapshots);
  }
};

std::vector<double> first(const std::vector<double>& v, std::size_t n)
{
  return {v.begin(), v.begin() + std::min(n, v.size())};
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

        // 1. Parameters: defaults < --config file < command line
        FormantParameters fp;
        fsai::acoustics::WaveParameters wave;
        fsai::acoustics::PulseParameters pulse;
        fsai::mesh::VocalTractGeometry geo;
        fsai::common::Parameters params(rt.program(),
                                        "Vocal-tract formants by the "
                                        "transfer-function method");
        fp.bind(params);
        wave.bind(params);
        pulse.bind(params);
        geo.bind(params);
        params.parse(rt.app_args());
        fp.validate();
        wave.validate();
        pulse.validate();
        params.print();
        fsai::io::prepare_output_dir(rt.comm(), fp.output);

        // 2. Area function and the 1D reference (always: it is cheap)
        const std::string af_path = fp.area_function.empty()
                                        ? fsai::mesh::vowel_file(fp.vowel)
                                        : fp.area_function;
        const fsai::mesh::AreaFunction af
            = fsai::mesh::read_area_function(af_path);
        // The 1D model of the same wall (smooth or stepped) as the FE mesh
        const fsai::mesh::AreaFunction af1d
            = fsai::mesh::resample(af, geo.smooth, 5e-4);
        const std::string label = fp.area_function.empty() ? fp.vowel : af_path;
        const ac::LipEnd lip = fp.radiation == "pressure-release"
                                   ? ac::LipEnd::pressure_release
                               : geo.baffle ? ac::LipEnd::flanged
                                            : ac::LipEnd::unflanged;
        // Observation point of H: the lips, or 5 mm inside them for p = 0
        const double x_obs = ac::default_observation_point(af, lip);
        // Yielding walls: the 1D model's wall perimeter is that of the FE
        // model (planar: its two walls of depth L_g; axisymmetric: 2πr)
        ac::TubeWall wall1d;
        if (fp.yielding_walls)
        {
          wall1d = {wave.wall_mass, wave.wall_resistance, wave.wall_stiffness,
                    fp.model == "axisym" ? 0.0 : geo.depth};
        }
        std::vector<ac::Resonance> ref = ac::tube_resonances(
            af1d, pulse.f_max, wave.c0, wave.rho0, lip, x_obs, wall1d);
        std::vector<double> f1d, b1d;
        for (auto r : ref)
          f1d.push_back(r.f), b1d.push_back(r.bandwidth);
        fsai::log::info("Area function {}: {} sections, L = {:.2f} cm", af_path,
                        af.size(), 100 * af.length());
        fsai::log::info("1D model ({} lip end): F = {::.0f} Hz",
                        fp.radiation == "pressure-release" ? "p = 0"
                        : geo.baffle                       ? "flanged"
                                                           : "unflanged",
                        first(f1d, fp.formants));

        fsai::io::RunSummary summary(rt.comm(), rt.program());
        summary.set_parameters(params.to_json());
        summary.set("vowel", label);
        summary.set("model", fp.model);
        summary.set("radiation", fp.radiation);
        summary.set("tract_length_m", af.length());
        summary.set("formants_1d_hz", first(f1d, fp.formants));
        summary.set("bandwidths_1d_hz", first(b1d, fp.formants));

        std::vector<double> formants, bandwidths;
        if (fp.model == "1d")
        {
          formants = first(f1d, fp.formants);
          bandwidths = first(b1d, fp.formants);
          fsai::io::CsvWriter csv(rt.comm(),
                                  fp.output + "/transfer_function.csv",
                                  {"f_hz", "h_db", "h_1d_db"});
          for (double f = 5.0; f <= pulse.f_max; f += 5.0)
          {
            auto r = ac::tube_response(af1d, f, wave.c0, wave.rho0, lip, x_obs,
                                       wall1d);
            const double h = 20 * std::log10(std::abs(r.h_obs));
            csv.row({f, h, h});
          }
        }
        else
        {
          // 3. Mesh: h from the shortest wavelength unless given
          geo.model = fp.model;
          geo.open = fp.radiation != "pressure-release";
          geo.layer = fp.radiation == "pml" ? fp.layer : 0.0;
          geo.h = fp.h > 0
                      ? fp.h
                      : wave.c0 / (pulse.f_max * fp.elements_per_wavelength);
          fsai::mesh::MeshData m = [&]
          {
            fsai::common::ScopedTimer t("formants: mesh");
            return fsai::mesh::vocal_tract(rt.comm(), af, geo);
          }();

          ac::TractBoundaryModel bm;
          bm.axisymmetric = fp.model == "axisym";
          bm.area_factor
              = bm.axisymmetric ? 2 * M_PI : geo.depth * (geo.half ? 2.0 : 1.0);
          bm.radiation = fp.radiation;
          bm.radiation_radius = geo.radius;
          bm.centre = {af.length(), 0.0, 0.0};
          bm.spherical = bm.axisymmetric;
          bm.layer = geo.layer;
          bm.curvature = fp.curvature;
          if (fp.yielding_walls)
          {
            // The tract's own walls: inside the tract (not its outer face
            // or the baffle in the radiation region)
            const double L = af.length();
            bm.yielding = m.facets_where(
                "wall",
                [&](const double* x)
                {
                  return x[0] < L - 1e-9
                         and std::abs(x[1])
                                 <= fsai::mesh::tract_half_width(
                                        geo, af.area_at(x[0], geo.smooth))
                                        + 0.5 * geo.wall;
                });
          }
          if (geo.open)
          {
            fsai::require(fp.mic_distance < geo.radius, "--mic_distance",
                          "inside the radiation region (< --tract.radius)",
                          fp.mic_distance);
          }
          const double L = af.length();
          std::vector<std::array<double, 3>> probes
              = {{0.0, 0.0, 0.0}, {x_obs, 0.0, 0.0}};
          if (geo.open)
            probes.push_back({L + fp.mic_distance, 0.0, 0.0});

          // 4. Pulse run with progress and p' snapshots
          const int steps = int(std::ceil(pulse.duration / pulse.dt()));
          const int every
              = fp.snapshots > 0 ? std::max(1, steps / fp.snapshots) : 0;
          std::unique_ptr<fsai::io::TimeSeriesWriter> xdmf;
          fsai::io::Progress progress("step", steps, 5.0);
          fsai::log::info("Pulse run: dt = {:.3e} s, {} steps, h = {:.2e} m",
                          pulse.dt(), steps, geo.h);
          ac::PulseResult r = ac::pulse_response(
              m, wave, pulse, bm, probes,
              [&](int k, const ac::WaveSolver& s)
              {
                if (every > 0 and k % every == 0)
                {
                  fsai::common::ScopedTimer t("formants: xdmf output");
                  if (!xdmf)
                  {
                    xdmf = std::make_unique<fsai::io::TimeSeriesWriter>(
                        fp.output + "/pressure.xdmf",
                        std::vector<fsai::io::TimeSeriesWriter::Field>{
                            s.pressure()});
                  }
                  xdmf->write(s.time());
                }
                progress.update(k, fmt::format("E = {:.3e} J", s.energy()));
              });

          // 5. Transfer functions and formants
          const std::size_t out = 1; // x_obs
          ac::TransferFunction H
              = ac::transfer_function(r.U, r.p[out], r.dt, pulse.decay());
          ac::TransferFunction Hmic;
          if (geo.open)
            Hmic = ac::transfer_function(r.U, r.p[2], r.dt, pulse.decay());
          std::vector<double> mag;
          for (auto h : H.h)
            mag.push_back(std::abs(h));
          for (const ac::Peak& p : ac::find_peaks(H.f, mag, 50.0, pulse.f_max))
          {
            if (int(formants.size()) == fp.formants)
              break;
            formants.push_back(p.f);
            bandwidths.push_back(p.bandwidth - H.window_bandwidth);
          }
          {
            fsai::io::CsvWriter csv(rt.comm(),
                                    fp.output + "/transfer_function.csv",
                                    {"f_hz", "h_db", "h_mic_db", "h_1d_db"});
            for (std::size_t k = 1; k < H.f.size() and H.f[k] <= pulse.f_max;
                 ++k)
            {
              auto t1 = ac::tube_response(af1d, H.f[k], wave.c0, wave.rho0, lip,
                                          x_obs, wall1d);
              csv.row({H.f[k], 20 * std::log10(std::abs(H.h[k])),
                       geo.open ? 20 * std::log10(std::abs(Hmic.h[k])) : NAN,
                       20 * std::log10(std::abs(t1.h_obs))});
            }
          }
          {
            std::vector<std::string> cols
                = {"t_s", "U_m3s", "p_glottis_pa", "p_obs_pa"};
            if (geo.open)
              cols.push_back("p_mic_pa");
            cols.push_back("energy_j");
            fsai::io::CsvWriter csv(rt.comm(), fp.output + "/time_series.csv",
                                    cols);
            for (std::size_t k = 0; k < r.t.size(); ++k)
            {
              std::vector<double> row = {r.t[k], r.U[k]};
              for (auto& p : r.p)
                row.push_back(p[k]);
              row.push_back(r.energy[k]);
              csv.row(row);
            }
          }
          summary.set("dofs", r.dofs);
          summary.set("steps", r.steps);
          summary.set("dt_s", r.dt);
          summary.set("h_m", geo.h);
          summary.set("window_bandwidth_hz", H.window_bandwidth);
          summary.set("observation_x_m", x_obs);
        }

        // 6. Report
        summary.set("formants_hz", formants);
        summary.set("bandwidths_hz", bandwidths);
        std::vector<double> dev;
        for (std::size_t k = 0; k < formants.size() and k < f1d.size(); ++k)
          dev.push_back(100.0 * (formants[k] - f1d[k]) / f1d[k]);
        summary.set("deviation_from_1d_percent", dev);
        const double wall = std::chrono::duration<double>(
                                std::chrono::steady_clock::now() - wall0)
                                .count();
        summary.write(fp.output + "/summary.json");
        fsai::log::info("{:>4} {:>10} {:>10} {:>10} {:>8}", "", "F [Hz]",
                        "B [Hz]", "1D F [Hz]", "dev [%]");
        for (std::size_t k = 0; k < formants.size(); ++k)
        {
          fsai::log::info("F{:<3} {:>10.1f} {:>10.1f} {:>10.1f} {:>8.2f}",
                          k + 1, formants[k], bandwidths[k],
                          k < f1d.size() ? f1d[k] : NAN,
                          k < dev.size() ? dev[k] : NAN);
        }
        fsai::log::info("Wall time {:.2f} s; wrote {}/summary.json", wall,
                        fp.output);

        // 7. Chart (optional: a missing matplotlib only warns)
        if (rt.rank() == 0)
        {
          const std::string cmd = std::string(FSAI_PYTHON) + " "
                                  + FSAI_SCRIPTS_DIR
                                  + "/plot_transfer_function.py " + fp.output
                                  + " > /dev/null 2>&1";
          if (std::system(cmd.c_str()) != 0)
            fsai::log::warn("could not draw transfer_function.png ({})", cmd);
        }

        // 8. Self-check against the 1D model
        if (fp.check_result)
        {
          for (std::size_t k = 0; k < 3; ++k)
          {
            if (k >= dev.size() or std::abs(dev[k]) > 3.0)
            {
              throw std::runtime_error(fmt::format(
                  "check failed: F{} deviates from the 1D model by {} %", k + 1,
                  k < dev.size() ? dev[k] : NAN));
            }
          }
          // With yielding walls the wall losses set B1 (the lip end's are
          // small): the FE wall must reproduce the 1D model's shunt losses
          if (fp.yielding_walls
              and !(bandwidths.size() > 0 and b1d.size() > 0
                    and std::abs(bandwidths[0] - b1d[0]) <= 0.2 * b1d[0]))
          {
            throw std::runtime_error(fmt::format(
                "check failed: B1 = {} Hz vs {} Hz in the 1D model (want "
                "within 20 %)",
                bandwidths.empty() ? NAN : bandwidths[0],
                b1d.empty() ? NAN : b1d[0]));
          }
        }
      });
}
