// Copyright (C) 2026 fsai developers
// Acoustics (docs/model.md E14, E21): Newmark energy conservation,
// space/time convergence on an exact standing mode, closed-open tube
// resonances (planar and axisymmetric FE), the 1D chain-matrix model, and
// area-function input errors.
#include "catch.h"
#include <Eigen/Dense>
#include <acoustics/MonopoleMicrophone.h>
#include <acoustics/TubeTract.h>
#include <acoustics/WaveSolver.h>
#include <acoustics/pulse_response.h>
#include <acoustics/spectrum.h>
#include <acoustics/tube_model.h>
#include <common/errors.h>
#include <common/log.h>
#include <dolfinx/fem/assembler.h>
#include <dolfinx/fem/utils.h>
#include <dolfinx/mesh/generation.h>
#include <dolfinx/mesh/utils.h>
#include <fsai_forms/acoustics.h>
#include <fstream>
#include <functional>
#include <io/PointProbes.h>
#include <mesh/area_function.h>
#include <mesh/vocal_tract.h>
#include <xtensor/xview.hpp>

namespace
{
std::shared_ptr<dolfinx::mesh::Mesh> unit_square(std::size_t n)
{
  using namespace dolfinx::mesh;
  return std::make_shared<Mesh>(
      create_rectangle(MPI_COMM_WORLD, {{{0.0, 0.0}, {1.0, 1.0}}}, {n, n},
                       CellType::triangle, GhostMode::shared_facet));
}

std::shared_ptr<dolfinx::mesh::Mesh> unit_cube(std::size_t n)
{
  using namespace dolfinx::mesh;
  return std::make_shared<Mesh>(
      create_box(MPI_COMM_WORLD, {{{0.0, 0.0, 0.0}, {1.0, 1.0, 1.0}}},
                 {n, n, n}, CellType::tetrahedron, GhostMode::shared_facet));
}

/// Exact standing mode cos(πx)cos(πy) as the initial pressure
std::shared_ptr<dolfinx::fem::Function<double>>
standing_mode(const fsai::acoustics::WaveSolver& s)
{
  auto p0 = std::make_shared<dolfinx::fem::Function<double>>(
      s.pressure()->function_space());
  p0->interpolate(
      [](auto& x) -> xt::xarray<double>
      {
        xt::xarray<double> v = xt::zeros<double>({x.shape(1)});
        for (std::size_t i = 0; i < x.shape(1); ++i)
          v(i) = std::cos(M_PI * x(0, i)) * std::cos(M_PI * x(1, i));
        return v;
      });
  return p0;
}

/// L2 error against p_e = cos(c0 π √2 t) cos(πx) cos(πy) at the solver's time
double mode_error(const fsai::acoustics::WaveSolver& s, double c0, int degree)
{
  namespace forms = fsai::forms::acoustics;
  auto mesh = s.pressure()->function_space()->mesh();
  using C = std::shared_ptr<const dolfinx::fem::Constant<double>>;
  auto e = dolfinx::fem::create_form<double>(
      forms::error_L2(2, degree), {}, {{"ph", s.pressure()}},
      std::map<std::string, C>{
          {"c0", std::make_shared<dolfinx::fem::Constant<double>>(c0)},
          {"t_exact",
           std::make_shared<dolfinx::fem::Constant<double>>(s.time())}},
      {}, mesh);
  double local = dolfinx::fem::assemble_scalar(e), global = 0;
  MPI_Allreduce(&local, &global, 1, MPI_DOUBLE, MPI_SUM, mesh->comm());
  return std::sqrt(global);
}

/// First n peaks of the pulse response of a tract observed at probe 1
std::vector<double>
pulse_formants(const fsai::mesh::AreaFunction& af,
               fsai::mesh::VocalTractGeometry g, const std::string& radiation,
               int n, const fsai::acoustics::WaveParameters& wave = {},
               bool yielding = false)
{
  namespace ac = fsai::acoustics;
  g.open = radiation != "pressure-release";
  auto m = fsai::mesh::vocal_tract(MPI_COMM_WORLD, af, g);
  ac::PulseParameters pulse;
  pulse.duration = 0.05;
  ac::TractBoundaryModel bm;
  bm.axisymmetric = g.model == "axisym";
  bm.area_factor = bm.axisymmetric ? 2 * M_PI : g.depth;
  bm.radiation = radiation;
  bm.radiation_radius = g.radius;
  bm.centre = {af.length(), 0, 0};
  bm.spherical = bm.axisymmetric;
  if (yielding)
    bm.yielding = m.facet_tags->find(m.facet_tag("wall"));
  const double x_obs = ac::default_observation_point(
      af, g.open ? ac::LipEnd::unflanged : ac::LipEnd::pressure_release);
  auto r = ac::pulse_response(m, wave, pulse, bm, {{0, 0, 0}, {x_obs, 0, 0}});
  auto H = ac::transfer_function(r.U, r.p[1], r.dt, pulse.decay());
  std::vector<double> mag, f;
  for (auto h : H.h)
    mag.push_back(std::abs(h));
  for (auto p : ac::find_peaks(H.f, mag, 50.0, pulse.f_max))
    if (int(f.size()) < n)
      f.push_back(p.f);
  return f;
}

std::string write_file(const fsai::test::TempDir& dir, const std::string& name,
                       const std::string& text)
{
  const std::string path = dir / name;
  int rank;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  if (rank == 0)
    std::ofstream(path) << text;
  MPI_Barrier(MPI_COMM_WORLD);
  return path;
}
} // namespace

TEST_CASE("Acoustic energy of a closed rigid domain is conserved by Newmark",
          "[acoustics][mpi]")
{
  // Undamped, unforced E21 with β = 1/4, γ = 1/2: ½ṖᵀMṖ + ½PᵀKP is an
  // exact invariant of the discrete scheme; 10^4 steps of a standing mode
  const int dim = GENERATE(2, 3);
  CAPTURE(dim);
  fsai::acoustics::WaveParameters wave;
  wave.c0 = 1.0;
  fsai::acoustics::WaveSolver s(dim == 2 ? unit_square(12) : unit_cube(5), 1,
                                false, wave, {}, 0.01);
  s.set_initial_state(*standing_mode(s));
  const double e0 = s.energy();
  double worst = 0.0;
  for (int k = 0; k < 10000; ++k)
  {
    s.step();
    if (k % 100 == 99)
      worst = std::max(worst, std::abs(s.energy() - e0) / e0);
  }
  fsai::log::info("Acoustics energy {}D: 1e4 steps, max relative drift {:.2e}",
                  dim, worst);
  CHECK(e0 > 0.0);
  CHECK(worst < 1e-8);
}

TEST_CASE("Newmark with gamma > 1/2 damps mesh-scale modes, keeps resolved "
          "ones",
          "[acoustics][mpi]")
{
  // γ = 0.6, β = (γ + ½)²/4 (the voice scene's sound step). For one mode
  // ẍ + ω²x = 0 the scheme's amplitude falls by the spectral radius ρ(ωΔt)
  // of its amplification matrix per step; the mode's energy by ρ². Checked
  // on the standing mode cos πx cos πy (ωΔt = 0.044) against ρ, and on the
  // mesh's checkerboard cos 12πx cos 12πy (an eigenmode of the P1 matrices
  // on this mesh, ω² = 24 c0²/h²: ωΔt = 0.59): the trapezoidal rule (γ = ½)
  // keeps it, γ = 0.6 removes it
  namespace ac = fsai::acoustics;
  ac::WaveParameters wave;
  wave.c0 = 1.0;
  wave.newmark_gamma = 0.6;
  wave.newmark_beta = 0.3025;
  const double dt = 0.01;
  auto radius = [](double W, double g)
  {
    // Amplification matrix of (x, v, a) over one step, Δt = 1
    const double b = (g + 0.5) * (g + 0.5) / 4;
    Eigen::Matrix3d A;
    for (int j = 0; j < 3; ++j)
    {
      Eigen::Vector3d e = Eigen::Vector3d::Zero();
      e[j] = 1;
      const double xp = e[0] + e[1] + (0.5 - b) * e[2],
                   vp = e[1] + (1 - g) * e[2];
      const double a1 = -W * W * xp / (1 + b * W * W);
      A.col(j) << xp + b * a1, vp + g * a1, a1;
    }
    return A.eigenvalues().cwiseAbs().maxCoeff();
  };
  auto mode = [](const ac::WaveSolver& s, double k)
  {
    auto p0 = std::make_shared<dolfinx::fem::Function<double>>(
        s.pressure()->function_space());
    p0->interpolate(
        [k](auto& x) -> xt::xarray<double>
        {
          xt::xarray<double> v = xt::zeros<double>({x.shape(1)});
          for (std::size_t i = 0; i < x.shape(1); ++i)
            v(i) = std::cos(k * M_PI * x(0, i)) * std::cos(k * M_PI * x(1, i));
          return v;
        });
    return p0;
  };
  // Resolved: 1000 steps (7 periods)
  {
    ac::WaveSolver s(unit_square(12), 1, false, wave, {}, dt);
    s.set_initial_state(*mode(s, 1.0));
    const double e0 = s.energy();
    const int n = 1000;
    for (int k = 0; k < n; ++k)
      s.step();
    const double per_step = std::sqrt(std::pow(s.energy() / e0, 1.0 / n));
    const double theory = radius(M_PI * std::sqrt(2.0) * dt, 0.6);
    fsai::log::info("Newmark gamma 0.6, resolved mode (w dt = 0.044): "
                    "amplitude loss per step {:.3e}, theory {:.3e}",
                    1 - per_step, 1 - theory);
    // The mesh's ω is 1-2 % above π√2 and the loss goes as (ωΔt)²
    CHECK(std::abs((1 - per_step) / (1 - theory) - 1) < 0.1);
  }
  // Mesh scale: 200 steps, γ = 0.6 against γ = ½
  for (const double gamma : {0.6, 0.5})
  {
    ac::WaveParameters w = wave;
    w.newmark_gamma = gamma;
    w.newmark_beta = (gamma + 0.5) * (gamma + 0.5) / 4;
    ac::WaveSolver s(unit_square(12), 1, false, w, {}, dt);
    s.set_initial_state(*mode(s, 12.0));
    const double e0 = s.energy();
    for (int k = 0; k < 200; ++k)
      s.step();
    const double ratio = s.energy() / e0;
    fsai::log::info("Newmark gamma {}, checkerboard mode: energy after 200 "
                    "steps {:.3e} of the initial (theory {:.3e})",
                    gamma, ratio,
                    std::pow(radius(std::sqrt(24.0) * 12 * dt, gamma), 400));
    if (gamma > 0.5)
      CHECK(ratio < 0.01); // theory ρ(0.59)^400 = 1.6e-3
    else
      CHECK(std::abs(ratio - 1) < 1e-9);
  }
}

TEST_CASE("Standing mode converges at second order in space and time",
          "[acoustics][mpi]")
{
  fsai::acoustics::WaveParameters wave;
  wave.c0 = 1.0;
  const double T = 0.5;
  auto run = [&](std::size_t n, int degree, double dt)
  {
    fsai::acoustics::WaveSolver s(unit_square(n), degree, false, wave, {}, dt);
    s.set_initial_state(*standing_mode(s));
    const int steps = int(std::lround(T / dt));
    for (int k = 0; k < steps; ++k)
      s.step();
    return mode_error(s, wave.c0, degree);
  };
  // Space: P1, Δt small enough that the time error is negligible
  const double e8 = run(8, 1, 1e-3), e16 = run(16, 1, 1e-3),
               e32 = run(32, 1, 1e-3);
  const double rs = std::log2(e16 / e32);
  // Time: P2 on a fine mesh, Δt halved
  const double t1 = run(24, 2, 0.1), t2 = run(24, 2, 0.05),
               t3 = run(24, 2, 0.025);
  const double rt = std::log2(t2 / t3);
  fsai::log::info(
      "Acoustics MMS: space P1 e = {:.3e} {:.3e} {:.3e} rate {:.3f};"
      " time e = {:.3e} {:.3e} {:.3e} rate {:.3f}",
      e8, e16, e32, rs, t1, t2, t3, rt);
  CHECK(rs == Approx(2.0).margin(0.15));
  CHECK(rt == Approx(2.0).margin(0.15));
}

TEST_CASE("1D chain-matrix model: closed-open tube resonances", "[acoustics]")
{
  const double L = 0.175, c0 = 343.0;
  auto af = fsai::mesh::resample(fsai::mesh::uniform_tube(L, 3e-4), true, 1e-3);
  auto r = fsai::acoustics::tube_resonances(
      af, 4000.0, c0, 1.2, fsai::acoustics::LipEnd::pressure_release);
  REQUIRE(r.size() >= 4);
  for (int n = 1; n <= 4; ++n)
    CHECK(r[n - 1].f == Approx((2 * n - 1) * c0 / (4 * L)).epsilon(1e-4));
}

TEST_CASE("Yielding walls of mass m: f_n^2 = f_n,rigid^2 + f_w^2",
          "[acoustics][mpi]")
{
  // A closed-open tube whose walls are a mass per unit area m (r = k = 0)
  // has the dispersion relation β² = ω²/c0² − ρ0 P/(m A) (P the wall
  // perimeter), so each resonance moves to f_n² = ((2n−1) c0/4L)² + f_w²
  // with the closed-tract wall resonance f_w = (c0/2π) √(ρ0 P/(m A))
  // (Fant 1960; Sondhi 1974). Planar channel of depth L_g: P = 2 L_g.
  namespace ac = fsai::acoustics;
  const double L = 0.175, A = 3e-4, c0 = 343.0, rho0 = 1.2, m = 15.0;
  fsai::mesh::VocalTractGeometry g;
  const double fw
      = c0 / (2 * M_PI) * std::sqrt(rho0 * 2 * g.depth / (m * A)); // 169 Hz
  auto exact
      = [&](int n) { return std::hypot((2 * n - 1) * c0 / (4 * L), fw); };
  ac::TubeWall wall{m, 0.0, 0.0, g.depth};
  auto r1d = ac::tube_resonances(
      fsai::mesh::resample(fsai::mesh::uniform_tube(L, A), true, 1e-3), 4000.0,
      c0, rho0, ac::LipEnd::pressure_release, -1.0, wall);
  REQUIRE(r1d.size() >= 3);
  ac::WaveParameters wave;
  wave.wall_mass = m;
  wave.wall_resistance = 0.0;
  wave.wall_stiffness = 0.0;
  g.h = 0.005;
  auto fe = pulse_formants(fsai::mesh::uniform_tube(L, A), g,
                           "pressure-release", 3, wave, true);
  REQUIRE(fe.size() == 3);
  for (int n = 1; n <= 3; ++n)
  {
    fsai::log::info("Yielding walls f{}: exact {:.2f} Hz (rigid {:.2f}), 1D "
                    "{:.2f}, FE {:.2f} Hz ({:+.3f} %)",
                    n, exact(n), (2 * n - 1) * c0 / (4 * L), r1d[n - 1].f,
                    fe[n - 1], 100 * (fe[n - 1] - exact(n)) / exact(n));
    CHECK(r1d[n - 1].f == Approx(exact(n)).epsilon(1e-3));
    CHECK(fe[n - 1] == Approx(exact(n)).epsilon(5e-3));
  }
}

TEST_CASE("Slit law: a resistive slab closes the tube, air at rest is "
          "the plain solver",
          "[acoustics][mpi]")
{
  // A closed–open tube (rigid at x = 0, p' = 0 at x = L) whose cells in the
  // slab x ∈ [x1, x2] follow the slit law ρ' ∂v/∂t + r' v = −∇p'
  // (acoustics::SlitLaw, forms/acoustics.py). A large r' closes
  // the tube at the slab: the part beyond it resonates as a closed–open
  // tube of length L − x2, f1 = c0 / 4 (L − x2) (the part before it,
  // closed at both ends, has its first mode at c0 / 2 x1, far above).
  // ρ' = ρ0, r' = 0 must give the plain solver's pressure history.
  namespace ac = fsai::acoustics;
  const double L = 0.175, A = 3e-4, c0 = 343.0, x1 = 0.06, x2 = 0.07;
  fsai::mesh::VocalTractGeometry g;
  g.h = 0.004;
  g.open = false;
  auto m = fsai::mesh::vocal_tract(MPI_COMM_WORLD,
                                   fsai::mesh::uniform_tube(L, A), g);
  const int tdim = m.mesh->topology().dim();
  const std::int32_t nc = m.mesh->topology().index_map(tdim)->size_local();
  const auto x = m.mesh->geometry().x();
  const auto& xdofs = m.mesh->geometry().dofmap();
  std::vector<std::int32_t> slab;
  for (std::int32_t c = 0; c < nc; ++c)
  {
    double xm = 0;
    for (auto v : xdofs.links(c))
      xm += x[3 * v] / double(xdofs.links(c).size());
    if (xm > x1 and xm < x2)
      slab.push_back(c);
  }
  ac::WaveParameters wave;
  const double dt = 2e-5;
  auto run = [&](double inertia, double resistance, bool section)
  {
    ac::WaveBoundaries b;
    b.pressure_release = m.facet_tags->find(m.facet_tag("lips"));
    ac::WaveSolver s(m.mesh, 1, false, wave, b, dt, nullptr, false);
    if (section)
    {
      auto slit = std::make_shared<ac::SlitLaw>(slab, true);
      s.set_slit(slit);
      const std::size_t n = slit->cells().size();
      slit->set(std::vector<double>(n, inertia),
                std::vector<double>(n, resistance));
    }
    // Initial state: a smooth bump beyond the slab, at rest
    auto p0 = std::make_shared<dolfinx::fem::Function<double>>(
        s.pressure()->function_space());
    p0->interpolate(
        [](auto& X) -> xt::xarray<double>
        {
          xt::xarray<double> v = xt::zeros<double>({X.shape(1)});
          for (std::size_t i = 0; i < X.shape(1); ++i)
            v(i) = std::exp(-std::pow((X(0, i) - 0.12) / 0.01, 2));
          return v;
        });
    s.set_initial_state(*p0);
    fsai::io::PointProbes probe(m.mesh, {{0.1, 0.0, 0.0}});
    std::vector<double> series;
    for (int k = 0; k < 2500; ++k)
    {
      s.step();
      series.push_back(probe.values(*s.pressure())[0]);
    }
    return series;
  };
  const auto plain = run(1.0, 0.0, false), same = run(1.0, 0.0, true);
  double diff = 0, scale = 0;
  for (std::size_t i = 0; i < plain.size(); ++i)
  {
    diff = std::max(diff, std::abs(same[i] - plain[i]));
    scale = std::max(scale, std::abs(plain[i]));
  }
  CHECK(diff <= 1e-12 * scale);
  // r' = 1e8 kg/(m³ s): the slab's resistance r' (x2 − x1) / A_planar is
  // ~1e4 times the tube's ρ0 c0 / A
  const auto closed = run(1.0, 1e8, true);
  auto [f, a] = ac::amplitude_spectrum(closed, dt, 8);
  auto peaks = ac::find_peaks(f, a, 100.0, 2000.0);
  REQUIRE(!peaks.empty());
  const double exact = c0 / (4 * (L - x2)), open = c0 / (4 * L);
  fsai::log::info("Slit law: air at rest vs plain solver {:.1e} of the "
                  "peak; resistive slab (r' = 1e8): f1 {:.1f} Hz, closed "
                  "tube beyond the slab {:.1f} Hz ({:+.2f} %), whole tube "
                  "{:.1f} Hz",
                  diff / scale, peaks[0].f, exact,
                  100 * (peaks[0].f - exact) / exact, open);
  CHECK(peaks[0].f == Approx(exact).epsilon(0.02));
  // An inertia alone (ρ' = 100 ρ0, a slit 1 % as wide, no loss) lowers the
  // whole tube's f1 (the slab is a series inertance) but keeps it above
  // the closed part's: the tube stays open through it
  const auto narrow = run(100.0, 0.0, true);
  auto [f2, a2] = ac::amplitude_spectrum(narrow, dt, 8);
  auto p2 = ac::find_peaks(f2, a2, 100.0, 2000.0);
  REQUIRE(!p2.empty());
  fsai::log::info("Slit law: inertia x100 in the slab: f1 {:.1f} Hz", p2[0].f);
  CHECK(p2[0].f < 0.98 * open);
}

TEST_CASE("1D model with a glottal branch: a split tube is one tube",
          "[acoustics]")
{
  // A uniform tube of length L (p' = 0 at the lips) whose glottal end leads
  // into a branch of the same area and length L_b, rigid at its far end, is
  // one closed-open tube of length L + L_b with the source at the joint:
  // its resonances are (2n−1) c0 / 4 (L + L_b) (none is cancelled here:
  // the branch's quarter-wave zero, c0 / 4 L_b = 1143 Hz, is not one of
  // them). A wrong sign of the branch impedance moves them all.
  namespace ac = fsai::acoustics;
  const double L = 0.1, Lb = 0.075, A = 3e-4, c0 = 343.0;
  ac::GlottalBranch branch{
      fsai::mesh::resample(fsai::mesh::uniform_tube(Lb, A), true, 1e-3), false};
  auto r = ac::tube_resonances(
      fsai::mesh::resample(fsai::mesh::uniform_tube(L, A), true, 1e-3), 3000.0,
      c0, 1.2, ac::LipEnd::pressure_release, -1.0, {}, branch);
  REQUIRE(r.size() >= 3);
  for (int n = 1; n <= 3; ++n)
    CHECK(r[n - 1].f
          == Approx((2 * n - 1) * c0 / (4 * (L + Lb))).epsilon(1e-3));
  // A vanishing glottal opening is the closed end again
  ac::GlottalBranch slit{fsai::mesh::uniform_tube(0.004, 1e-12), true};
  auto closed = ac::tube_resonances(
      fsai::mesh::resample(fsai::mesh::uniform_tube(L, A), true, 1e-3), 3000.0,
      c0, 1.2, ac::LipEnd::pressure_release, -1.0, {}, slit);
  REQUIRE(closed.size() >= 2);
  CHECK(closed[0].f == Approx(c0 / (4 * L)).epsilon(1e-3));
}

TEST_CASE("FE closed-open tube: f_n = (2n-1) c / 4L within 0.5%",
          "[acoustics][mpi]")
{
  const std::string model
      = GENERATE(std::string("planar"), std::string("axisym"));
  CAPTURE(model);
  const double L = 0.175, c0 = 343.0;
  fsai::mesh::VocalTractGeometry g;
  g.model = model;
  g.h = 0.005;
  auto f = pulse_formants(fsai::mesh::uniform_tube(L, 3e-4), g,
                          "pressure-release", 4);
  REQUIRE(f.size() == 4);
  for (int n = 1; n <= 4; ++n)
  {
    const double ref = (2 * n - 1) * c0 / (4 * L);
    fsai::log::info(
        "Acoustics tube {} f{} = {:.2f} Hz (exact {:.2f}, {:+.3f}%)", model, n,
        f[n - 1], ref, 100 * (f[n - 1] - ref) / ref);
    CHECK(f[n - 1] == Approx(ref).epsilon(0.005));
  }
}

TEST_CASE("FE vowel [u] F1-F3 within 3% of the 1D model (p' = 0 at lips)",
          "[acoustics][mpi]")
{
  namespace ac = fsai::acoustics;
  const std::string model
      = GENERATE(std::string("planar"), std::string("axisym"));
  CAPTURE(model);
  auto af = fsai::mesh::read_area_function(fsai::mesh::vowel_file("u"));
  fsai::mesh::VocalTractGeometry g;
  g.model = model;
  g.h = 0.00686;
  auto f = pulse_formants(af, g, "pressure-release", 3);
  auto ref = ac::tube_resonances(fsai::mesh::resample(af, true, 5e-4), 5000,
                                 343.0, 1.2, ac::LipEnd::pressure_release);
  REQUIRE(f.size() == 3);
  for (int n = 0; n < 3; ++n)
  {
    fsai::log::info("Acoustics [u] {} F{} = {:.1f} Hz, 1D {:.1f} Hz ({:+.2f}%)",
                    model, n + 1, f[n], ref[n].f,
                    100 * (f[n] - ref[n].f) / ref[n].f);
    CHECK(f[n] == Approx(ref[n].f).epsilon(0.03));
  }
}

TEST_CASE("Area-function files: clear errors for bad input", "[acoustics]")
{
  fsai::test::TempDir dir;
  using fsai::InputError;
  auto bad = [&](const std::string& text)
  { return write_file(dir, "bad.csv", text); };
  CHECK_THROWS_AS(fsai::mesh::read_area_function(dir / "none.csv"), InputError);
  CHECK_THROWS_AS(fsai::mesh::read_area_function(bad("x_cm,area_cm2\n1,abc\n")),
                  InputError);
  CHECK_THROWS_AS(fsai::mesh::read_area_function(bad("x_cm,area_cm2\n1,-2\n")),
                  InputError);
  CHECK_THROWS_AS(
      fsai::mesh::read_area_function(bad("x_cm,area_cm2\n1,2\n0.5,2\n")),
      InputError);
  CHECK_THROWS_AS(fsai::mesh::read_area_function(bad("a,b\n1,2\n")),
                  InputError);
  CHECK_THROWS_AS(fsai::mesh::read_area_function(bad("x_cm,area_cm2\n")),
                  InputError);
  CHECK_THROWS_AS(fsai::mesh::vowel_file("y"), InputError);
  auto af = fsai::mesh::read_area_function(
      bad("# comment\nx_cm,area_cm2\n1,2\n3,4.5\n"));
  CHECK(af.size() == 2);
  CHECK(af.length() == Approx(0.03));
  CHECK(af.area[1] == Approx(4.5e-4));
  CHECK(af.area_at(0.0125, true) == Approx(3.25e-4)); // centres 0.5, 2 cm
}

TEST_CASE("Unflanged tube radiating into free field: end correction 0.6133 a",
          "[acoustics][mpi]")
{
  // Axisymmetric tube, thin wall (1 mm), radiation region of radius 8 cm
  // closed by the Sommerfeld condition with its curvature term. The end
  // correction follows from f1 = c / 4 (L + Δ); Levine & Schwinger (1948):
  // Δ = 0.6133 a for an infinitely thin wall, ka → 0 (here ka = 0.09)
  const double L = 0.175, A = 3e-4, c0 = 343.0, a = std::sqrt(A / M_PI);
  fsai::mesh::VocalTractGeometry g;
  g.model = "axisym";
  g.h = 0.003;
  g.wall = 0.001;
  auto f = pulse_formants(fsai::mesh::uniform_tube(L, A), g, "sommerfeld", 1);
  REQUIRE(f.size() == 1);
  const double delta = c0 / (4 * f[0]) - L;
  fsai::log::info("Acoustics end correction: f1 = {:.2f} Hz, delta/a = {:.4f} "
                  "(Levine-Schwinger 0.6133, {:+.1f}%)",
                  f[0], delta / a, 100 * (delta / a - 0.6133) / 0.6133);
  CHECK(delta / a == Approx(0.6133).epsilon(0.15));
}

namespace
{
/// b(φ_h) = Σ_i b_i φ(x_i) over owned dofs (collective)
double load_on(fsai::acoustics::WaveSolver& s,
               const std::function<double(double, double)>& phi)
{
  std::vector<double> b = s.source_vector();
  auto V = s.pressure()->function_space();
  dolfinx::fem::Function<double> f(V);
  f.interpolate(
      [&](auto& x) -> xt::xarray<double>
      {
        xt::xarray<double> v = xt::zeros<double>({x.shape(1)});
        for (std::size_t i = 0; i < x.shape(1); ++i)
          v(i) = phi(x(0, i), x(1, i));
        return v;
      });
  double local = 0.0, global = 0.0;
  for (std::size_t i = 0; i < b.size(); ++i)
    local += b[i] * f.x()->array()[i];
  MPI_Allreduce(&local, &global, 1, MPI_DOUBLE, MPI_SUM, V->mesh()->comm());
  return global;
}
} // namespace

TEST_CASE("Lighthill source converges to the integral of d2T_ij/dx_i dx_j",
          "[acoustics][mpi]")
{
  // On (0,1)² with T = ρ0 v⊗v vanishing with its normal derivative on the
  // boundary, the weak source −((∇·T)_w, ∇q) tested with φ must approach
  // ∫ ∂i∂j T_ij φ w dx:
  //  planar, v = (sin πx sin πy, 0), φ = cos 2πx:          ρ0 π²/2
  //  axisym (y = r), the same v:                           ρ0 π²/4
  //  axisym, v = (0, sin πx sin πr), φ = cos πr, with the cylindrical
  //  divergence (r-weighted: ∫∫ ∂r²(r T_rr) φ dr dx):       2ρ0/9
  //  (without the hoop term T_rr/r the limit would differ by ρ0·2/3)
  struct Case
  {
    bool axi;
    int component;
    bool phi_of_y;
    double exact;
    const char* name;
  };
  const double rho0 = 1.2, pi2 = M_PI * M_PI;
  const Case c
      = GENERATE_COPY(Case{false, 0, false, rho0 * pi2 / 2, "planar T_xx"},
                      Case{true, 0, false, rho0 * pi2 / 4, "axisym T_xx"},
                      Case{true, 1, true, 2 * rho0 / 9, "axisym T_rr"});
  CAPTURE(c.name);
  std::vector<double> err;
  for (std::size_t n : {16, 32, 64})
  {
    fsai::acoustics::WaveParameters wave;
    wave.rho0 = rho0;
    fsai::acoustics::WaveSolver s(unit_square(n), 1, c.axi, wave, {}, 1e-3,
                                  nullptr, true);
    s.flow_velocity().interpolate(
        [&](auto& x) -> xt::xarray<double>
        {
          xt::xarray<double> v
              = xt::zeros<double>({std::size_t(2), x.shape(1)});
          for (std::size_t i = 0; i < x.shape(1); ++i)
            v(c.component, i)
                = std::sin(M_PI * x(0, i)) * std::sin(M_PI * x(1, i));
          return v;
        });
    const double b = load_on(
        s, [&](double x, double y)
        { return c.phi_of_y ? std::cos(M_PI * y) : std::cos(2 * M_PI * x); });
    err.push_back(std::abs(b - c.exact) / c.exact);
  }
  fsai::log::info("Acoustics Lighthill source {}: relative error {:.2e} "
                  "{:.2e} {:.2e} (n = 16, 32, 64)",
                  c.name, err[0], err[1], err[2]);
  CHECK(err[2] < 0.01);
  CHECK(err[2] < 0.5 * err[1]);
}

TEST_CASE("Vibrating wall load is -rho0 a.n over the wall", "[acoustics][mpi]")
{
  // Wall x = 1 of the unit square accelerating with a = (a0, 0): the load
  // tested with q = 1 is −ρ0 a0 |Γ| (planar) or −ρ0 a0 ∫ r dr = −ρ0 a0 / 2
  const bool axi = GENERATE(false, true);
  auto mesh = unit_square(8);
  const int fdim = 1;
  mesh->topology_mutable().create_connectivity(fdim, 2);
  std::vector<std::int32_t> wall = dolfinx::mesh::locate_entities_boundary(
      *mesh, fdim,
      [](auto& x) -> xt::xtensor<bool, 1>
      { return xt::isclose(xt::row(x, 0), 1.0); });
  fsai::acoustics::WaveBoundaries bnd;
  bnd.vibrating = wall;
  fsai::acoustics::WaveParameters wave;
  fsai::acoustics::WaveSolver s(mesh, 1, axi, wave, bnd, 1e-3);
  const double a0 = 3.0;
  s.wall_acceleration().interpolate(
      [&](auto& x) -> xt::xarray<double>
      {
        xt::xarray<double> v = xt::zeros<double>({std::size_t(2), x.shape(1)});
        xt::row(v, 0) = a0;
        return v;
      });
  const double b = load_on(s, [](double, double) { return 1.0; });
  CHECK(b == Approx(-wave.rho0 * a0 * (axi ? 0.5 : 1.0)).epsilon(1e-10));
}
TEST_CASE("Volume source in a duct: plane waves rho0 c0 Q / 2W each way",
          "[acoustics][mpi]")
{
  // A channel of width W (planar, per unit depth) with anechoic ends and a
  // compact volume source Q(t) (a Gaussian pulse, m²/s) at its middle: the
  // 1D solution is p = ρ0 c0 Q(t − |x − x_s|/c0) / (2W) on each side. The
  // load tested with q = 1 is ρ0 dQ/dt exactly (∫ψ = 1).
  namespace ac = fsai::acoustics;
  using namespace dolfinx::mesh;
  const double L = 0.4, W = 0.02, xs = 0.2, Q0 = 1e-4, t0 = 6e-4, tau = 2e-4;
  auto mesh = std::make_shared<Mesh>(create_rectangle(
      MPI_COMM_WORLD, {{{0.0, 0.0}, {L, W}}}, {400, 20}, CellType::triangle,
      GhostMode::shared_facet, DiagonalType::right));
  mesh->topology_mutable().create_connectivity(1, 2);
  ac::WaveBoundaries bnd;
  bnd.absorbing = locate_entities_boundary(
      *mesh, 1,
      [&](auto& x) -> xt::xtensor<bool, 1> {
        return xt::isclose(xt::row(x, 0), 0.0) || xt::isclose(xt::row(x, 0), L);
      });
  ac::WaveParameters wave;
  const double dt = 1e-5;
  ac::WaveSolver s(mesh, 1, false, wave, bnd, dt);
  const std::size_t src = s.add_volume_source(
      [&](double x, double)
      {
        const double u = (x - xs) / 0.005;
        return std::abs(u) < 1 ? std::pow(std::cos(0.5 * M_PI * u), 2) : 0.0;
      });
  s.set_volume_source_rate(src, 2.0);
  CHECK(load_on(s, [](double, double) { return 1.0; })
        == Approx(wave.rho0 * 2.0).epsilon(1e-12));
  CHECK_THROWS_AS(s.add_volume_source([](double, double) { return 0.0; }),
                  fsai::InputError);
  // No r weight: an axisymmetric model refuses it
  ac::WaveSolver axi(mesh, 1, true, wave, bnd, dt);
  CHECK_THROWS_AS(axi.add_volume_source([](double, double) { return 1.0; }),
                  fsai::InputError);
  auto Q
      = [&](double t) { return Q0 * std::exp(-std::pow((t - t0) / tau, 2)); };
  auto dQ = [&](double t) { return -2 * (t - t0) / (tau * tau) * Q(t); };
  fsai::io::PointProbes probe(mesh, {{0.3, 0.5 * W, 0.0}, {0.1, 0.5 * W, 0.0}});
  double err = 0.0, peak = 0.0, back = 0.0;
  for (int k = 1; k <= 200; ++k)
  {
    s.set_volume_source_rate(src, dQ(k * dt));
    s.step();
    const auto p = probe.values(*s.pressure());
    const double exact
        = wave.rho0 * wave.c0 * Q(k * dt - 0.1 / wave.c0) / (2 * W);
    err = std::max(err, std::abs(p[0] - exact));
    peak = std::max(peak, exact);
    back = std::max(back, std::abs(p[1] - p[0]));
  }
  fsai::log::info("Volume source in a duct: max error {:.2e} of the peak "
                  "{:.3f} Pa; left - right {:.1e}",
                  err / peak, peak, back / peak);
  CHECK(err < 0.01 * peak);
  CHECK(back < 0.01 * peak);
}

TEST_CASE("1D time-domain tract: resonances of the chain-matrix model (A9)",
          "[acoustics]")
{
  // The transmission line stepped in time, driven by a short glottal flow
  // pulse: the peaks of P_lips/U_g are the chain-matrix model's (A7, same
  // walls, the flanged load it approximates by R ∥ L_r) for the three
  // vowels, and a rigid closed-open tube rings at (2n−1) c0 / 4L
  namespace ac = fsai::acoustics;
  const std::string vowel
      = GENERATE(std::string("u"), std::string("a"), std::string("i"));
  CAPTURE(vowel);
  const auto af = fsai::mesh::read_area_function(fsai::mesh::vowel_file(vowel));
  ac::TubeTractParameters p;
  p.wall = {15.0, 1.6e4, 3e6, 0.018};
  const double dt = 2e-5, tau = 1e-4;
  ac::TubeTract tract(af, p, dt);
  std::vector<double> ug, pl;
  for (int k = 0; k < 8000; ++k)
  {
    const double t = (k + 1) * dt;
    const double u = 1e-4 * std::exp(-std::pow((t - 5 * tau) / tau, 2));
    tract.step(u);
    ug.push_back(u);
    pl.push_back(tract.p_lips());
    REQUIRE(std::isfinite(tract.p_lips()));
  }
  const auto tf = ac::transfer_function(ug, pl, dt, 1e300, 4);
  std::vector<double> mag;
  for (const auto& h : tf.h)
    mag.push_back(std::abs(h));
  const auto peaks = ac::find_peaks(tf.f, mag, 100.0, 3500.0);
  const auto ref
      = ac::tube_resonances(fsai::mesh::resample(af, true, 5e-4), 3500.0, p.c0,
                            p.rho0, ac::LipEnd::flanged, -1.0, p.wall);
  REQUIRE(peaks.size() >= 3);
  REQUIRE(ref.size() >= 3);
  for (int n = 0; n < 3; ++n)
  {
    // The nearest peak: the line also shows the chain model's weak ones
    // that its own peak search drops (for [u] a back-cavity peak at
    // 1576 Hz, 96 dB against F2's 130 dB in both models)
    auto near = std::min_element(
        peaks.begin(), peaks.end(),
        [&](const auto& x, const auto& y)
        { return std::abs(x.f - ref[n].f) < std::abs(y.f - ref[n].f); });
    fsai::log::info("1D time-domain [{}] F{} = {:.1f} Hz, chain matrix "
                    "{:.1f} Hz (B {:.0f}): {:+.2f} %",
                    vowel, n + 1, near->f, ref[n].f, ref[n].bandwidth,
                    100 * (near->f - ref[n].f) / ref[n].f);
    // F3 of [i] (3.2 kHz, ka 0.5) is where R ∥ L_r departs most from the
    // low-ka formula it matches: +1.05 %
    CHECK(near->f == Approx(ref[n].f).epsilon(n < 2 ? 0.005 : 0.02));
  }
}

TEST_CASE("Monopole microphone: the lip flow's rate delayed by r/c0 (A9, A11)",
          "[acoustics]")
{
  // U̇_L = sin(ωt) recorded at the steps' ends (lag 0) or midpoints (lag ½):
  // the microphone at r hears ρ0 sin(ω(t − r/c0)) / (2π r), the delay
  // between recorded values interpolated linearly
  namespace ac = fsai::acoustics;
  const double r = 0.3, c0 = 343.0, rho0 = 1.2, dt = 2e-5;
  const double w = 2 * M_PI * 300.0;
  const double lag = GENERATE(0.0, 0.5);
  ac::MonopoleMicrophone mic(r, c0, rho0, dt, lag);
  double err = 0;
  for (int k = 1; k <= 2000; ++k)
  {
    const double t = k * dt;
    mic.record(std::sin(w * (t - lag * dt)));
    if (t > r / c0 + 2 * dt)
    {
      const double exact = rho0 * std::sin(w * (t - r / c0)) / (2 * M_PI * r);
      err = std::max(err, std::abs(mic.pressure() - exact));
    }
  }
  // Linear interpolation: error ≤ (ω Δt)²/8 of the amplitude
  CHECK(err <= rho0 / (2 * M_PI * r) * std::pow(w * dt, 2) / 8 * 1.01);
  // A checkpoint's history gives the same pressure
  ac::MonopoleMicrophone copy(r, c0, rho0, dt, lag);
  copy.load(mic.save());
  CHECK(copy.pressure() == mic.pressure());
}
