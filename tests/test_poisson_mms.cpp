// Copyright (C) 2026 fsai developers
// The forms pipeline end to end: forms/poisson.py compiled for triangles
// and tetrahedra, P1 and P2, must converge in L2 at the theoretical rate
// k + 1 (measured between the two finest meshes, within ±0.1). Runs in
// serial and under mpirun -n 2 (same test binary).
#include "catch.h"
#include <common/log.h>
#include <dolfinx/mesh/generation.h>
#include <verification/poisson_mms.h>

namespace
{
std::shared_ptr<dolfinx::mesh::Mesh> unit_mesh(int tdim, std::size_t n)
{
  using namespace dolfinx::mesh;
  if (tdim == 2)
  {
    return std::make_shared<Mesh>(
        create_rectangle(MPI_COMM_WORLD, {{{0.0, 0.0}, {1.0, 1.0}}}, {n, n},
                         CellType::triangle, GhostMode::shared_facet));
  }
  return std::make_shared<Mesh>(
      create_box(MPI_COMM_WORLD, {{{0.0, 0.0, 0.0}, {1.0, 1.0, 1.0}}},
                 {n, n, n}, CellType::tetrahedron, GhostMode::shared_facet));
}
} // namespace

TEST_CASE("Poisson MMS converges at rate k+1 in L2", "[verification][mpi]")
{
  // (tdim, degree, coarse n, fine n)
  auto [tdim, degree, n0, n1] = GENERATE(table<int, int, int, int>(
      {{2, 1, 16, 32}, {2, 2, 16, 32}, {3, 1, 8, 16}, {3, 2, 6, 12}}));
  CAPTURE(tdim, degree);

  auto r0 = fsai::verification::solve_poisson_mms(unit_mesh(tdim, n0), degree);
  auto r1 = fsai::verification::solve_poisson_mms(unit_mesh(tdim, n1), degree);
  const double rate = fsai::verification::convergence_rate(
      1.0 / n0, r0.error_L2, 1.0 / n1, r1.error_L2);
  int size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &size);
  fsai::log::info("Poisson MMS {}D P{} ranks={}: n={} e={:.4e}, n={} e={:.4e}"
                  " (dofs {}), L2 rate {:.3f} (theory {})",
                  tdim, degree, size, n0, r0.error_L2, n1, r1.error_L2, r1.dofs,
                  rate, degree + 1);
  CHECK(rate == Approx(degree + 1).margin(0.1));
}
