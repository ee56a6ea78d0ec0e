// Copyright (C) 2026 fsai developers
// Fluid–solid interface (Turek–Hron FSI geometry, one gmsh model, two
// meshes): the parts share their interface vertices, and InterfaceMap moves
// fields across exactly — a quadratic solid field (P2) to the fluid's
// vertices, a linear fluid field (P1) to the solid's P2 dofs — on any
// partitioning.
#include "catch.h"
#include <ale/MeshMotion.h>
#include <common/log.h>
#include <coupling/InterfaceMap.h>
#include <coupling/PartitionedFsi.h>
#include <dolfinx/fem/FunctionSpace.h>
#include <dolfinx/fem/utils.h>
#include <fsai_forms/ale.h>
#include <fsai_forms/structure.h>
#include <io/PointProbes.h>
#include <io/TimeSeriesWriter.h>
#include <mesh/benchmarks.h>

TEST_CASE("Turek-Hron FSI meshes share the interface; InterfaceMap "
          "transfers fields exactly",
          "[coupling][mesh][mpi]")
{
  auto [fluid, solid] = fsai::mesh::turek_hron_fsi(MPI_COMM_WORLD, 0.05, 0.005);
  auto Vf = std::make_shared<dolfinx::fem::FunctionSpace>(
      dolfinx::fem::create_functionspace(
          fsai::forms::ale::functionspace_a(2, 1), "d", fluid.mesh));
  auto Vs = std::make_shared<dolfinx::fem::FunctionSpace>(
      dolfinx::fem::create_functionspace(
          fsai::forms::structure::functionspace_R(2, 2), "u", solid.mesh));
  auto fi = fluid.facet_tags->find(fluid.facet_tag("interface"));
  auto si = solid.facet_tags->find(solid.facet_tag("interface"));
  fsai::coupling::InterfaceMap map(*Vf, fi, *Vs, si);

  // Interface sizes (owned dofs, summed over ranks)
  auto owned = [](const std::vector<std::int32_t>& dofs,
                  const dolfinx::fem::FunctionSpace& V)
  {
    std::int64_t n = 0;
    for (auto d : dofs)
      n += d < V.dofmap()->index_map->size_local();
    MPI_Allreduce(MPI_IN_PLACE, &n, 1, MPI_INT64_T, MPI_SUM, MPI_COMM_WORLD);
    return n;
  };
  const std::int64_t nf = owned(map.fluid_dofs(), *Vf),
                     ns = owned(map.solid_dofs(), *Vs);

  // Quadratic solid field -> fluid vertices
  auto q = [](double x, double y) -> std::array<double, 2> {
    return {x * x - 0.3 * x * y, 2 * y * y + x};
  };
  dolfinx::fem::Function<double> us(Vs), uf(Vf), tf(Vf), ts(Vs);
  us.interpolate(
      [&](auto& x) -> xt::xarray<double>
      {
        xt::xarray<double> v = xt::zeros<double>({std::size_t(2), x.shape(1)});
        for (std::size_t i = 0; i < x.shape(1); ++i)
        {
          auto e = q(x(0, i), x(1, i));
          v(0, i) = e[0], v(1, i) = e[1];
        }
        return v;
      });
  map.solid_to_fluid(us, uf);
  const auto Xf = Vf->tabulate_dof_coordinates(false);
  double err = 0;
  for (auto d : map.fluid_dofs())
  {
    auto e = q(Xf[3 * d], Xf[3 * d + 1]);
    err = std::max({err, std::abs(uf.x()->array()[2 * d] - e[0]),
                    std::abs(uf.x()->array()[2 * d + 1] - e[1])});
  }
  // Linear fluid field -> solid P2 interface dofs (midpoints exact)
  auto l = [](double x, double y) -> std::array<double, 2> {
    return {1 + 2 * x - 3 * y, 0.5 * x + y};
  };
  tf.interpolate(
      [&](auto& x) -> xt::xarray<double>
      {
        xt::xarray<double> v = xt::zeros<double>({std::size_t(2), x.shape(1)});
        for (std::size_t i = 0; i < x.shape(1); ++i)
        {
          auto e = l(x(0, i), x(1, i));
          v(0, i) = e[0], v(1, i) = e[1];
        }
        return v;
      });
  map.fluid_to_solid(tf, ts);
  const auto Xs = Vs->tabulate_dof_coordinates(false);
  double err2 = 0;
  for (auto d : map.solid_dofs())
  {
    auto e = l(Xs[3 * d], Xs[3 * d + 1]);
    err2 = std::max({err2, std::abs(ts.x()->array()[2 * d] - e[0]),
                     std::abs(ts.x()->array()[2 * d + 1] - e[1])});
  }
  double g[2] = {err, err2};
  MPI_Allreduce(MPI_IN_PLACE, g, 2, MPI_DOUBLE, MPI_MAX, MPI_COMM_WORLD);
  fsai::log::info("Turek-Hron FSI meshes: {} fluid / {} solid (P2) interface "
                  "dofs; solid->fluid error {:.1e}, fluid->solid error {:.1e}",
                  nf, ns, g[0], g[1]);
  // P2 has a midside dof per interface edge: (fluid vertices − 2 ends) + 1
  // edges on the open interface polyline
  CHECK(ns == 2 * nf - 1);
  CHECK(g[0] < 1e-12);
  CHECK(g[1] < 1e-12);
  // The parts: the fluid has no "clamped" facets, the solid no "inlet"
  CHECK(fluid.facet_tags->find(fluid.facet_tag("clamped")).empty());
}

TEST_CASE("3D flap in a channel: the partitioned FSI step converges (IQN-ILS) "
          "and the flap bends downstream",
          "[coupling][fsi][mpi]")
{
  auto [fm, sm] = fsai::mesh::channel_flap_3d(MPI_COMM_WORLD, 0.05);
  auto f_if = fm.facet_tags->find(fm.facet_tag("interface"));
  fsai::fluid::FluidBoundaries fb;
  fb.inlet_dirichlet = fm.facet_tags->find(fm.facet_tag("inlet"));
  fb.outlet = fm.facet_tags->find(fm.facet_tag("outlet"));
  fb.walls = fm.facet_tags->find(fm.facet_tag("walls"));
  fb.walls.insert(fb.walls.end(), f_if.begin(), f_if.end());
  fsai::fluid::FluidParameters fp;
  fp.rho = 1.0;
  fp.mu = 0.01;
  const double dt = 0.05;
  fsai::fluid::FluidSolver flow(fm.mesh, fb, fp, dt);
  fsai::structure::SolidParameters sp;
  sp.model = "svk";
  sp.degree = 2;
  sp.material = {5e3, 0.3, 100.0};
  fsai::structure::ElasticSolver solid(
      sm.mesh, sm.facet_tags->find(sm.facet_tag("clamped")),
      sm.facet_tags->find(sm.facet_tag("interface")), sp, dt);
  fsai::ale::MeshMotionBoundaries mb;
  mb.interface = f_if;
  mb.fixed = fb.inlet_dirichlet;
  for (auto* f : {&fb.outlet, &fb.walls})
    mb.fixed.insert(mb.fixed.end(), f->begin(), f->end());
  fsai::ale::MeshMotion motion(fm.mesh, flow.velocity_space(), mb, {});
  fsai::coupling::InterfaceMap imap(
      *flow.velocity_space(), f_if, *solid.space(),
      sm.facet_tags->find(sm.facet_tag("interface")));
  fsai::coupling::CouplingParameters cp;
  cp.atol = 1e-10;
  fsai::coupling::PartitionedFsi fsi(flow, solid, motion, imap, f_if, cp, "");
  fsai::io::PointProbes tip(sm.mesh, {{0.425, 0.25, 0.2}});
  int its = 0;
  for (int k = 1; k <= 6; ++k)
  {
    const double s = std::min(1.0, k * dt / 0.2); // inflow ramp over 0.2 s
    flow.inlet_velocity().interpolate(
        [&](auto& x) -> xt::xarray<double>
        {
          xt::xarray<double> v
              = xt::zeros<double>({std::size_t(3), x.shape(1)});
          for (std::size_t i = 0; i < x.shape(1); ++i)
            v(0, i) = s * 16 * x(1, i) * (0.4 - x(1, i)) * x(2, i)
                      * (0.4 - x(2, i)) / std::pow(0.4, 4);
          return v;
        });
    auto rep = fsi.step(k * dt);
    CHECK(rep.converged);
    its += rep.iterations;
  }
  auto u = tip.values(*solid.displacement());
  fsai::log::info("3D flap FSI ({} fluid dofs): 6 steps, {} coupling "
                  "iterations, tip displacement ({:.3e}, {:.3e}, {:.3e}) m",
                  flow.dofs(), its, u[0], u[1], u[2]);
  fsai::io::TimeSeriesWriter(
      "fsi3d_flow.xdmf",
      {flow.velocity(), flow.pressure(), motion.displacement()})
      .write(6 * dt);
  CHECK(u[0] > 1e-4);
  CHECK(std::abs(u[2]) < 0.1 * u[0]); // symmetric about z = 0.2
}
