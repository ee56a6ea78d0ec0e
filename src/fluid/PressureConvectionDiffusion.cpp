// Copyright (C) 2026 fsai developers
#include "PressureConvectionDiffusion.h"
#include <dolfinx/fem/assembler.h>
#include <dolfinx/fem/petsc.h>
#include <dolfinx/la/Vector.h>
#include <stdexcept>

using namespace dolfinx;

namespace
{
// Owned entries of a linear form's vector on Q, ghost contributions summed
std::vector<double> assemble_owned(const fem::Form<double>& L,
                                   const fem::FunctionSpace& Q)
{
  auto map = Q.dofmap()->index_map;
  la::Vector<double> v(map, 1);
  v.set(0.0);
  fem::assemble_vector(v.mutable_array(), L);
  v.scatter_rev(std::plus<double>());
  auto a = v.array();
  return std::vector<double>(a.begin(), a.begin() + map->size_local());
}

PetscErrorCode apply_shell(PC pc, Vec x, Vec y)
{
  void* ctx = nullptr;
  PCShellGetContext(pc, &ctx);
  static_cast<fsai::fluid::PressureConvectionDiffusion*>(ctx)->apply(x, y);
  return 0;
}
} // namespace

fsai::fluid::PressureConvectionDiffusion::PressureConvectionDiffusion(
    std::shared_ptr<const fem::FunctionSpace> Q,
    std::shared_ptr<const fem::Form<double>> K,
    std::shared_ptr<const fem::Form<double>> F,
    std::shared_ptr<const fem::Form<double>> m,
    std::shared_ptr<const fem::Form<double>> g,
    std::vector<std::int32_t> natural, std::vector<std::int32_t> order)
    : _Q(Q), _K_form(K), _F_form(F), _m_form(m), _g_form(g),
      _order(std::move(order)), _K(fem::petsc::create_matrix(*K), false),
      _F(fem::petsc::create_matrix(*F), false), _laplace(Q->mesh()->comm()),
      _x(la::petsc::create_vector(*Q->dofmap()->index_map, 1), false),
      _t(la::petsc::create_vector(*Q->dofmap()->index_map, 1), false),
      _Ft(la::petsc::create_vector(*Q->dofmap()->index_map, 1), false),
      _diag(la::petsc::create_vector(*Q->dofmap()->index_map, 1), false)
{
  auto map = Q->dofmap()->index_map;
  const std::int32_t owned = map->size_local();
  for (std::int32_t j : _order)
    if (j < 0 or j >= owned)
      throw std::logic_error("PCD: a Schur-block entry is not an owned "
                             "pressure dof");
  // Without a natural-pressure boundary K_p is singular (enclosed flow)
  std::vector<std::int32_t> rows;
  for (std::int32_t d : natural)
    if (d < owned)
      rows.push_back(d);
  std::vector<std::int64_t> global(rows.size());
  map->local_to_global(rows, global);
  _natural_rows.assign(global.begin(), global.end());
  std::int64_t n = std::int64_t(_natural_rows.size()), n_all = 0;
  MPI_Allreduce(&n, &n_all, 1, MPI_INT64_T, MPI_SUM, Q->mesh()->comm());
  if (n_all == 0)
    throw std::runtime_error(
        "--fluid.schur pcd needs a boundary where the pressure is natural "
        "(penalty inlet or outlet); use --fluid.schur selfp");

  KSP ksp = _laplace.ksp();
  KSPSetType(ksp, KSPPREONLY);
  PC pc;
  KSPGetPC(ksp, &pc);
  PCSetType(pc, PCHYPRE);
  _laplace.set_options_prefix("fluid_pcd_laplace_");
  _laplace.set_from_options();
}
//-----------------------------------------------------------------------------
void fsai::fluid::PressureConvectionDiffusion::assemble_with_natural_rows(
    Mat A, const fem::Form<double>& a)
{
  // p = 0 on the natural-pressure boundaries (Elman, Silvester & Wathen
  // 2014, §9.2), the rows and columns cleared and the operator's own
  // diagonal kept, so that those dofs are scaled as their neighbours
  MatZeroEntries(A);
  fem::assemble_matrix(
      la::petsc::Matrix::set_fn(A, ADD_VALUES), a,
      std::vector<std::shared_ptr<const fem::DirichletBC<double>>>{});
  MatAssemblyBegin(A, MAT_FINAL_ASSEMBLY);
  MatAssemblyEnd(A, MAT_FINAL_ASSEMBLY);
  MatGetDiagonal(A, _diag.vec());
  MatZeroRowsColumns(A, PetscInt(_natural_rows.size()), _natural_rows.data(),
                     1.0, nullptr, nullptr);
  MatDiagonalSet(A, _diag.vec(), INSERT_VALUES);
}
//-----------------------------------------------------------------------------
void fsai::fluid::PressureConvectionDiffusion::assemble()
{
  assemble_with_natural_rows(_K.mat(), *_K_form);
  assemble_with_natural_rows(_F.mat(), *_F_form);
  const std::vector<double> m = assemble_owned(*_m_form, *_Q);
  const std::vector<double> g = assemble_owned(*_g_form, *_Q);
  _inv_m.resize(m.size());
  _g_over_m2.resize(m.size());
  for (std::size_t i = 0; i < m.size(); ++i)
  {
    _inv_m[i] = 1.0 / m[i];
    _g_over_m2[i] = g[i] / (m[i] * m[i]);
  }
  _laplace.set_operator(_K.mat());
  KSPSetUp(_laplace.ksp());
}
//-----------------------------------------------------------------------------
void fsai::fluid::PressureConvectionDiffusion::attach(PC pc)
{
  PCSetType(pc, PCSHELL);
  PCShellSetContext(pc, this);
  PCShellSetApply(pc, apply_shell);
  PCShellSetName(pc, "pressure convection-diffusion (docs/model.md E20b)");
}
//-----------------------------------------------------------------------------
void fsai::fluid::PressureConvectionDiffusion::apply(Vec x, Vec y)
{
  const std::size_t n = _order.size();
  {
    const PetscScalar* xs = nullptr;
    PetscScalar* xq = nullptr;
    VecGetArrayRead(x, &xs);
    VecGetArray(_x.vec(), &xq);
    for (std::size_t k = 0; k < n; ++k)
      xq[_order[k]] = xs[k];
    VecRestoreArray(_x.vec(), &xq);
    VecRestoreArrayRead(x, &xs);
  }
  KSPSolve(_laplace.ksp(), _x.vec(), _t.vec()); // K_p⁻¹ x
  MatMult(_F.mat(), _t.vec(), _Ft.vec());       // F_p K_p⁻¹ x
  const PetscScalar* xs = nullptr;
  const PetscScalar* ft = nullptr;
  PetscScalar* ys = nullptr;
  VecGetArrayRead(x, &xs);
  VecGetArrayRead(_Ft.vec(), &ft);
  VecGetArray(y, &ys);
  for (std::size_t k = 0; k < n; ++k)
  {
    const std::int32_t j = _order[k];
    ys[k] = _inv_m[j] * ft[j] + _g_over_m2[j] * xs[k];
  }
  VecRestoreArray(y, &ys);
  VecRestoreArrayRead(_Ft.vec(), &ft);
  VecRestoreArrayRead(x, &xs);
}
