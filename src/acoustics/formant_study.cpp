// Copyright (C) 2026 fsai developers
#include "formant_study.h"
#include "spectrum.h"
#include <cmath>
#include <common/Parameters.h>
#include <common/errors.h>
#include <common/log.h>
#include <common/timer.h>
#include <io/CsvWriter.h>
#include <io/Progress.h>
#include <io/RunSummary.h>
#include <io/TimeSeriesWriter.h>

namespace ac = fsai::acoustics;

//-----------------------------------------------------------------------------
void ac::FormantParameters::bind(fsai::common::Parameters& p)
{
  p.add("output", output, "output folder");
  p.add("yielding_walls", yielding_walls,
        "tract walls yield (mass-resistance-spring per unit area, "
        "--wave.wall_*), in the FE and the 1D model alike");
  p.add_choice("vowel", vowel, {"u", "a", "i"},
               "vowel of the shipped area functions (meshes/vowel_*.csv)");
  p.add("area-function", area_function,
        "area-function CSV (x_cm,area_cm2); overrides --vowel");
  p.add_choice("model", model, {"planar", "axisym", "1d"},
               "planar 2D channel, axisymmetric tube, or 1D chain matrices");
  p.add_choice("radiation", radiation,
               {"sommerfeld", "pml", "pressure-release", "piston"},
               "lip end: radiation region closed by Sommerfeld or an "
               "absorbing layer, p' = 0 at the lips, or the tract ending at "
               "the lips with a flanged piston's load (A11)");
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
//-----------------------------------------------------------------------------
void ac::FormantParameters::validate() const
{
  fsai::require_positive("--elements_per_wavelength", elements_per_wavelength);
  fsai::require(h >= 0, "--h", ">= 0", h);
  fsai::require_positive("--mic_distance", mic_distance);
  fsai::require(formants >= 1 and formants <= 10, "--formants", "in [1, 10]",
                formants);
  fsai::require(snapshots >= 0, "--snapshots", ">= 0", snapshots);
}
//-----------------------------------------------------------------------------
ac::TractReference ac::tract_reference(const FormantParameters& fp,
                                       const WaveParameters& wave,
                                       const PulseParameters& pulse,
                                       const mesh::VocalTractGeometry& geo)
{
  TractReference ref;
  ref.area = mesh::read_area_function(
      fp.area_function.empty() ? mesh::vowel_file(fp.vowel) : fp.area_function);
  // The 1D model of the same wall (smooth or stepped) as the FE mesh
  ref.area1d = mesh::resample(ref.area, geo.smooth, 5e-4);
  ref.lip = fp.radiation == "pressure-release"       ? LipEnd::pressure_release
            : geo.baffle or fp.radiation == "piston" ? LipEnd::flanged
                                                     : LipEnd::unflanged;
  // Observation point of H: the lips, or 5 mm inside them for p = 0
  ref.x_obs = default_observation_point(ref.area, ref.lip);
  // Yielding walls: the 1D model's wall perimeter is that of the FE model
  // (planar: its two walls of depth L_g; axisymmetric: 2πr)
  if (fp.yielding_walls)
  {
    ref.wall = {wave.wall_mass, wave.wall_resistance, wave.wall_stiffness,
                fp.model == "axisym" ? 0.0 : geo.depth};
  }
  for (auto r : tube_resonances(ref.area1d, pulse.f_max, wave.c0, wave.rho0,
                                ref.lip, ref.x_obs, ref.wall))
  {
    ref.formants.push_back(r.f);
    ref.bandwidths.push_back(r.bandwidth);
  }
  return ref;
}
//-----------------------------------------------------------------------------
ac::Formants ac::formants_1d(MPI_Comm comm, const FormantParameters& fp,
                             const WaveParameters& wave,
                             const PulseParameters& pulse,
                             const TractReference& ref)
{
  io::CsvWriter csv(comm, fp.output + "/transfer_function.csv",
                    {"f_hz", "h_db", "h_1d_db"});
  for (double f = 5.0; f <= pulse.f_max; f += 5.0)
  {
    auto r = tube_response(ref.area1d, f, wave.c0, wave.rho0, ref.lip,
                           ref.x_obs, ref.wall);
    const double h = 20 * std::log10(std::abs(r.h_obs));
    csv.row({f, h, h});
  }
  const std::size_t n = std::min<std::size_t>(fp.formants, ref.formants.size());
  return {{ref.formants.begin(), ref.formants.begin() + long(n)},
          {ref.bandwidths.begin(), ref.bandwidths.begin() + long(n)}};
}
//-----------------------------------------------------------------------------
ac::Formants ac::formants_fe(MPI_Comm comm, const FormantParameters& fp,
                             const WaveParameters& wave,
                             const PulseParameters& pulse,
                             mesh::VocalTractGeometry geo,
                             const TractReference& ref, io::RunSummary& summary)
{
  // Mesh: h from the shortest wavelength unless given
  const auto& af = ref.area;
  const auto& af1d = ref.area1d;
  const auto lip = ref.lip;
  const double x_obs = ref.x_obs;
  const auto& wall1d = ref.wall;
  std::vector<double> formants, bandwidths;
  geo.model = fp.model;
  geo.open = fp.radiation == "sommerfeld" or fp.radiation == "pml";
  geo.layer = fp.radiation == "pml" ? fp.layer : 0.0;
  geo.h
      = fp.h > 0 ? fp.h : wave.c0 / (pulse.f_max * fp.elements_per_wavelength);
  fsai::mesh::MeshData m = [&]
  {
    fsai::common::ScopedTimer t("formants: mesh");
    return fsai::mesh::vocal_tract(comm, af, geo);
  }();

  ac::TractBoundaryModel bm;
  bm.axisymmetric = fp.model == "axisym";
  bm.area_factor
      = bm.axisymmetric ? 2 * M_PI : geo.depth * (geo.half ? 2.0 : 1.0);
  bm.radiation = fp.radiation;
  bm.piston_area = af.area_at(af.length(), geo.smooth);
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
                 and std::abs(x[1]) <= fsai::mesh::tract_half_width(
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

  // Pulse run with progress and p' snapshots
  const int steps = int(std::ceil(pulse.duration / pulse.dt()));
  const int every = fp.snapshots > 0 ? std::max(1, steps / fp.snapshots) : 0;
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
                std::vector<fsai::io::TimeSeriesWriter::Field>{s.pressure()});
          }
          xdmf->write(s.time());
        }
        progress.update(k, fmt::format("E = {:.3e} J", s.energy()));
      });

  // Transfer functions and formants
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
    fsai::io::CsvWriter csv(comm, fp.output + "/transfer_function.csv",
                            {"f_hz", "h_db", "h_mic_db", "h_1d_db"});
    for (std::size_t k = 1; k < H.f.size() and H.f[k] <= pulse.f_max; ++k)
    {
      auto t1 = ac::tube_response(af1d, H.f[k], wave.c0, wave.rho0, lip, x_obs,
                                  wall1d);
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
    fsai::io::CsvWriter csv(comm, fp.output + "/time_series.csv", cols);
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
  return {formants, bandwidths};
}
//-----------------------------------------------------------------------------
void ac::check_formants(const FormantParameters& fp, const Formants& fe,
                        const std::vector<double>& dev,
                        const TractReference& ref)
{
  if (!fp.check_result)
    return;
  for (std::size_t k = 0; k < 3; ++k)
  {
    if (k >= dev.size() or std::abs(dev[k]) > 3.0)
    {
      throw std::runtime_error(
          fmt::format("check failed: F{} deviates from the 1D model by {} %",
                      k + 1, k < dev.size() ? dev[k] : NAN));
    }
  }
  // With yielding walls the wall losses set B1 (the lip end's are small):
  // the FE wall must reproduce the 1D model's shunt losses
  const auto& b1d = ref.bandwidths;
  if (fp.yielding_walls
      and !(fe.bandwidth.size() > 0 and b1d.size() > 0
            and std::abs(fe.bandwidth[0] - b1d[0]) <= 0.2 * b1d[0]))
  {
    throw std::runtime_error(fmt::format(
        "check failed: B1 = {} Hz vs {} Hz in the 1D model (want within 20 "
        "%)",
        fe.bandwidth.empty() ? NAN : fe.bandwidth[0],
        b1d.empty() ? NAN : b1d[0]));
  }
}
