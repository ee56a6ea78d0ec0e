// Copyright (C) 2026 fsai developers
#include "PrescribedMotion.h"
#include "../common/bdf.h"

//-----------------------------------------------------------------------------
fsai::ale::PrescribedMotion::PrescribedMotion(
    std::shared_ptr<dolfinx::mesh::Mesh> mesh,
    const dolfinx::fem::FunctionSpace& V, Displacement d)
    : _mesh(mesh), _d(std::move(d))
{
  auto x = mesh->geometry().x();
  _X.assign(x.begin(), x.end());
  _dofX = V.tabulate_dof_coordinates(false);
}
//-----------------------------------------------------------------------------
void fsai::ale::PrescribedMotion::move(double t)
{
  auto x = _mesh->geometry().x();
  const int gdim = _mesh->geometry().dim();
  for (std::size_t i = 0; i < x.size() / 3; ++i)
  {
    const std::array<double, 3> X{_X[3 * i], _X[3 * i + 1], _X[3 * i + 2]};
    const auto d = _d(X, t);
    for (int k = 0; k < gdim; ++k)
      x[3 * i + k] = X[k] + d[k];
  }
}
//-----------------------------------------------------------------------------
void fsai::ale::PrescribedMotion::velocity(dolfinx::fem::Function<double>& w,
                                           double t, double dt, double dt_n,
                                           bool bdf1) const
{
  const auto c = common::bdf2_weights(dt, dt_n, bdf1);
  auto a = w.x()->mutable_array();
  const int bs = w.function_space()->dofmap()->bs();
  for (std::size_t i = 0; i < _dofX.size() / 3; ++i)
  {
    const std::array<double, 3> X{_dofX[3 * i], _dofX[3 * i + 1],
                                  _dofX[3 * i + 2]};
    const auto d1 = _d(X, t), d0 = _d(X, t - dt), dm = _d(X, t - dt - dt_n);
    for (int k = 0; k < bs; ++k)
      a[bs * i + k] = c.w0 * d1[k] + c.w1 * d0[k] + c.w2 * dm[k];
  }
}
//-----------------------------------------------------------------------------
