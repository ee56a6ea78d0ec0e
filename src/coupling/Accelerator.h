// Copyright (C) 2026 fsai developers
//
// Acceleration of the partitioned FSI fixed point (docs/model.md §3, loop O–V):
// each coupling iteration maps the interface variable x_k (displacement or
// load) to H(x_k) = x̃_k by one structure + ALE + flow pass, with residual r_k =
// x̃_k − x_k. An accelerator turns (x_k, x̃_k) into the next iterate x_{k+1}:
//   constant  x_{k+1} = x_k + ω r_k (ω = 1 with one pass: explicit coupling)
//   aitken    the same with ω_k = −ω_{k−1} r_{k−1}·(r_k − r_{k−1}) /
//             |r_k − r_{k−1}|² (Irons–Tuck / Küttler & Wall 2008), ω_0 from
//             the parameters at the start of every step
//   iqn-ils   interface quasi-Newton with an inverse Jacobian from least
//             squares (Degroote, Bathe & Vierendeels 2009):
//             columns V = [Δr_i], W = [Δx̃_i] from this step's iterations
//             and those of the last `reuse` steps; c = argmin |V c + r_k|,
//             x_{k+1} = x̃_k + W c; columns whose QR diagonal is below
//             `filter` |column| are dropped (QR1 filter), newest kept first.
// Vectors are the rank-local parts of a distributed interface vector:
// inner products are summed over the communicator.
#pragma once

#include <deque>
#include <io/run_state.h>
#include <memory>
#include <mpi.h>
#include <span>
#include <string>
#include <vector>

namespace fsai::common
{
class Parameters;
}

namespace fsai::coupling
{
/// Accelerator parameters ([coupling] section)
struct AcceleratorParameters
{
  std::string method = "iqn-ils"; ///< constant | aitken | iqn-ils
  double omega = 0.5;   ///< constant ω; first ω of Aitken and IQN-ILS
  int reuse = 8;        ///< IQN-ILS: past time steps whose columns are kept
  double filter = 1e-3; ///< IQN-ILS: QR1 filter ε (noise in H makes
                        ///< nearly dependent columns harmful: 1e-8
                        ///< diverged on Turek-Hron FSI1)

  void bind(fsai::common::Parameters& p);
  void validate() const;
};

class Accelerator
{
public:
  virtual ~Accelerator() = default;
  /// Start of a time step (Aitken restarts its ω, IQN-ILS moves this
  /// step's columns into the reuse history)
  virtual void new_step() = 0;
  /// Next iterate from x_k and x̃_k = H(x_k) (rank-local parts)
  virtual void update(std::span<const double> x, std::span<const double> Hx,
                      std::span<double> x_next)
      = 0;
  /// Relaxation factor used by the last update (NaN for IQN-ILS updates)
  virtual double last_omega() const = 0;
  /// What carries over from past time steps, into / from a checkpoint
  /// (constant and Aitken: nothing, they restart every step)
  virtual void save(io::RankState&, const std::string&) const {}
  virtual void load(const io::RankState&, const std::string&) {}
  /// Forget what earlier steps taught (IQN-ILS's reused columns); the
  /// next step starts as the first one does
  virtual void clear_history() {}
};

std::unique_ptr<Accelerator> make_accelerator(MPI_Comm comm,
                                              const AcceleratorParameters& p);

/// Global Euclidean norm of a distributed vector
double norm(MPI_Comm comm, std::span<const double> v);
} // namespace fsai::coupling
