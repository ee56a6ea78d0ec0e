// Copyright (C) 2026 fsai developers
//
// The BDF2 derivative on a variable time grid (docs/model.md E19), shared by
// the flow (∂v/∂t) and the mesh motion (w = ∂d/∂t), which must use the same
// weights for the ALE scheme to stay consistent.
#pragma once

#include <cassert>
#include <span>

namespace fsai::common
{
/// du/dt at t_{n+1} ≈ w0 u_{n+1} + w1 u_n + w2 u_{n−1}
struct Bdf2Weights
{
  double w0, w1, w2;
};

/// Weights for the step dt = t_{n+1} − t_n after the step
/// dt_n = t_n − t_{n−1} (E19; with r = dt/dt_n, second order for any r,
/// zero-stable for r < 1 + √2); BDF1 when `first` (no history)
inline Bdf2Weights bdf2_weights(double dt, double dt_n, bool first)
{
  if (first)
    return {1 / dt, -1 / dt, 0.0};
  const double r = dt / dt_n;
  return {(1 + 2 * r) / ((1 + r) * dt), -(1 + r) / dt, r * r / ((1 + r) * dt)};
}

/// u_{n+1} ≈ u_n + r (u_n − u_{n−1}) with r = dt/dt_n: the linear
/// extrapolation that goes with the weights above (the Oseen convecting
/// velocity, E20; the elastic glottis's load predictor)
inline void extrapolate(std::span<double> out, std::span<const double> u_n,
                        std::span<const double> u_nn, double r)
{
  assert(out.size() == u_n.size() and u_n.size() == u_nn.size());
  for (std::size_t i = 0; i < out.size(); ++i)
    out[i] = (1 + r) * u_n[i] - r * u_nn[i];
}
} // namespace fsai::common
