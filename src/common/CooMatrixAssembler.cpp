// Copyright (C) 2026 fsai developers
#include "CooMatrixAssembler.h"
#include <dolfinx/fem/assembler.h>
#include <dolfinx/la/petsc.h>
#include <span>
#include <stdexcept>

namespace
{
/// DOLFINx's PETSc error report (logs and throws)
void check(PetscErrorCode ierr, const char* function)
{
  if (ierr != 0)
    dolfinx::la::petsc::error(ierr, __FILE__, function);
}
} // namespace

fsai::common::CooMatrixAssembler::CooMatrixAssembler(
    Mat A, const dolfinx::fem::Form<double>& a, const BCs& bcs)
    : _bcs(bcs)
{
  const auto& V0 = *a.function_spaces().at(0);
  const auto& V1 = *a.function_spaces().at(1);
  _bs0 = V0.dofmap()->index_map_bs();
  _bs1 = V1.dofmap()->index_map_bs();
  const auto map = V0.dofmap()->index_map;
  if (!bcs.empty() and (map != V1.dofmap()->index_map or _bs0 != _bs1))
    throw std::logic_error("CooMatrixAssembler: Dirichlet conditions need "
                           "the same test and trial space");
  std::vector<PetscInt> coo_i, coo_j;
  // DOLFINx calls the insertion function with block indices and the
  // element matrix of the expanded (scalar) rows and columns, row-major
  auto record
      = [&](std::span<const std::int32_t> rows,
            std::span<const std::int32_t> cols, std::span<const double>) -> int
  {
    for (std::int32_t r : rows)
      for (int k0 = 0; k0 < _bs0; ++k0)
        for (std::int32_t c : cols)
          for (int k1 = 0; k1 < _bs1; ++k1)
          {
            coo_i.push_back(PetscInt(r) * _bs0 + k0);
            coo_j.push_back(PetscInt(c) * _bs1 + k1);
          }
    return 0;
  };
  dolfinx::fem::assemble_matrix(record, a, BCs{});
  _element_entries = coo_i.size();

  // One diagonal entry per owned constrained dof (a dof of two conditions,
  // a corner, still gets one)
  const std::size_t n0 = _bs0 * (map->size_local() + map->num_ghosts());
  _marker.assign(n0, 0);
  for (const auto& bc : bcs)
  {
    if (!V0.contains(*bc->function_space()))
      throw std::logic_error(
          "CooMatrixAssembler: a condition outside the form's space");
    bc->mark_dofs(_marker);
  }
  for (std::int32_t i = 0; i < _bs0 * map->size_local(); ++i)
    if (_marker[i])
      coo_i.push_back(i), coo_j.push_back(i);
  _values.assign(coo_i.size(), 0.0);
  _g.assign(n0, 0.0);
  _lift.assign(n0, 0.0);
  // PETSc converts the indices to global ones in place
  check(MatSetPreallocationCOOLocal(A, PetscCount(coo_i.size()), coo_i.data(),
                                    coo_j.data()),
        "MatSetPreallocationCOOLocal");
}
//-----------------------------------------------------------------------------
void fsai::common::CooMatrixAssembler::assemble(
    Mat A, const dolfinx::fem::Form<double>& a)
{
  for (const auto& bc : _bcs)
    bc->set(_g);
  std::fill(_lift.begin(), _lift.end(), 0.0);
  std::size_t k = 0;
  const std::size_t n = _element_entries;
  double* out = _values.data();
  const std::int8_t* D = _marker.data();
  const int bs0 = _bs0, bs1 = _bs1;
  auto fill = [&](std::span<const std::int32_t> rows,
                  std::span<const std::int32_t> cols,
                  std::span<const double> vals) -> int
  {
    if (k + vals.size() > n)
      throw std::logic_error(
          "CooMatrixAssembler: more entries than the recorded pattern");
    std::size_t e = 0;
    for (std::int32_t r : rows)
      for (int k0 = 0; k0 < bs0; ++k0)
      {
        const std::int32_t i = r * bs0 + k0;
        const bool row_bc = D[i];
        double lift = 0;
        for (std::int32_t c : cols)
          for (int k1 = 0; k1 < bs1; ++k1, ++e)
          {
            const std::int32_t j = c * bs1 + k1;
            double v = vals[e];
            if (D[j])
            {
              lift -= v * _g[j];
              v = 0;
            }
            out[k + e] = row_bc ? 0.0 : v;
          }
        if (!row_bc)
          _lift[i] += lift;
      }
    k += vals.size();
    return 0;
  };
  dolfinx::fem::assemble_matrix(fill, a, BCs{});
  if (k != n)
    throw std::logic_error(
        "CooMatrixAssembler: fewer entries than the recorded pattern");
  std::fill(_values.begin() + long(n), _values.end(), 1.0);
  check(MatSetValuesCOO(A, _values.data(), INSERT_VALUES), "MatSetValuesCOO");
  check(MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  check(MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
}
//-----------------------------------------------------------------------------
void fsai::common::assemble_matrix_per_cell(Mat A,
                                            const dolfinx::fem::Form<double>& a,
                                            const CooMatrixAssembler::BCs& bcs)
{
  namespace fem = dolfinx::fem;
  using dolfinx::la::petsc::Matrix;
  MatZeroEntries(A);
  fem::assemble_matrix(Matrix::set_block_fn(A, ADD_VALUES), a, bcs);
  MatAssemblyBegin(A, MAT_FLUSH_ASSEMBLY);
  MatAssemblyEnd(A, MAT_FLUSH_ASSEMBLY);
  fem::set_diagonal<double>(Matrix::set_fn(A, INSERT_VALUES),
                            *a.function_spaces()[0], bcs);
  MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY);
  MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY);
}
