// Copyright (C) 2026 fsai developers
#pragma once

#include <functional>
#include <mpi.h>
#include <string>
#include <vector>

namespace fsai::common
{
/// Owns the process-wide libraries: DOLFINx logging, MPI, PETSc and SLEPc.
/// Construct exactly once at the top of main; everything that holds PETSc
/// or MPI objects must be destroyed before it.
///
/// The command line is split in two: PETSc options (a single dash and a
/// letter, e.g. `-fluid_ksp_type gmres`, with their value) go to
/// SlepcInitialize, so they win over code defaults (set_option_default);
/// everything else (`--output DIR`, `--config FILE`, `--mesh.h 0.01`, `-h`)
/// is returned by app_args() for the parameter parser.
class Runtime
{
public:
  Runtime(int argc, char* argv[]);
  ~Runtime();
  Runtime(const Runtime&) = delete;
  Runtime& operator=(const Runtime&) = delete;

  /// MPI_COMM_WORLD
  MPI_Comm comm() const { return MPI_COMM_WORLD; }
  int rank() const { return _rank; }
  int size() const { return _size; }

  /// Program name (basename of argv[0])
  const std::string& program() const { return _program; }

  /// Arguments for the application's own parser (program name excluded)
  const std::vector<std::string>& app_args() const { return _app_args; }

  /// Split argv into (application arguments, PETSc arguments), both
  /// without the program name; exposed for testing
  static std::pair<std::vector<std::string>, std::vector<std::string>>
  split_arguments(const std::vector<std::string>& args);

private:
  std::string _program;
  std::vector<std::string> _app_args;
  std::vector<std::string> _petsc_args;
  std::vector<char*> _petsc_argv; // Storage PETSc keeps pointers to
  int _rank = 0;
  int _size = 1;
};

/// Set the PETSc option `-name value` unless it is already set (on the
/// command line or from a config file's [petsc] table): code defaults
/// never overwrite a user's choice
void set_option_default(const std::string& name, const std::string& value);

/// Run a demo's body with the common error policy and return the exit
/// status for main:
/// - InputError (bad input, raised on every rank): one line
///   "<program>: error: <message>" on rank 0's stderr, status 2;
/// - HelpRequested: status 0;
/// - any other exception: "<program>: error: <message>" on stderr of the
///   rank that caught it; with several ranks MPI_Abort, so no rank waits
///   forever for one that failed; status 1 in serial.
/// On success the timing table is printed.
int run_main(int argc, char* argv[], const std::function<void(Runtime&)>& body);
} // namespace fsai::common
