// Copyright (C) 2026 fsai developers
// gmsh-built meshes: physical groups become DOLFINx tags with the right
// measures, in serial and distributed; .geo files and XDMF round trips keep
// them
#include "catch.h"
#include <array>
#include <cmath>
#include <common/errors.h>
#include <dolfinx/common/IndexMap.h>
#include <dolfinx/fem/FunctionSpace.h>
#include <dolfinx/fem/utils.h>
#include <dolfinx/mesh/utils.h>
#include <filesystem>
#include <fsai_forms/ale.h>
#include <mesh/TriangleField.h>
#include <mesh/builders.h>
#include <mesh/gmsh_model.h>
#include <mesh/xdmf_mesh.h>

namespace
{
/// Measure (length, area, volume) of a simplex given its vertices
double simplex_measure(const std::vector<std::array<double, 3>>& p)
{
  auto sub = [](auto a, auto b) {
    return std::array<double, 3>{a[0] - b[0], a[1] - b[1], a[2] - b[2]};
  };
  auto cross = [](auto a, auto b)
  {
    return std::array<double, 3>{a[1] * b[2] - a[2] * b[1],
                                 a[2] * b[0] - a[0] * b[2],
                                 a[0] * b[1] - a[1] * b[0]};
  };
  auto norm = [](auto a)
  { return std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]); };
  auto u = sub(p[1], p[0]);
  if (p.size() == 2)
    return norm(u);
  auto c = cross(u, sub(p[2], p[0]));
  if (p.size() == 3)
    return 0.5 * norm(c);
  auto w = sub(p[3], p[0]);
  return std::abs(c[0] * w[0] + c[1] * w[1] + c[2] * w[2]) / 6.0;
}

/// Total measure of the owned entities of dimension `dim` tagged `tag`
/// (all entities if tags is null), summed over ranks
double tagged_measure(const dolfinx::mesh::Mesh& mesh, int dim,
                      const dolfinx::mesh::MeshTags<std::int32_t>* tags,
                      int tag)
{
  const std::int32_t owned = mesh.topology().index_map(dim)->size_local();
  std::vector<std::int32_t> entities;
  if (tags)
  {
    for (std::int32_t e : tags->find(tag))
      if (e < owned)
        entities.push_back(e);
  }
  else
  {
    for (std::int32_t e = 0; e < owned; ++e)
      entities.push_back(e);
  }
  const int nv = dim + 1;
  std::vector<std::int32_t> g
      = dolfinx::mesh::entities_to_geometry(mesh, dim, entities, false);
  std::span<const double> x = mesh.geometry().x();
  double local = 0.0;
  for (std::size_t i = 0; i < entities.size(); ++i)
  {
    std::vector<std::array<double, 3>> p(nv);
    for (int j = 0; j < nv; ++j)
      for (int k = 0; k < 3; ++k)
        p[j][k] = x[3 * g[i * nv + j] + k];
    local += simplex_measure(p);
  }
  double global = 0.0;
  MPI_Allreduce(&local, &global, 1, MPI_DOUBLE, MPI_SUM, mesh.comm());
  return global;
}

void check_rectangle_tags(const fsai::mesh::MeshData& m, double lx, double ly)
{
  const int tdim = m.mesh->topology().dim();
  REQUIRE(m.facet_tags);
  REQUIRE(m.cell_tags);
  const double tol = 1e-12;
  CHECK(tagged_measure(*m.mesh, 1, m.facet_tags.get(), m.facet_tag("left"))
        == Approx(ly).epsilon(tol));
  CHECK(tagged_measure(*m.mesh, 1, m.facet_tags.get(), m.facet_tag("right"))
        == Approx(ly).epsilon(tol));
  CHECK(tagged_measure(*m.mesh, 1, m.facet_tags.get(), m.facet_tag("bottom"))
        == Approx(lx).epsilon(tol));
  CHECK(tagged_measure(*m.mesh, 1, m.facet_tags.get(), m.facet_tag("top"))
        == Approx(lx).epsilon(tol));
  CHECK(tagged_measure(*m.mesh, tdim, m.cell_tags.get(), m.cell_tag("domain"))
        == Approx(lx * ly).epsilon(tol));
  CHECK(tagged_measure(*m.mesh, tdim, nullptr, 0)
        == Approx(lx * ly).epsilon(tol));
}
} // namespace

TEST_CASE("gmsh rectangle: facet groups have the side lengths", "[mesh][mpi]")
{
  auto m
      = fsai::mesh::rectangle(MPI_COMM_WORLD, {0.0, -0.01}, {0.2, 0.01}, 0.004);
  check_rectangle_tags(m, 0.2, 0.02);
  CHECK_THROWS_WITH(m.facet_tag("inlet"), Catch::Contains("left"));
}

TEST_CASE("gmsh box: facet groups have the face areas", "[mesh][mpi]")
{
  auto m = fsai::mesh::box(MPI_COMM_WORLD, {0, 0, 0}, {2.0, 1.0, 0.5}, 0.25);
  const std::map<std::string, double> area
      = {{"xmin", 0.5}, {"xmax", 0.5}, {"ymin", 1.0},
         {"ymax", 1.0}, {"zmin", 2.0}, {"zmax", 2.0}};
  for (auto& [name, a] : area)
  {
    CAPTURE(name);
    CHECK(tagged_measure(*m.mesh, 2, m.facet_tags.get(), m.facet_tag(name))
          == Approx(a).epsilon(1e-12));
  }
  CHECK(tagged_measure(*m.mesh, 3, m.cell_tags.get(), 1)
        == Approx(1.0).epsilon(1e-12));
}

TEST_CASE("Mesh builders reject bad sizes with InputError", "[mesh]")
{
  CHECK_THROWS_AS(fsai::mesh::rectangle(MPI_COMM_WORLD, {0, 0}, {1, 1}, -0.1),
                  fsai::InputError);
  CHECK_THROWS_AS(fsai::mesh::rectangle(MPI_COMM_WORLD, {0, 0}, {1, 1}, 1e-7),
                  fsai::InputError);
  CHECK_THROWS_AS(fsai::mesh::box(MPI_COMM_WORLD, {0, 0, 0}, {1, -1, 1}, 0.1),
                  fsai::InputError);
}

TEST_CASE(".geo file and XDMF round trip keep tags and names", "[mesh][mpi]")
{
  auto m = fsai::mesh::from_geo_file(
      MPI_COMM_WORLD, std::string(FSAI_SOURCE_DIR) + "/meshes/unit_square.geo",
      2, 0.05);
  check_rectangle_tags(m, 1.0, 1.0);

  fsai::test::TempDir dir;
  const std::string path = dir / "square.xdmf";
  fsai::mesh::write_xdmf(path, m);
  auto r = fsai::mesh::read_xdmf(MPI_COMM_WORLD, path);
  CHECK(r.facet_names == m.facet_names);
  CHECK(r.cell_names == m.cell_names);
  check_rectangle_tags(r, 1.0, 1.0);
  CHECK(r.mesh->topology().index_map(2)->size_global()
        == m.mesh->topology().index_map(2)->size_global());

  CHECK_THROWS_AS(fsai::mesh::read_xdmf(MPI_COMM_WORLD, "/nonexistent.xdmf"),
                  fsai::InputError);
  CHECK_THROWS_AS(
      fsai::mesh::from_geo_file(MPI_COMM_WORLD, "/nonexistent.geo", 2),
      fsai::InputError);
}

TEST_CASE("Remeshing transfer: P1 fields onto another triangulation",
          "[mesh][mpi]")
{
  // Two unrelated triangulations of the unit square (the flow's meshes
  // before and after a remeshing, docs/model.md E13a)
  MPI_Comm comm = MPI_COMM_WORLD;
  auto a = fsai::mesh::rectangle(comm, {0, 0}, {1, 1}, 0.05);
  auto b = fsai::mesh::rectangle(comm, {0, 0}, {1, 1}, 0.037);
  auto space = [](std::shared_ptr<dolfinx::mesh::Mesh> m)
  {
    return std::make_shared<dolfinx::fem::FunctionSpace>(
        dolfinx::fem::create_functionspace(
            fsai::forms::ale::functionspace_a(2, 1), "d", m));
  };
  const double pi = std::acos(-1.0);
  // A linear field (reproduced exactly) and the divergence-free field of
  // the stream function sin(πx) sin(πy)
  auto linear = [](double x, double y) {
    return std::array<double, 2>{1 + 2 * x - 3 * y, 0.5 * x + y};
  };
  auto vortex = [&](double x, double y)
  {
    return std::array<double, 2>{pi * std::sin(pi * x) * std::cos(pi * y),
                                 -pi * std::cos(pi * x) * std::sin(pi * y)};
  };
  auto sample = [](const dolfinx::fem::FunctionSpace& V, auto f)
  {
    const auto X = V.tabulate_dof_coordinates(false);
    std::vector<double> out;
    for (std::size_t i = 0; i < X.size() / 3; ++i)
    {
      const auto v = f(X[3 * i], X[3 * i + 1]);
      out.insert(out.end(), {v[0], v[1]});
    }
    return out;
  };
  const auto Va = space(a.mesh), Vb = space(b.mesh);
  const auto la = sample(*Va, linear), va = sample(*Va, vortex);
  const auto from_a = fsai::mesh::TriangleField::gather(comm, *Va, {la, va});
  REQUIRE(from_a.components() == 4);
  // Onto b's nodes
  const auto Xb = Vb->tabulate_dof_coordinates(false);
  std::vector<double> vb;
  double err_linear = 0;
  for (std::size_t i = 0; i < Xb.size() / 3; ++i)
  {
    const auto f = from_a({Xb[3 * i], Xb[3 * i + 1]});
    const auto l = linear(Xb[3 * i], Xb[3 * i + 1]);
    err_linear
        = std::max({err_linear, std::abs(f[0] - l[0]), std::abs(f[1] - l[1])});
    vb.insert(vb.end(), {f[2], f[3]});
  }
  CHECK(err_linear < 1e-12);
  // The transferred vortex carries the same flux through the section
  // y = 1/2, 0 ≤ x ≤ 1/2 (exactly −1) as the field it came from
  const auto from_b = fsai::mesh::TriangleField::gather(comm, *Vb, {vb});
  auto flux = [](const fsai::mesh::TriangleField& f, int c)
  {
    const int n = 4000;
    double q = 0;
    for (int k = 0; k < n; ++k)
      q += f({(k + 0.5) * 0.5 / n, 0.5})[c] * 0.5 / n;
    return q;
  };
  const double qa = flux(from_a, 3), qb = flux(from_b, 1);
  CHECK(std::abs(qa + 1) < 5e-3);
  CHECK(std::abs(qb - qa) < 2e-3);
  // A point just outside (a curved wall meshed twice) takes the value at
  // the nearest point of the triangulation
  CHECK(from_a.distance({1 + 1e-4, 0.3}) == Approx(1e-4).epsilon(1e-6));
  const auto edge = from_a({1 + 1e-4, 0.3}), at = from_a({1, 0.3});
  CHECK(edge[0] == Approx(at[0]).margin(1e-12));
}
