// Copyright (C) 2026 fsai developers
//
// The pressure convection–diffusion (PCD) approximation of the inverse
// Schur complement for the iterative flow solver (docs/model.md E20b):
//   S⁻¹ ≈ L_p⁻¹ F_p K_p⁻¹ + diag(g_i / m_i²),
// applied as a PCSHELL on the Schur block of the fieldsplit. Its only
// solve is one AMG V-cycle on the pressure Laplacian K_p, so it holds where
// the selfp matrix's convective parts make AMG diverge (the glottal jet).
#pragma once

#include <cstdint>
#include <dolfinx/fem/Form.h>
#include <dolfinx/fem/FunctionSpace.h>
#include <dolfinx/la/petsc.h>
#include <memory>
#include <petscpc.h>
#include <vector>

namespace fsai::fluid
{
class PressureConvectionDiffusion
{
public:
  /// Q: the pressure space; K, F: forms/fluid.py's K_p and F_p on (Q, Q);
  /// m, g: its m_p and g_p on Q; natural: local dofs of Q on the
  /// boundaries where the pressure is natural (p = 0 there in K_p, F_p);
  /// order: for each entry of the Schur block's local vector (the owned
  /// pressure dofs of the mixed space, in the fieldsplit's order) the
  /// owned dof of Q it is
  PressureConvectionDiffusion(
      std::shared_ptr<const dolfinx::fem::FunctionSpace> Q,
      std::shared_ptr<const dolfinx::fem::Form<double>> K,
      std::shared_ptr<const dolfinx::fem::Form<double>> F,
      std::shared_ptr<const dolfinx::fem::Form<double>> m,
      std::shared_ptr<const dolfinx::fem::Form<double>> g,
      std::vector<std::int32_t> natural, std::vector<std::int32_t> order);
  PressureConvectionDiffusion(const PressureConvectionDiffusion&) = delete;
  PressureConvectionDiffusion& operator=(const PressureConvectionDiffusion&)
      = delete;

  /// Assemble K_p, F_p, m, g with the forms' current coefficients (mesh,
  /// convecting velocity, porous indicator) and set up K_p's AMG
  void assemble();
  /// Make `pc` (the Schur block's) this approximation
  void attach(PC pc);
  /// Apply: y = S̃⁻¹ x (Schur-block vectors)
  void apply(Vec x, Vec y);

private:
  void assemble_with_natural_rows(Mat A, const dolfinx::fem::Form<double>& a);
  std::shared_ptr<const dolfinx::fem::FunctionSpace> _Q;
  std::shared_ptr<const dolfinx::fem::Form<double>> _K_form, _F_form, _m_form,
      _g_form;
  std::vector<PetscInt> _natural_rows; // global rows, owned
  std::vector<std::int32_t> _order;
  dolfinx::la::petsc::Matrix _K, _F;
  dolfinx::la::petsc::KrylovSolver _laplace;
  dolfinx::la::petsc::Vector _x, _t, _Ft, _diag;
  std::vector<double> _inv_m, _g_over_m2; // owned dofs of Q
};
} // namespace fsai::fluid
