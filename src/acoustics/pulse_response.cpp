// Copyright (C) 2026 fsai developers
#include "pulse_response.h"
#include "../common/Parameters.h"
#include "../common/errors.h"
#include "../common/timer.h"
#include "../io/PointProbes.h"
#include <cmath>

namespace
{
/// Local facet indices of the named group; a required group that the mesh
/// lacks is an error naming the groups it has
std::vector<std::int32_t> facets(const fsai::mesh::MeshData& m,
                                 const std::string& name)
{
  return m.facet_tags->find(m.facet_tag(name));
}
} // namespace

//-----------------------------------------------------------------------------
void fsai::acoustics::PulseParameters::bind(fsai::common::Parameters& p)
{
  p.add("pulse.f_max", f_max, "highest frequency of interest [Hz]");
  p.add("pulse.steps_per_period", steps_per_period,
        "time steps per period of f_max");
  p.add("pulse.duration", duration, "simulated time [s]");
  p.add("pulse.window_decay", window_decay,
        "decay time of the exponential window [s] (0: duration/5)");
  p.add("pulse.degree", degree, "Lagrange degree of the pressure (1 or 2)");
}
//-----------------------------------------------------------------------------
void fsai::acoustics::PulseParameters::validate() const
{
  fsai::require_positive("--pulse.f_max", f_max);
  fsai::require(steps_per_period >= 4, "--pulse.steps_per_period", ">= 4",
                steps_per_period);
  fsai::require_positive("--pulse.duration", duration);
  fsai::require(window_decay >= 0, "--pulse.window_decay", ">= 0",
                window_decay);
  fsai::require(degree == 1 or degree == 2, "--pulse.degree", "1 or 2", degree);
  fsai::require(duration * f_max * steps_per_period < 5e6, "--pulse.duration",
                "at most 5e6 time steps", duration);
}
//-----------------------------------------------------------------------------
fsai::acoustics::PulseResult fsai::acoustics::pulse_response(
    const fsai::mesh::MeshData& m, const WaveParameters& wave,
    const PulseParameters& pulse, const TractBoundaryModel& bm,
    const std::vector<std::array<double, 3>>& probes,
    const std::function<void(int, const WaveSolver&)>& on_step)
{
  pulse.validate();
  WaveBoundaries b;
  b.inlet = facets(m, "glottis");
  b.yielding = bm.yielding;
  std::shared_ptr<dolfinx::fem::Function<double>> sigma;
  if (bm.radiation == "pressure-release")
    b.pressure_release = facets(m, "lips");
  else if (bm.radiation == "piston")
  {
    b.piston = facets(m, "lips");
    b.piston_area = bm.piston_area;
  }
  else if (bm.radiation == "sommerfeld" or bm.radiation == "pml")
  {
    b.radiation = facets(m, "radiation");
    const double R
        = bm.radiation_radius + (bm.radiation == "pml" ? bm.layer : 0.0);
    b.radiation_beta = bm.curvature ? (bm.spherical ? 1.0 : 0.5) / R : 0.0;
    if (bm.radiation == "pml")
    {
      fsai::require_positive("absorbing layer thickness", bm.layer);
      std::vector<std::int32_t> cells = m.cell_tags->find(m.cell_tag("layer"));
      sigma = absorbing_layer(m.mesh, cells, bm.centre, bm.radiation_radius,
                              bm.layer, wave.c0, 1e-3);
    }
  }
  else
  {
    throw fsai::InputError("radiation must be sommerfeld, pml, "
                           "pressure-release or piston (got '"
                           + bm.radiation + "')");
  }

  const double dt = pulse.dt();
  WaveSolver solver(m.mesh, pulse.degree, bm.axisymmetric, wave, b, dt, sigma);
  fsai::io::PointProbes probe(m.mesh, probes);
  const double area = solver.inlet_measure() * bm.area_factor;
  fsai::require_positive("inlet area", area);

  const double tau = 0.84 / pulse.f_max, t0 = 4.0 * tau, U0 = 1e-4;
  auto U
      = [&](double t) { return U0 * std::exp(-std::pow((t - t0) / tau, 2)); };
  auto dUdt = [&](double t) { return -2.0 * (t - t0) / (tau * tau) * U(t); };

  PulseResult r;
  r.dt = dt;
  r.dofs = solver.dofs();
  r.p.resize(probes.size());
  const int n = int(std::ceil(pulse.duration / dt));
  auto record = [&](double t)
  {
    r.t.push_back(t);
    r.U.push_back(U(t));
    std::vector<double> v = probe.values(*solver.pressure());
    for (std::size_t i = 0; i < v.size(); ++i)
      r.p[i].push_back(v[i]);
    r.energy.push_back(solver.energy());
  };

  // The pulse starts at rest (U(0)/U0 = e^-16): zero initial state
  solver.set_inlet_acceleration(dUdt(0.0) / area);
  record(0.0);
  for (int k = 1; k <= n; ++k)
  {
    const double t = k * dt;
    solver.set_inlet_acceleration(dUdt(t) / area);
    solver.step();
    record(t);
    if (on_step)
      on_step(k, solver);
  }
  r.steps = n;
  return r;
}
//-----------------------------------------------------------------------------
