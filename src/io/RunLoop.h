// Copyright (C) 2026 fsai developers
//
// The time loop of a scene, written once: restart from a checkpoint, the
// series' kept rows, checkpoints every N steps, progress with ETA, the
// testing kill hook, the count of unconverged coupling steps, and the
// failed-step message that names the last good state (docs/model.md §6).
// The scene supplies one step (its physics and its output) and, for FE
// scenes, how to save its state and write the last good fields.
#pragma once
#include "Checkpointer.h"
#include "CsvWriter.h"
#include "Progress.h"
#include "run_state.h"
#include <functional>
#include <memory>
#include <mpi.h>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace fsai::io
{
class RunSummary;

/// What one step reports to the loop
struct StepReport
{
  double t = 0;          ///< time reached [s]
  bool converged = true; ///< the step's coupling reached its tolerance
};

/// What a scene gives the loop
struct RunHooks
{
  /// Advance step k (its physics and its output rows)
  std::function<StepReport(long k)> step;
  /// The state for a checkpoint: scalars merged into checkpoint.json and
  /// this rank's fields (none: a state held by scalars alone)
  std::function<void(nlohmann::json& scalars, std::optional<RankState>& fields)>
      save;
  /// A failed step: write the last good fields to `path` and return their
  /// time (nullopt: nothing to write, the error is passed on as it is)
  std::function<std::optional<double>(const std::string& path)> last_good;
  /// The progress line's extra text after step k
  std::function<std::string()> progress;
};

class RunLoop
{
public:
  /// Reads the checkpoint of `options.restart` (if set) before the scene
  /// is built: its step, time, scalars and fields
  RunLoop(MPI_Comm comm, const std::string& dir, const nlohmann::json& params,
          const RestartOptions& options);

  bool restarting() const { return !_options.restart.empty(); }
  /// The step the loop starts after (the checkpoint's; 0 for a new run)
  long first_step() const { return _checkpoint.step(); }
  /// The checkpoint's time (NaN for a new run): XDMF steps after it are
  /// replaced
  double restart_time() const;
  /// Rows kept from the checkpoint's logs (npos for a new run)
  std::size_t rows_kept() const;
  /// The checkpoint's JSON and its fields (after a restart)
  const nlohmann::json& checkpoint() const { return _checkpoint.meta(); }
  const std::vector<RankState>& fields() const { return _checkpoint.fields(); }

  /// Open the series `path`: a new file, or after a restart the file cut
  /// back to the checkpoint's step, whose rows are returned (on every rank)
  /// so that the scene can rebuild its statistics
  std::vector<std::vector<double>>
  open_series(const std::string& path, const std::vector<std::string>& columns,
              RunSummary& summary);
  /// Append a row to the series
  void row(const std::vector<double>& values) { _series->row(values); }

  /// Steps first_step() + 1 … n; returns the loop's wall time [s]
  double run(long n, const RunHooks& hooks);

  /// Steps whose coupling did not converge (kept across restarts)
  int unconverged_steps() const { return _unconverged; }

private:
  MPI_Comm _comm;
  std::string _dir;
  RestartOptions _options;
  Checkpointer _checkpoint;
  std::unique_ptr<CsvWriter> _series;
  int _unconverged = 0;
};
} // namespace fsai::io
