// Copyright (C) 2026 fsai developers
#pragma once

#include <cstdint>
#include <dolfinx/fem/Function.h>
#include <dolfinx/mesh/Mesh.h>
#include <memory>

namespace fsai::verification
{
/// Result of one manufactured-solution solve
struct PoissonResult
{
  int tdim = 0;
  int degree = 0;
  std::int64_t dofs = 0;
  double h = 0;        ///< Largest cell diameter (global)
  double error_L2 = 0; ///< ||u_h - u_e||_L2
  int iterations = 0;  ///< Krylov iterations
  /// The discrete solution (for output)
  std::shared_ptr<dolfinx::fem::Function<double>> u;
};

/// Solve -Δu = f on `mesh` with Pk Lagrange elements, f and the Dirichlet
/// data from the manufactured solution of forms/poisson.py, and measure
/// the L2 error. This exercises the whole forms pipeline (UFL -> FFCx
/// variant -> dispatch header -> DOLFINx assembly -> PETSc solve) in 2D and
/// 3D. Solver: PETSc options prefix "poisson_" (default CG + BoomerAMG,
/// rtol 1e-12, so the algebraic error is far below the discretisation
/// error).
/// @param[in] mesh Triangle or tetrahedron mesh; the whole boundary is
///   Dirichlet
/// @param[in] degree Polynomial degree (1 or 2)
PoissonResult solve_poisson_mms(std::shared_ptr<dolfinx::mesh::Mesh> mesh,
                                int degree);

/// Observed convergence rate log(e0/e1)/log(h0/h1)
double convergence_rate(double h0, double e0, double h1, double e1);
} // namespace fsai::verification
