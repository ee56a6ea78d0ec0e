// Copyright (C) 2026 fsai developers
#include "ModalProjection.h"
#include "ElasticSolver.h"
#include <common/timer.h>

//-----------------------------------------------------------------------------
fsai::structure::ModalProjection::ModalProjection(const ElasticSolver& solid,
                                                  int n)
    : _modes(modal_analysis(solid, n)), _M(solid.mass_matrix()),
      _Mu(*solid.space()->dofmap()->index_map,
          solid.space()->dofmap()->index_map_bs())
{
  for (const auto& mode : _modes)
  {
    dolfinx::la::petsc::Vector phi(
        dolfinx::la::petsc::create_vector_wrap(*mode.shape->x()), false);
    auto& Mphi = _Mphi.emplace_back(*solid.space()->dofmap()->index_map,
                                    solid.space()->dofmap()->index_map_bs());
    MatMult(_M.mat(), phi.vec(), Mphi.vec());
    double m = 0;
    VecDot(phi.vec(), Mphi.vec(), &m);
    _m.push_back(m);
  }
}
//-----------------------------------------------------------------------------
std::vector<double> fsai::structure::ModalProjection::frequencies_hz() const
{
  std::vector<double> f;
  for (const auto& m : _modes)
    f.push_back(m.frequency_hz);
  return f;
}
//-----------------------------------------------------------------------------
std::vector<double> fsai::structure::ModalProjection::coordinates(
    const dolfinx::fem::Function<double>& u) const
{
  common::ScopedTimer timer("modal: projection");
  dolfinx::la::petsc::Vector x(dolfinx::la::petsc::create_vector_wrap(*u.x()),
                               false);
  std::vector<double> q;
  double captured = 0;
  for (std::size_t k = 0; k < _Mphi.size(); ++k)
  {
    double d = 0;
    VecDot(x.vec(), _Mphi[k].vec(), &d); // M symmetric: φᵀ M u = uᵀ (M φ)
    q.push_back(d / _m[k]);
    captured += _m[k] * q.back() * q.back();
  }
  MatMult(_M.mat(), x.vec(), _Mu.vec());
  double uMu = 0;
  VecDot(x.vec(), _Mu.vec(), &uMu);
  q.push_back(uMu > 0 ? std::max(0.0, 1.0 - captured / uMu) : 0.0);
  return q;
}
//-----------------------------------------------------------------------------
std::vector<double>
fsai::structure::modal_shares(const std::vector<std::vector<double>>& q,
                              const std::vector<double>& modal_mass,
                              std::size_t first)
{
  const std::size_t n = modal_mass.size();
  std::vector<double> mean(n, 0.0), var(n, 0.0), share(n, 0.0);
  if (q.size() <= first + 1)
    return share;
  const double count = double(q.size() - first);
  for (std::size_t i = first; i < q.size(); ++i)
    for (std::size_t k = 0; k < n; ++k)
      mean[k] += q[i][k] / count;
  for (std::size_t i = first; i < q.size(); ++i)
    for (std::size_t k = 0; k < n; ++k)
      var[k] += (q[i][k] - mean[k]) * (q[i][k] - mean[k]) / count;
  double total = 0;
  for (std::size_t k = 0; k < n; ++k)
    total += modal_mass[k] * var[k];
  for (std::size_t k = 0; k < n; ++k)
    share[k] = total > 0 ? modal_mass[k] * var[k] / total : 0.0;
  return share;
}
