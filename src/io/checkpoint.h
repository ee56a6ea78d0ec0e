// Copyright (C) 2026 fsai developers
//
// Checkpoint files of the restartable demos (`--checkpoint-every N`,
// `--restart DIR`): a JSON document with the step, the state a step depends
// on and the parameters of the run, written so that a kill at any moment
// leaves either the previous or the new checkpoint, never a torn one.
#pragma once
#include <mpi.h>
#include <nlohmann/json.hpp>
#include <string>

namespace fsai::io
{
/// Rank 0 writes `data` to a temporary file, flushes it to disk and renames
/// it over `path`. Throws (on every rank) if the write fails (disk full).
void write_checkpoint(MPI_Comm comm, const std::string& path,
                      const nlohmann::json& data);

/// The checkpoint at `path` on every rank; InputError if it is missing or
/// not valid JSON
nlohmann::json read_checkpoint(MPI_Comm comm, const std::string& path);

/// Parameters that may differ between a run and its restart (output,
/// restart and checkpoint options, the simulated duration) are removed;
/// returns the first parameter whose value differs ("" if none)
std::string first_changed_parameter(nlohmann::json saved,
                                    nlohmann::json current);
} // namespace fsai::io
