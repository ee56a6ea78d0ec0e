// Copyright (C) 2026 fsai developers
//
// A mesh moved by a prescribed displacement of its reference coordinates,
// x = X + d(X, t) (no drift: always from X), with the mesh velocity at the
// P1 dofs given by the BDF formula of the flow solver (E19), which is what
// keeps the discrete scheme free of geometric-conservation errors:
//   w^{n+1} = (3 x^{n+1} − 4 x^n + x^{n−1}) / (2Δt)   (BDF1 at the start)
// Used by the ALE verification tests and by fsai_cylinder --ale_amplitude;
// the interface-driven mesh motion of the FSI scenes is ale::MeshMotion.
#pragma once

#include <array>
#include <dolfinx/fem/Function.h>
#include <functional>
#include <memory>
#include <vector>

namespace fsai::ale
{
class PrescribedMotion
{
public:
  /// d(X, t): displacement of the reference point X at time t
  using Displacement
      = std::function<std::array<double, 3>(std::array<double, 3>, double)>;

  /// @param[in] mesh Mesh whose geometry is moved (its current coordinates
  ///   are taken as the reference X)
  /// @param[in] V P1 vector space of the mesh velocity
  PrescribedMotion(std::shared_ptr<dolfinx::mesh::Mesh> mesh,
                   const dolfinx::fem::FunctionSpace& V, Displacement d);

  /// Move the mesh nodes to X + d(X, t)
  void move(double t);
  /// Mesh velocity at time t from the positions at t, t − Δt and
  /// t − Δt − Δt_n (variable-step BDF2, E19; BDF1 from t and t − Δt)
  void velocity(dolfinx::fem::Function<double>& w, double t, double dt,
                double dt_n, bool bdf1) const;

private:
  std::shared_ptr<dolfinx::mesh::Mesh> _mesh;
  std::vector<double> _X, _dofX;
  Displacement _d;
};
} // namespace fsai::ale
