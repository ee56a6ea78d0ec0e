// Copyright (C) 2026 fsai developers
//
// The checkpoints of one run folder (`--checkpoint-every N`, `--restart
// DIR`): DIR/checkpoint.json (step, time, number of ranks, parameters,
// scalars of the run) and, for FE scenes, the fields of each rank in
// DIR/checkpoint_<step>.r<rank>.bin (io/field_state.h). The field files are
// written first, the JSON that names them next (atomically), the previous
// field files removed last: a kill at any moment leaves one complete
// checkpoint.
#pragma once
#include "run_state.h"
#include <mpi.h>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace fsai::common
{
class Parameters;
}

namespace fsai::io
{
/// The restart options of a time-stepping demo (one set for all of them)
struct RestartOptions
{
  int checkpoint_every = 0; ///< steps between checkpoints (0: none)
  std::string restart;      ///< run folder to continue ("" : a new run)
  int kill_at_step = 0;     ///< testing: SIGKILL after this step

  void bind(fsai::common::Parameters& p);
  void validate() const;
  /// A checkpoint is due after step k
  bool checkpoint_due(long k) const
  {
    return checkpoint_every > 0 and k % checkpoint_every == 0;
  }
  /// Testing: SIGKILL this process if k is the step to be killed after
  void kill_if_requested(long k) const;
};

class Checkpointer
{
public:
  /// @param[in] dir Run folder
  /// @param[in] parameters The run's parameters (Parameters::to_json())
  Checkpointer(MPI_Comm comm, std::string dir, nlohmann::json parameters);

  /// Restart: read DIR/checkpoint.json and its fields (on every rank, from
  /// all the ranks that wrote them). InputError if there is none or a
  /// parameter other than output, restart, checkpoint-every, duration,
  /// write_every and debug.* differs (named in the message).
  void read();
  /// The checkpoint's JSON (after read())
  const nlohmann::json& meta() const { return _meta; }
  /// Its step (0 before read())
  long step() const { return _meta.is_object() ? _meta.value("step", 0L) : 0L; }
  /// The fields of all the checkpoint's ranks (empty if it has none)
  const std::vector<RankState>& fields() const { return _fields; }

  /// Write the checkpoint of `step` at time t with the scene's `scalars`
  /// (merged into the JSON) and this rank's `fields` (nullptr: none)
  void write(long step, double t, const nlohmann::json& scalars,
             const RankState* fields);
  /// Stem of the field files of the last checkpoint ("" if none)
  const std::string& fields_stem() const { return _stem; }
  /// ", the last checkpoint is <stem>" (or "" if none), for error messages
  std::string last_checkpoint_note() const
  {
    return _stem.empty() ? "" : ", the last checkpoint is " + _stem;
  }

private:
  MPI_Comm _comm;
  std::string _dir;
  nlohmann::json _parameters, _meta;
  std::vector<RankState> _fields;
  std::string _stem;
};
} // namespace fsai::io
