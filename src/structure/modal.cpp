// Copyright (C) 2026 fsai developers
#include "modal.h"
#include "../common/Runtime.h"
#include "../common/petsc_solver.h"
#include "../common/timer.h"
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <slepceps.h>

using namespace dolfinx;

namespace
{
/// RAII for a SLEPc EPS
struct Eps
{
  EPS eps = nullptr;
  explicit Eps(MPI_Comm comm) { EPSCreate(comm, &eps); }
  ~Eps() { EPSDestroy(&eps); }
  Eps(const Eps&) = delete;
  Eps& operator=(const Eps&) = delete;
};
} // namespace

std::vector<fsai::structure::Mode>
fsai::structure::modal_analysis(const ElasticSolver& solid, int n)
{
  common::ScopedTimer timer("modal: total");
  auto V = solid.space();
  MPI_Comm comm = V->mesh()->comm();
  la::petsc::Matrix K = [&]
  {
    common::ScopedTimer t("modal: assemble");
    return solid.stiffness_matrix(1.0);
  }();
  la::petsc::Matrix M = solid.mass_matrix();

  Eps e(comm);
  EPSSetOperators(e.eps, K.mat(), M.mat());
  EPSSetProblemType(e.eps, EPS_GHEP);
  EPSSetWhichEigenpairs(e.eps, EPS_TARGET_MAGNITUDE);
  EPSSetTarget(e.eps, 0.0);
  EPSSetDimensions(e.eps, n, PETSC_DEFAULT, PETSC_DEFAULT);
  EPSSetTolerances(e.eps, 1e-10, PETSC_DEFAULT);
  // Shift-and-invert about 0 with a direct solve (options may override)
  ST st;
  EPSGetST(e.eps, &st);
  STSetType(st, STSINVERT);
  KSP st_ksp;
  STGetKSP(st, &st_ksp);
  common::configure_direct_solver(st_ksp, comm, V->mesh()->topology().dim());
  EPSSetOptionsPrefix(e.eps, "modal_");
  EPSSetFromOptions(e.eps);
  {
    common::ScopedTimer t("modal: eigensolve");
    EPSSolve(e.eps);
  }
  PetscInt nconv;
  EPSGetConverged(e.eps, &nconv);
  if (nconv < n)
  {
    throw std::runtime_error(fmt::format(
        "modal: SLEPc converged {} of {} eigenpairs (try -modal_eps_ncv)",
        int(nconv), n));
  }

  // Directional kinetic-energy shares use the lumped ρ at the dofs: M x
  // split by component
  const int bs = V->dofmap()->index_map_bs();
  std::vector<Mode> modes;
  Vec xr, Mx;
  MatCreateVecs(K.mat(), &xr, nullptr);
  VecDuplicate(xr, &Mx);
  for (PetscInt i = 0; i < nconv and int(modes.size()) < n; ++i)
  {
    PetscScalar kr, ki;
    EPSGetEigenpair(e.eps, i, &kr, &ki, xr, nullptr);
    if (kr <= 0.0)
      continue;
    Mode m;
    m.frequency_hz = std::sqrt(kr) / (2 * M_PI);
    m.shape = std::make_shared<fem::Function<double>>(V);
    m.shape->name = "mode";
    const PetscScalar* x;
    PetscInt nloc;
    VecGetLocalSize(xr, &nloc);
    VecGetArrayRead(xr, &x);
    auto u = m.shape->x()->mutable_array();
    std::copy(x, x + nloc, u.begin());
    VecRestoreArrayRead(xr, &x);
    m.shape->x()->scatter_fwd();

    // Normalise max |u| = 1 (sign: largest entry positive)
    double amax = 0.0, loc = 0.0;
    for (std::int32_t j = 0; j < nloc; ++j)
      if (std::abs(u[j]) > std::abs(loc))
        loc = u[j];
    std::vector<double> in = {std::abs(loc)}, out(1);
    MPI_Allreduce(in.data(), out.data(), 1, MPI_DOUBLE, MPI_MAX, comm);
    amax = out[0];
    if (amax > 0)
      for (auto& v : u)
        v /= amax;

    // Kinetic energy by direction: Σ_dofs of component c of x (M x)
    MatMult(M.mat(), xr, Mx);
    const PetscScalar *xa, *mxa;
    VecGetArrayRead(xr, &xa);
    VecGetArrayRead(Mx, &mxa);
    std::array<double, 3> share{0, 0, 0}, total{};
    for (PetscInt j = 0; j < nloc; ++j)
      share[j % bs] += xa[j] * mxa[j];
    VecRestoreArrayRead(xr, &xa);
    VecRestoreArrayRead(Mx, &mxa);
    MPI_Allreduce(share.data(), total.data(), 3, MPI_DOUBLE, MPI_SUM, comm);
    const double sum = total[0] + total[1] + total[2];
    for (int c = 0; c < 3; ++c)
      m.direction_share[c] = sum > 0 ? total[c] / sum : 0.0;
    m.dominant = int(
        std::max_element(m.direction_share.begin(), m.direction_share.end())
        - m.direction_share.begin());
    modes.push_back(m);
  }
  VecDestroy(&xr);
  VecDestroy(&Mx);
  std::sort(modes.begin(), modes.end(),
            [](auto& a, auto& b) { return a.frequency_hz < b.frequency_hz; });
  return modes;
}
