// Copyright (C) 2026 fsai developers
#include "modal.h"
#include "../common/Runtime.h"
#include "../common/petsc_solver.h"
#include "../common/timer.h"
#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <limits>
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
  // The dofs' positions and the mesh's extent, for the modes' sign
  const std::vector<double> X = V->tabulate_dof_coordinates(false);
  std::array<double, 3> lo, hi;
  for (int c = 0; c < 3; ++c)
  {
    lo[c] = std::numeric_limits<double>::max();
    hi[c] = std::numeric_limits<double>::lowest();
  }
  for (std::size_t i = 0; i < X.size(); i += 3)
    for (int c = 0; c < 3; ++c)
    {
      lo[c] = std::min(lo[c], X[i + c]);
      hi[c] = std::max(hi[c], X[i + c]);
    }
  MPI_Allreduce(MPI_IN_PLACE, lo.data(), 3, MPI_DOUBLE, MPI_MIN, comm);
  MPI_Allreduce(MPI_IN_PLACE, hi.data(), 3, MPI_DOUBLE, MPI_MAX, comm);
  const double span
      = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2], 1e-300});
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

    // Normalise max |u| = 1, with a sign that does not depend on the
    // partition (SLEPc's does): Σ_j u_j w_j > 0 over the owned dofs, with
    // a weight w linear in the node's position and the component, so that
    // no mode shape (even or odd in any direction) is orthogonal to it
    double amax = 0.0, weighted = 0.0;
    for (std::int32_t j = 0; j < nloc; ++j)
    {
      amax = std::max(amax, std::abs(u[j]));
      const double* p = &X[3 * (j / bs)];
      weighted
          += u[j]
             * (1.0 + 0.3 * (j % bs) + (p[0] - lo[0]) / span
                + 2.0 * (p[1] - lo[1]) / span + 3.0 * (p[2] - lo[2]) / span);
    }
    std::array<double, 2> in = {amax, weighted}, out{};
    MPI_Allreduce(in.data(), out.data(), 1, MPI_DOUBLE, MPI_MAX, comm);
    MPI_Allreduce(&in[1], &out[1], 1, MPI_DOUBLE, MPI_SUM, comm);
    amax = out[0];
    const double scale = out[1] < 0 ? -1.0 / amax : 1.0 / amax;
    if (amax > 0)
      for (auto& v : u)
        v *= scale;

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
