// Copyright (C) 2026 fsai developers
//
// The fold's motion in its in-vacuo modes (docs/model.md §1): with the
// modes φ_k of K φ = ω² M φ (modal_analysis, max |φ_k| = 1) and the mass
// matrix M, the displacement u has the modal coordinates
//   q_k = φ_kᵀ M u / φ_kᵀ M φ_k    [m: the mode's largest displacement],
// the M-orthogonal projection of u on each mode. The model justifies the
// reduced (2-DOF) fold by the few shapes that carry the motion: the
// coordinates' share of the motion tells which.
#pragma once

#include "modal.h"
#include <dolfinx/la/petsc.h>
#include <vector>

namespace fsai::structure
{
class ElasticSolver;

class ModalProjection
{
public:
  /// The first `n` modes of the solver's linear stiffness and mass
  ModalProjection(const ElasticSolver& solid, int n);

  /// The modes' frequencies [Hz]
  std::vector<double> frequencies_hz() const;
  const std::vector<Mode>& modes() const { return _modes; }
  /// m_k = φ_kᵀ M φ_k [kg]
  const std::vector<double>& modal_masses() const { return _m; }

  /// q_k of u (collective), then the share of uᵀ M u that the modes leave
  /// out: 1 − Σ m_k q_k² / uᵀ M u (m_k = φ_kᵀ M φ_k; 0 when u = 0)
  std::vector<double>
  coordinates(const dolfinx::fem::Function<double>& u) const;

private:
  std::vector<Mode> _modes;
  dolfinx::la::petsc::Matrix _M;
  std::vector<dolfinx::la::petsc::Vector> _Mphi; ///< M φ_k
  std::vector<double> _m;                        ///< φ_kᵀ M φ_k
  dolfinx::la::petsc::Vector _Mu;                ///< workspace of coordinates()
};

/// Each mode's share of the motion's variance over the window: from the
/// series of coordinates q[i][k] (rows from `first`), m_k var(q_k) / Σ_j
/// m_j var(q_j), with m_k the modal masses (the M-norm of the
/// oscillation about its mean)
std::vector<double> modal_shares(const std::vector<std::vector<double>>& q,
                                 const std::vector<double>& modal_mass,
                                 std::size_t first);
} // namespace fsai::structure
