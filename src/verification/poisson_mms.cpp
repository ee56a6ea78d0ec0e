// Copyright (C) 2026 fsai developers
#include "poisson_mms.h"
#include "../common/Runtime.h"
#include "../common/timer.h"
#include <cmath>
#include <dolfinx/common/IndexMap.h>
#include <dolfinx/fem/Constant.h>
#include <dolfinx/fem/DirichletBC.h>
#include <dolfinx/fem/Expression.h>
#include <dolfinx/fem/assembler.h>
#include <dolfinx/fem/petsc.h>
#include <dolfinx/fem/utils.h>
#include <dolfinx/la/petsc.h>
#include <dolfinx/mesh/utils.h>
#include <fsai_forms/poisson.h>
#include <numeric>

using namespace dolfinx;
using T = PetscScalar;
using Coefficients
    = std::map<std::string, std::shared_ptr<const fem::Function<T>>>;
using Constants
    = std::map<std::string, std::shared_ptr<const fem::Constant<T>>>;

namespace
{
/// Largest cell diameter over all ranks
double max_cell_diameter(const mesh::Mesh& mesh)
{
  const int tdim = mesh.topology().dim();
  const std::int32_t n = mesh.topology().index_map(tdim)->size_local();
  std::vector<std::int32_t> cells(n);
  std::iota(cells.begin(), cells.end(), 0);
  std::vector<double> h = mesh::h(mesh, cells, tdim);
  double local = h.empty() ? 0.0 : *std::max_element(h.begin(), h.end());
  double global = 0.0;
  MPI_Allreduce(&local, &global, 1, MPI_DOUBLE, MPI_MAX, mesh.comm());
  return global;
}
} // namespace

//-----------------------------------------------------------------------------
fsai::verification::PoissonResult
fsai::verification::solve_poisson_mms(std::shared_ptr<mesh::Mesh> mesh,
                                      int degree)
{
  namespace forms = fsai::forms::poisson;
  const int tdim = mesh->topology().dim();

  auto V = std::make_shared<fem::FunctionSpace>(fem::create_functionspace(
      forms::functionspace_a(tdim, degree), "u", mesh));

  // Dirichlet data: the exact solution interpolated by the compiled
  // Expression (defined once, in the form file)
  auto g = std::make_shared<fem::Function<T>>(V);
  g->interpolate(
      fem::create_expression<T>(forms::expression_u_exact(tdim, degree),
                                Coefficients{}, Constants{}, mesh));

  const int fdim = tdim - 1;
  mesh->topology_mutable().create_connectivity(fdim, tdim);
  std::vector<std::int32_t> boundary_facets
      = mesh::exterior_facet_indices(mesh->topology());
  std::vector<std::int32_t> dofs
      = fem::locate_dofs_topological(*V, fdim, boundary_facets);
  std::vector<std::shared_ptr<const fem::DirichletBC<T>>> bcs
      = {std::make_shared<const fem::DirichletBC<T>>(g, dofs)};

  auto a = std::make_shared<fem::Form<T>>(fem::create_form<T>(
      forms::a(tdim, degree), {V, V}, Coefficients{}, Constants{}, {}));
  auto L = std::make_shared<fem::Form<T>>(fem::create_form<T>(
      forms::L(tdim, degree), {V}, Coefficients{}, Constants{}, {}));

  common::ScopedTimer t_assemble("poisson: assemble");
  // Assemble (DOLFINx order: matrix with bcs, diagonal, vector, lifting,
  // ghost accumulation, bc values)
  la::petsc::Matrix A(fem::petsc::create_matrix(*a), false);
  MatZeroEntries(A.mat());
  fem::assemble_matrix(la::petsc::Matrix::set_block_fn(A.mat(), ADD_VALUES), *a,
                       bcs);
  MatAssemblyBegin(A.mat(), MAT_FLUSH_ASSEMBLY);
  MatAssemblyEnd(A.mat(), MAT_FLUSH_ASSEMBLY);
  fem::set_diagonal<T>(la::petsc::Matrix::set_fn(A.mat(), INSERT_VALUES), *V,
                       bcs);
  MatAssemblyBegin(A.mat(), MAT_FINAL_ASSEMBLY);
  MatAssemblyEnd(A.mat(), MAT_FINAL_ASSEMBLY);

  la::Vector<T> b(L->function_spaces()[0]->dofmap()->index_map,
                  L->function_spaces()[0]->dofmap()->index_map_bs());
  b.set(0.0);
  fem::assemble_vector(b.mutable_array(), *L);
  fem::apply_lifting<T>(
      b.mutable_array(), std::vector<std::shared_ptr<const fem::Form<T>>>{a},
      std::vector<decltype(bcs)>{bcs}, std::vector<std::span<const T>>{}, 1.0);
  b.scatter_rev(std::plus<T>());
  fem::set_bc<T>(b.mutable_array(), bcs);

  t_assemble.stop();

  // Solve
  common::ScopedTimer t_solve("poisson: solve");
  common::set_option_default("poisson_ksp_type", "cg");
  common::set_option_default("poisson_pc_type", "hypre");
  common::set_option_default("poisson_pc_hypre_type", "boomeramg");
  common::set_option_default("poisson_ksp_rtol", "1e-12");
  la::petsc::KrylovSolver solver(mesh->comm());
  solver.set_options_prefix("poisson_");
  solver.set_from_options();
  solver.set_operator(A.mat());

  auto u = std::make_shared<fem::Function<T>>(V);
  u->name = "u";
  la::petsc::Vector _u(la::petsc::create_vector_wrap(*u->x()), false);
  la::petsc::Vector _b(la::petsc::create_vector_wrap(b), false);
  PoissonResult r;
  r.iterations = solver.solve(_u.vec(), _b.vec());
  KSPConvergedReason reason;
  KSPGetConvergedReason(solver.ksp(), &reason);
  if (reason < 0)
  {
    throw std::runtime_error("Poisson solve diverged (KSPConvergedReason "
                             + std::to_string(reason) + ")");
  }
  u->x()->scatter_fwd();
  t_solve.stop();

  // L2 error
  auto M = std::make_shared<fem::Form<T>>(
      fem::create_form<T>(forms::error_L2(tdim, degree), {},
                          Coefficients{{"uh", u}}, Constants{}, {}, mesh));
  double e2_local = fem::assemble_scalar(*M);
  double e2 = 0.0;
  MPI_Allreduce(&e2_local, &e2, 1, MPI_DOUBLE, MPI_SUM, mesh->comm());

  r.tdim = tdim;
  r.degree = degree;
  r.dofs = V->dofmap()->index_map->size_global() * V->dofmap()->index_map_bs();
  r.h = max_cell_diameter(*mesh);
  r.error_L2 = std::sqrt(e2);
  r.u = u;
  return r;
}
//-----------------------------------------------------------------------------
double fsai::verification::convergence_rate(double h0, double e0, double h1,
                                            double e1)
{
  return std::log(e0 / e1) / std::log(h0 / h1);
}
//-----------------------------------------------------------------------------
