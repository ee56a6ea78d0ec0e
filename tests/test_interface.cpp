// Copyright (C) 2026 fsai developers
// Fluid–solid interface (Turek–Hron FSI geometry, one gmsh model, two
// meshes): the parts share their interface vertices, and InterfaceMap moves
// fields across exactly — a quadratic solid field (P2) to the fluid's
// vertices, a linear fluid field (P1) to the solid's P2 dofs — on any
// partitioning.
#include "catch.h"
#include <common/log.h>
#include <coupling/InterfaceMap.h>
#include <dolfinx/fem/FunctionSpace.h>
#include <dolfinx/fem/utils.h>
#include <fsai_forms/ale.h>
#include <fsai_forms/structure.h>
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
