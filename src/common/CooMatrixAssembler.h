// Copyright (C) 2026 fsai developers
#pragma once

#include <dolfinx/fem/DirichletBC.h>
#include <dolfinx/fem/Form.h>
#include <memory>
#include <petscmat.h>
#include <span>
#include <vector>

namespace fsai::common
{
/// Assembles a bilinear form into a PETSc matrix through PETSc's COO
/// interface (MatSetPreallocationCOOLocal / MatSetValuesCOO), for operators
/// reassembled at every time step on a fixed sparsity (the ALE flow), and
/// the lifting of its Dirichlet conditions in the same pass.
///
/// Why: DOLFINx inserts each cell's element matrix with
/// MatSetValuesBlockedLocal, which maps the indices and searches every row
/// for its columns; on the FE glottis scene (31.5k unknowns, 2 ranks) that
/// insertion took 21.5 of the 38 ms of a matrix assembly. Here
/// the entries' positions are fixed once and each assembly only writes the
/// values in order and hands them to PETSc in one call. The lifting
/// (b −= A_{:,D} g, DOLFINx's apply_lifting, which packs the form's
/// coefficients and calls its kernel again on the cells at the boundary)
/// comes from the same element matrices.
///
/// The element matrices come from DOLFINx's own assembler (fem::
/// assemble_matrix with a recording insertion function, without
/// conditions), so its cell and facet loops and dof transformations are
/// unchanged. Entries in a constrained row or column are then zeroed, the
/// column ones after entering the lifting, and constrained rows get 1 on
/// the diagonal, once per owned dof. The matrix and lifting are those of
/// fem::assemble_matrix + set_diagonal and apply_lifting, summed in
/// another order (equal to rounding).
///
/// Cost in memory: the values and PETSc's map of them, about 20 bytes per
/// element-matrix entry (81 per P1/P1 triangle, 256 per tetrahedron):
/// +31 MB peak RSS on the FE glottis mesh (19855 triangles, serial).
///
/// The form's integration domains, the dofmap and the set of constrained
/// dofs must not change after construction (coefficients, constants, mesh
/// coordinates and boundary values may): assemble() throws if the number
/// of entries differs from the recorded pattern.
class CooMatrixAssembler
{
public:
  using BCs
      = std::vector<std::shared_ptr<const dolfinx::fem::DirichletBC<double>>>;
  /// Records the pattern of `a` and the dofs constrained by `bcs`, and sets
  /// the pattern as A's preallocation (A: created for `a`, e.g. by
  /// fem::petsc::create_matrix)
  CooMatrixAssembler(Mat A, const dolfinx::fem::Form<double>& a,
                     const BCs& bcs);
  /// A = assembled a, with the constrained rows and columns zeroed and 1
  /// on their diagonal (final assembly included); lifting() = −A_{:,D} g
  /// for the current boundary values g of the constructor's conditions
  void assemble(Mat A, const dolfinx::fem::Form<double>& a);
  /// The lifting of the last assemble(), by local dof of the test space
  /// (owned and ghost: add it to the right-hand side before its reverse
  /// scatter, as apply_lifting does)
  std::span<const double> lifting() const { return _lift; }

private:
  BCs _bcs;
  int _bs0 = 1, _bs1 = 1;
  std::size_t _element_entries = 0; ///< entries from the element matrices
  std::vector<double> _values;      ///< in the recorded order
  std::vector<std::int8_t> _marker; ///< constrained dofs (local, ghosts too)
  std::vector<double> _g;           ///< boundary values at those dofs
  std::vector<double> _lift;
};

/// The same matrix through DOLFINx's own insertion (MatSetValuesBlockedLocal
/// per cell, then 1 on the constrained rows' diagonal): the reference path
/// of the solvers' `assembly = "dolfinx"`. No lifting
void assemble_matrix_per_cell(Mat A, const dolfinx::fem::Form<double>& a,
                              const CooMatrixAssembler::BCs& bcs);
} // namespace fsai::common
