// Copyright (C) 2026 fsai developers
//
// Modal analysis (docs/model.md §1): K x = ω² M x with SLEPc,
// shift-and-invert about 0. Dirichlet dofs have K rows/columns zero with
// diagonal 1 and M rows/columns zero (diagonal 0): their eigenvalue is
// infinite, so no spurious mode appears near the target. PETSc/SLEPc
// options prefix "modal_".
#pragma once

#include "ElasticSolver.h"
#include <array>
#include <memory>
#include <string>
#include <vector>

namespace fsai::structure
{
/// One eigenmode (max |φ| = 1; its sign does not depend on the partition)
struct Mode
{
  double frequency_hz;
  std::shared_ptr<dolfinx::fem::Function<double>> shape; ///< max |u| = 1
  /// Share of the mode's kinetic energy (ρ|φ|²) per direction x, y, z
  std::array<double, 3> direction_share;
  /// Largest share: 0 (x), 1 (y), 2 (z)
  int dominant;
};

/// First `n` modes of the solver's linear stiffness and mass, sorted by
/// frequency
std::vector<Mode> modal_analysis(const ElasticSolver& solid, int n);
} // namespace fsai::structure
