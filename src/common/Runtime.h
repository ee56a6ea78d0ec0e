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

  /// Communicator reserved for error agreement (a duplicate of
  /// MPI_COMM_WORLD, so it never matches a collective of the solvers)
  MPI_Comm error_comm() const { return _error_comm; }

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
  MPI_Comm _error_comm = MPI_COMM_NULL;
  int _argc = 0;
  char** _argv = nullptr;
  bool _deferred = false, _started = false;
  void start();
  static Runtime* instance;
  friend void start_deferred_libraries();
};

/// Start MPI, PETSc and SLEPc if the Runtime deferred them (a "--help"
/// token on the command line: the usage needs none of them). Called by
/// Parameters::parse once the arguments are parsed without a help request.
void start_deferred_libraries();

/// True if every rank of `comm` calls this within `timeout_s` seconds (a
/// non-blocking barrier polled until the deadline). Used on the error path
/// to tell an error every rank met (bad input, a diverged solve: exit
/// cleanly) from an error on some ranks only (abort, since the others may
/// wait forever in a collective).
bool all_ranks_arrive(MPI_Comm comm, double timeout_s);

/// Set the PETSc option `-name value` unless it is already set (on the
/// command line or from a config file's [petsc] table): code defaults
/// never overwrite a user's choice
void set_option_default(const std::string& name, const std::string& value);

/// Run a demo's body with the common error policy and return the exit
/// status for main:
/// - HelpRequested: status 0;
/// - an exception raised on every rank: one line
///   "<program>: error: <message>" (rank 0's message) on stderr, status 2
///   for InputError (bad input), 1 otherwise;
/// - an exception raised on some ranks only (they wait up to 10 s for the
///   others): each of those ranks prints
///   "<program>: error [rank r]: <message>" and calls MPI_Abort, so no rank
///   waits forever for one that failed.
/// On success the timing table is printed.
int run_main(int argc, char* argv[], const std::function<void(Runtime&)>& body);
} // namespace fsai::common
