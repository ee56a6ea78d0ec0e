// Copyright (C) 2026 fsai developers
#pragma once

#include <mpi.h>
#include <string>

namespace fsai::io
{
/// Create the output folder (collective; rank 0 creates, all ranks check).
/// Throws InputError "output folder '<dir>' is not writable: ..." on failure.
void prepare_output_dir(MPI_Comm comm, const std::string& dir);

/// Create the parent folder of `path` if missing (no-op if it exists)
void ensure_parent_dir(const std::string& path);
/// Rank 0 runs scripts/<script> on the run folder `dir` to draw a chart
/// (optional: a missing matplotlib only warns)
void draw_chart(MPI_Comm comm, const std::string& script,
                const std::string& dir);
} // namespace fsai::io
