// Copyright (C) 2026 fsai developers
//
// The coupling iteration of one time step of the partitioned FSI loop
// (docs/model.md §3, §4, loop O–V): the caller's
// map H (structure step with the interface load, ALE move, flow step,
// consistent interface traction E12 → the new interface variable) is
// iterated with an Accelerator until the relative interface residual
//   |H(x_k) − x_k| / |H(x_k)|
// is below `tol`. One pass (`max_iterations` = 1, constant ω = 1) is the
// explicit (loosely coupled) scheme. A step that does not converge is an
// error or a logged warning by policy, never silent; every step's
// iterations, residual and relaxation go to a CSV file.
#pragma once

#include "Accelerator.h"
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace fsai::io
{
class CsvWriter;
}

namespace fsai::coupling
{
/// Coupling parameters ([coupling] section, with the accelerator's)
struct CouplingParameters
{
  AcceleratorParameters accelerator;
  double tol = 1e-6; ///< relative interface residual
  /// Absolute interface residual that also counts as converged (0: off):
  /// while the interface barely moves (a start-up ramp) the relative
  /// measure would ask for more than the sub-solvers' own accuracy
  double atol = 0.0;
  int max_iterations = 50; ///< per time step (1: explicit coupling)
  /// What a step that misses `tol` in `max_iterations` does: "error"
  /// (throws) or "warn" (logs and goes on, unless its relative residual
  /// is above 1: divergence always throws)
  std::string on_failure = "error";

  void bind(fsai::common::Parameters& p);
  void validate() const;
};

/// Outcome of one coupled time step
struct StepReport
{
  int iterations = 0;            ///< evaluations of H
  double residual = 0;           ///< relative residual of the kept iterate
  double first_residual = 0;     ///< relative residual of the first iteration
  double residual_abs = 0;       ///< |H(x) − x| of the kept iterate
  double first_residual_abs = 0; ///< |H(x) − x| of the first iteration
  bool converged = false;
  /// The accelerator's last relaxation factor (NaN: it did not act)
  double omega = std::numeric_limits<double>::quiet_NaN();
};

/// How step() ends
struct StepOptions
{
  /// Write the step's row to the CSV log (false: the caller records it,
  /// e.g. one row for a step it took in parts)
  bool record = true;
  /// The caller takes an unconverged step again (shorter): such a step
  /// returns with converged = false, without a warning, an error or a row
  bool may_retry = false;
};

class FixedPointCoupling
{
public:
  /// The interface map: fills Hx = H(x) (rank-local parts)
  using Map
      = std::function<void(std::span<const double> x, std::span<double> Hx)>;

  /// @param[in] csv_path Per-step log (empty: none)
  /// @param[in] keep_rows Restart: continue the log after its first
  ///   `keep_rows` rows (the checkpoint's step count); npos: a new log
  FixedPointCoupling(MPI_Comm comm, const CouplingParameters& p,
                     const std::string& csv_path = "",
                     std::size_t keep_rows = std::string::npos);
  ~FixedPointCoupling();

  /// Iterate one time step from the predictor x (on return: the last
  /// iterate, whose H the sub-solvers hold; for a step that does not
  /// converge, the iterate with the smallest residual, evaluated once more)
  StepReport step(double t, std::vector<double>& x, const Map& H,
                  StepOptions options = {});
  /// The CSV row of a step at time t
  void record(double t, const StepReport& rep);

  /// The accelerator's history from past steps (IQN-ILS reuse) into / from
  /// a checkpoint
  void save(io::RankState& state, const std::string& prefix) const
  {
    _acc->save(state, prefix);
  }
  void load(const io::RankState& state, const std::string& prefix)
  {
    _acc->load(state, prefix);
  }
  /// Forget the accelerator's history of earlier steps
  void clear_history() { _acc->clear_history(); }

private:
  MPI_Comm _comm;
  CouplingParameters _par;
  std::unique_ptr<Accelerator> _acc;
  std::unique_ptr<fsai::io::CsvWriter> _csv;
};
} // namespace fsai::coupling
