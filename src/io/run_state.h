// Copyright (C) 2026 fsai developers
//
// The run state of the restartable demos: checkpoint files (`--checkpoint-every
// N`,
// `--restart DIR`): a JSON document with the step, the state a step depends
// on and the parameters of the run, written so that a kill at any moment
// leaves either the previous or the new checkpoint, never a torn one.
#pragma once
#include <map>
#include <mpi.h>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

namespace fsai::io
{
/// Rank 0 writes `data` to a temporary file, flushes it to disk and renames
/// it over `path`. Throws (on every rank) if the write fails (disk full).
void write_checkpoint(MPI_Comm comm, const std::string& path,
                      const nlohmann::json& data);

/// The checkpoint at `path` on every rank; InputError if it is missing or
/// not valid JSON
nlohmann::json read_checkpoint(MPI_Comm comm, const std::string& path);

/// The arrays of a checkpoint that live on each rank (FE fields: the
/// rank's owned entries with their keys, field_state.h; time-stepping
/// history), keyed by name
using RankState = std::map<std::string, std::vector<double>>;

/// Every rank writes its `state` to `<stem>.r<rank>.bin` (temporary file,
/// fsync, rename); throws on every rank if any rank fails (disk full). The
/// files are only valid with the JSON checkpoint that names `stem`, written
/// after them, so a kill leaves a consistent pair. FE fields go in with
/// partition-independent keys (field_state.h).
void write_rank_state(MPI_Comm comm, const std::string& stem,
                      const RankState& state);

/// The state in one file written by write_rank_state() (`<stem>.r<k>.bin`),
/// read on every rank of `comm`; InputError on every rank if it is missing
/// or truncated on any
RankState read_rank_state_file(MPI_Comm comm, const std::string& path);

/// Remove this rank's `<stem>.r<rank>.bin` (an older checkpoint's)
void remove_rank_state(MPI_Comm comm, const std::string& stem);

/// `state[name]`, which must have `size` entries (SIZE_MAX: any); throws
/// InputError naming the entry otherwise (a restart with another mesh)
const std::vector<double>& state_entry(const RankState& state,
                                       const std::string& name,
                                       std::size_t size = std::size_t(-1));

/// Throw InputError on every rank if `error` is not empty on any rank (the
/// lowest such rank's message): restores that fail on one rank only
void throw_if_any_rank(MPI_Comm comm, const std::string& error);

/// Run `restore` on every rank; if it throws on any rank, every rank throws
/// (throw_if_any_rank), so that none is left waiting in a later collective
/// call
template <typename F>
void on_every_rank(MPI_Comm comm, F&& restore)
{
  std::string error;
  try
  {
    restore();
  }
  catch (const std::exception& e)
  {
    error = e.what();
  }
  throw_if_any_rank(comm, error);
}

/// How a restart's parameters differ from the checkpointed run's, as JSON
/// pointers ("/fluid/rho"). Parameters that may differ (output, restart and
/// checkpoint options, the simulated duration, the XDMF output interval
/// `write_every`: none of them changes the solution) are left out.
struct ParameterChanges
{
  std::vector<std::string> changed; ///< in both, different values: an error
  /// only in the restart: added to the code since the checkpoint was
  /// written (their current values are used), with those values
  std::vector<std::pair<std::string, nlohmann::json>> added;
  std::vector<std::string> removed; ///< only in the checkpoint
};
ParameterChanges compare_parameters(nlohmann::json saved,
                                    nlohmann::json current);
} // namespace fsai::io
