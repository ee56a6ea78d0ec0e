// Copyright (C) 2026 fsai developers
//
// The BDF2 derivative on a variable time grid (docs/model.md E19), shared by
// the flow (∂v/∂t) and the mesh motion (w = ∂d/∂t), which must use the same
// weights for the ALE scheme to stay consistent.
#pragma once

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
} // namespace fsai::common
