// Copyright (C) 2026 fsai developers
// ALE mesh motion (docs/model.md E13, src/ale/MeshMotion): affine
// boundary motion is reproduced exactly, x = X + d has no drift, the mesh
// velocity is the BDF derivative, and in a squeezing glottal gap the plain
// harmonic extension inverts cells where the stiffened extension does not.
#include "catch.h"
#include <ale/MeshMotion.h>
#include <cmath>
#include <common/log.h>
#include <dolfinx/fem/FunctionSpace.h>
#include <dolfinx/fem/utils.h>
#include <fsai_forms/ale.h>
#include <gmsh.h>
#include <mesh/builders.h>
#include <mesh/gmsh_model.h>

namespace
{
/// P1 vector space of the ALE form on `mesh`
std::shared_ptr<const dolfinx::fem::FunctionSpace>
p1_space(std::shared_ptr<dolfinx::mesh::Mesh> mesh)
{
  const int tdim = mesh->topology().dim();
  return std::make_shared<dolfinx::fem::FunctionSpace>(
      dolfinx::fem::create_functionspace(
          fsai::forms::ale::functionspace_a(tdim, 1), "d", mesh));
}

/// Set the interface displacement from its reference dof coordinates
void set_interface(
    fsai::ale::MeshMotion& m, const std::vector<double>& X,
    const std::function<std::array<double, 2>(double, double)>& d)
{
  auto a = m.interface_displacement().x()->mutable_array();
  for (std::size_t i = 0; i < X.size() / 3; ++i)
  {
    auto v = d(X[3 * i], X[3 * i + 1]);
    a[2 * i] = v[0], a[2 * i + 1] = v[1];
  }
}

// Squeezing gap (glottis-like, in mm): half channel [0, 12] x [0, 3] with
// the symmetry axis y = 0; a fold protrudes from the top wall between x = 4
// and 8, y_f = 3 − (3 − g0) sin²(π(x − 4)/4), tip at x = 6 (radius of
// curvature ≈ 0.3 mm); cells of size h_gap at the fold, 0.25 mm far away.
constexpr double mm = 1e-3;
fsai::mesh::MeshData squeezing_gap(double g0, double h_gap)
{
  return fsai::mesh::build_with_gmsh(
      MPI_COMM_WORLD, 2,
      [&]()
      {
        namespace geo = gmsh::model::geo;
        gmsh::model::add("gap");
        const double L = 12 * mm, H = 3 * mm;
        const int a = geo::addPoint(0, 0, 0), b = geo::addPoint(L, 0, 0),
                  c = geo::addPoint(L, H, 0), e = geo::addPoint(0, H, 0);
        std::vector<int> fold;
        for (int i = 0; i <= 60; ++i)
        {
          const double x = 8 * mm - 4 * mm * i / 60.0;
          const double s = std::sin(M_PI * (x - 4 * mm) / (4 * mm));
          fold.push_back(geo::addPoint(x, H - (H - g0) * s * s, 0));
        }
        const int axis = geo::addLine(a, b), outlet = geo::addLine(b, c),
                  top_r = geo::addLine(c, fold.front()),
                  surface = geo::addSpline(fold),
                  top_l = geo::addLine(fold.back(), e),
                  inlet = geo::addLine(e, a);
        const int loop
            = geo::addCurveLoop({axis, outlet, top_r, surface, top_l, inlet});
        geo::addPlaneSurface({loop});
        geo::synchronize();
        gmsh::model::addPhysicalGroup(1, {axis}, 1);
        gmsh::model::setPhysicalName(1, 1, "axis");
        gmsh::model::addPhysicalGroup(1, {inlet, outlet, top_r, top_l}, 2);
        gmsh::model::setPhysicalName(1, 2, "walls");
        gmsh::model::addPhysicalGroup(1, {surface}, 3);
        gmsh::model::setPhysicalName(1, 3, "fold");
        gmsh::model::addPhysicalGroup(2, {1}, 1);
        gmsh::model::setPhysicalName(2, 1, "fluid");
        fsai::mesh::size_near_curves({surface}, h_gap, 0.25 * mm, 1.5 * mm,
                                     400);
        gmsh::model::mesh::generate(2);
      });
}

/// Close the gap to the fraction `closure` of g0 in `steps` moves: the fold
/// translates towards the axis and rotates (swing of the 2-DOF fold, tip
/// ahead), tapered to zero where it meets the wall. Returns the smallest
/// quality met, or −1 if a move threw MeshInvertedError.
double squeeze(const fsai::mesh::MeshData& m, double g0,
               fsai::ale::MeshMotionParameters p, double closure, int steps,
               double* reached = nullptr)
{
  auto mesh = m.mesh;
  auto V = p1_space(mesh);
  fsai::ale::MeshMotionBoundaries bnd;
  bnd.interface = m.facet_tags->find(m.facet_tag("fold"));
  bnd.fixed = m.facet_tags->find(m.facet_tag("walls"));
  bnd.slip = {{1, m.facet_tags->find(m.facet_tag("axis"))}};
  // The reference geometry is restored afterwards: the mesh is shared
  const std::vector<double> x0(mesh->geometry().x().begin(),
                               mesh->geometry().x().end());
  double qmin = 1;
  {
    fsai::ale::MeshMotion motion(mesh, V, bnd, p);
    const std::vector<double> X = V->tabulate_dof_coordinates(false);
    const double phi_max = 0.15; // rad, about the fold's root (6, 3) mm
    try
    {
      for (int n = 1; n <= steps; ++n)
      {
        const double s = closure * n / steps;
        set_interface(
            motion, X,
            [&](double x, double y) -> std::array<double, 2>
            {
              const double w
                  = std::pow(std::sin(M_PI * (x - 4 * mm) / (4 * mm)), 2);
              const double phi = phi_max * s, rx = x - 6 * mm, ry = y - 3 * mm;
              return {
                  w * (std::cos(phi) * rx - std::sin(phi) * ry - rx),
                  w * (std::sin(phi) * rx + std::cos(phi) * ry - ry - s * g0)};
            });
        qmin = std::min(qmin, motion.move(n).min_scaled_jacobian);
        if (reached)
          *reached = s;
      }
    }
    catch (const fsai::ale::MeshInvertedError& e)
    {
      fsai::log::info("{}", e.what());
      qmin = -1;
    }
  }
  std::copy(x0.begin(), x0.end(), mesh->geometry().x().begin());
  return qmin;
}
} // namespace

TEST_CASE("ALE: affine boundary motion is extended exactly, without drift, "
          "with the BDF mesh velocity",
          "[ale][mpi]")
{
  auto m = fsai::mesh::rectangle(MPI_COMM_WORLD, {0, 0}, {2, 1}, 0.1);
  auto mesh = m.mesh;
  auto V = p1_space(mesh);
  std::vector<std::int32_t> all;
  for (auto& [name, tag] : m.facet_names)
  {
    auto f = m.facet_tags->find(tag);
    all.insert(all.end(), f.begin(), f.end());
  }
  const std::vector<double> x0(mesh->geometry().x().begin(),
                               mesh->geometry().x().end());
  for (std::string method : {"harmonic", "elastic"})
  {
    fsai::ale::MeshMotionParameters p;
    p.method = method;
    p.stiffening = "none"; // a cell-wise k does not keep affine fields exact
    fsai::ale::MeshMotion motion(mesh, V, {all, {}, {}, {}}, p);
    const std::vector<double> X = V->tabulate_dof_coordinates(false);
    // d(X, t) = G(t) X + c(t): affine, so the extension is exact
    auto d = [](double x, double y, double t) -> std::array<double, 2>
    {
      return {0.1 * t * x - 0.05 * t * t * y + 0.01 * t,
              0.03 * t * x + 0.2 * t * y};
    };
    const double dt = 0.1;
    fsai::ale::MeshMotion* mo = &motion;
    dolfinx::fem::Function<double> w(
        std::const_pointer_cast<dolfinx::fem::FunctionSpace>(V));
    double err_d = 0, err_w = 0;
    for (int n = 1; n <= 3; ++n)
    {
      const double t = n * dt;
      set_interface(*mo, X, [&](double x, double y) { return d(x, y, t); });
      const auto q = mo->move(t);
      CHECK(q.min_scaled_jacobian > 0.3);
      mo->velocity(w, dt, dt);
      auto dd = mo->displacement()->x()->array();
      auto ww = w.x()->array();
      for (std::size_t i = 0; i < X.size() / 3; ++i)
      {
        auto e = d(X[3 * i], X[3 * i + 1], t);
        auto e1 = d(X[3 * i], X[3 * i + 1], t - dt);
        auto e2 = d(X[3 * i], X[3 * i + 1], t - 2 * dt);
        for (int k = 0; k < 2; ++k)
        {
          err_d = std::max(err_d, std::abs(dd[2 * i + k] - e[k]));
          // BDF1 at the first step (from rest at X), then BDF2
          const double we = n == 1 ? (e[k] - 0) / dt
                                   : (3 * e[k] - 4 * e1[k] + e2[k]) / (2 * dt);
          err_w = std::max(err_w, std::abs(ww[2 * i + k] - we));
        }
      }
      mo->advance();
    }
    // Back to d = 0: the geometry returns to X exactly (no drift)
    set_interface(*mo, X,
                  [](double, double) -> std::array<double, 2> {
                    return {0, 0};
                  });
    mo->move(1.0);
    double drift = 0;
    auto x = mesh->geometry().x();
    for (std::size_t i = 0; i < x.size(); ++i)
      drift = std::max(drift, std::abs(x[i] - x0[i]));
    fsai::log::info("ALE {}: affine extension error {:.2e} m, mesh velocity "
                    "error {:.2e} m/s, drift {:.2e} m",
                    method, err_d, err_w, drift);
    CHECK(err_d < 1e-12);
    CHECK(err_w < 1e-10);
    CHECK(drift < 1e-14);
  }
}

TEST_CASE("ALE: in a squeezing glottal gap the harmonic extension inverts "
          "cells, the pseudo-elastic one (plain or Jacobian-stiffened) does "
          "not, and cell-size stiffening makes it worse",
          "[ale][mpi]")
{
  // Gap 0.4 mm closed to 5 % (0.02 mm) in 19 moves with the swing rotation
  const double g0 = 0.4 * mm, closure = 0.95;
  auto m = squeezing_gap(g0, 0.02 * mm);
  auto run = [&](std::string method, std::string stiffening, double chi)
  {
    fsai::ale::MeshMotionParameters p;
    p.method = method;
    p.stiffening = stiffening;
    p.chi = chi;
    double reached = 0;
    const double q = squeeze(m, g0, p, closure, 19, &reached);
    fsai::log::info("Squeezing gap, {} extension, stiffening {} (chi {}): "
                    "min scaled Jacobian {:.3f}, reached closure {:.2f}",
                    method, stiffening, chi, q, reached);
    return q;
  };
  CHECK(run("harmonic", "none", 0) < 0);
  CHECK(run("elastic", "none", 0) > 0.03);
  CHECK(run("elastic", "jacobian", 0.5) > 0.03);
  // Size stiffening keeps the small cells at the fold rigid and pushes the
  // whole closure into the larger cells at the axis
  CHECK(run("elastic", "size", 1) < 0);
}
