// Copyright (C) 2026 fsai developers
// Flow (shared/DESIGN.md E11a): the penalty inlet tends to the Dirichlet
// inflow as ε → 0 and to a pressure inlet as ε → ∞ (Poiseuille channel).
#include "catch.h"
#include <common/log.h>
#include <dolfinx/mesh/generation.h>
#include <dolfinx/mesh/utils.h>
#include <fluid/FluidSolver.h>
#include <xtensor/xview.hpp>

namespace
{
struct Channel
{
  std::shared_ptr<dolfinx::mesh::Mesh> mesh;
  std::vector<std::int32_t> inlet, outlet, walls;
};

/// [0, L] x [0, H] channel, structured triangles
Channel channel(double L, double H, std::size_t nx, std::size_t ny)
{
  using namespace dolfinx::mesh;
  Channel c;
  c.mesh = std::make_shared<Mesh>(
      create_rectangle(MPI_COMM_WORLD, {{{0, 0}, {L, H}}}, {nx, ny},
                       CellType::triangle, GhostMode::shared_facet));
  c.mesh->topology_mutable().create_connectivity(1, 2);
  auto at = [&](int axis, double v)
  {
    return locate_entities_boundary(*c.mesh, 1,
                                    [=](auto& x) -> xt::xtensor<bool, 1> {
                                      return xt::isclose(xt::row(x, axis), v);
                                    });
  };
  c.inlet = at(0, 0.0);
  c.outlet = at(0, L);
  c.walls = at(1, 0.0);
  auto top = at(1, H);
  c.walls.insert(c.walls.end(), top.begin(), top.end());
  return c;
}

/// Steady flow rate through the outlet
double outlet_flow(const Channel& c, fsai::fluid::FluidParameters p,
                   bool dirichlet, double Umax, double H)
{
  fsai::fluid::FluidBoundaries b;
  (dirichlet ? b.inlet_dirichlet : b.inlet_penalty) = c.inlet;
  b.outlet = c.outlet;
  b.walls = c.walls;
  fsai::fluid::FluidSolver flow(c.mesh, b, p, 1.0);
  flow.inlet_velocity().interpolate(
      [&](auto& x) -> xt::xarray<double>
      {
        xt::xarray<double> v = xt::zeros<double>({std::size_t(2), x.shape(1)});
        for (std::size_t i = 0; i < x.shape(1); ++i)
          v(0, i) = 4 * Umax * x(1, i) * (H - x(1, i)) / (H * H);
        return v;
      });
  flow.solve_steady(100);
  return flow.flow_rate(c.outlet);
}
} // namespace

TEST_CASE("Penalty inlet: small epsilon reproduces the Dirichlet inflow",
          "[fluid][mpi]")
{
  const double L = 1.0, H = 0.2, Umax = 0.01;
  auto c = channel(L, H, 50, 20);
  fsai::fluid::FluidParameters p;
  p.rho = 1.0;
  p.mu = 1e-2;
  const double q_dir = outlet_flow(c, p, true, Umax, H);
  p.inlet_eps = 1e-8;
  const double q_pen = outlet_flow(c, p, false, Umax, H);
  const double q_exact = 2.0 / 3.0 * Umax * H;
  fsai::log::info("Fluid penalty inlet eps=1e-8: Q = {:.8e}, Dirichlet {:.8e} "
                  "(exact {:.8e})",
                  q_pen, q_dir, q_exact);
  // The P1 interpolant of the parabola carries 1/ny² = 0.25 % less flux
  CHECK(q_dir == Approx(q_exact * (1 - 1.0 / 400)).epsilon(1e-4));
  CHECK(q_pen == Approx(q_dir).epsilon(1e-5));
}

TEST_CASE("Penalty inlet: large epsilon gives the pressure-driven flow",
          "[fluid][mpi]")
{
  // Poiseuille: Q = Δp H³ / (12 μ L) per unit depth, Δp = p_in − p_out
  // (P1 PSPG drops −μΔv from the momentum residual: an O(h²) error, +3.0 %
  // with 0.02 m cells, +0.22 % with 0.005 m cells)
  const double L = 1.0, H = 0.2, dp = 0.01;
  auto c = channel(L, H, 200, 40);
  fsai::fluid::FluidParameters p;
  p.rho = 1.0;
  p.mu = 1e-2;
  p.inlet_eps = 1e8;
  p.p_in = dp;
  const double q = outlet_flow(c, p, false, 0.0, H);
  const double q_exact = dp * H * H * H / (12 * p.mu * L);
  fsai::log::info("Fluid penalty inlet eps=1e8, p_in = {}: Q = {:.6e} "
                  "(Poiseuille {:.6e}, {:+.3f}%)",
                  dp, q, q_exact, 100 * (q / q_exact - 1));
  CHECK(q == Approx(q_exact).epsilon(0.01));
}
