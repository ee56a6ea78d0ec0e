// Copyright (C) 2026 fsai developers
#include "Runtime.h"
#include "errors.h"
#include "timer.h"
#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdlib>
#include <dolfinx/common/log.h>
#include <filesystem>
#include <iostream>
#include <petscsys.h>
#include <slepcsys.h>
#include <thread>

fsai::common::Runtime* fsai::common::Runtime::instance = nullptr;

namespace
{
/// True for a token PETSc owns: "-x..." with a letter after one dash.
/// "-h" is ours (help); "--..." is ours.
bool is_petsc_option(const std::string& a)
{
  return a.size() >= 2 and a[0] == '-' and std::isalpha(a[1]) and a != "-h";
}

/// True if `a` reads as a number (so "-1e-8" is a value, not an option)
bool is_number(const std::string& a)
{
  char* end = nullptr;
  std::strtod(a.c_str(), &end);
  return !a.empty() and end == a.c_str() + a.size();
}
} // namespace

//-----------------------------------------------------------------------------
std::pair<std::vector<std::string>, std::vector<std::string>>
fsai::common::Runtime::split_arguments(const std::vector<std::string>& args)
{
  std::vector<std::string> app, petsc;
  for (std::size_t i = 0; i < args.size(); ++i)
  {
    if (is_petsc_option(args[i]))
    {
      petsc.push_back(args[i]);
      // An option takes the next token as its value unless that is another
      // option (flags such as -ksp_view take none)
      if (i + 1 < args.size()
          and (args[i + 1].empty() or args[i + 1][0] != '-'
               or is_number(args[i + 1])))
      {
        petsc.push_back(args[++i]);
      }
    }
    else
      app.push_back(args[i]);
  }
  return {app, petsc};
}
//-----------------------------------------------------------------------------
fsai::common::Runtime::Runtime(int argc, char* argv[])
{
  _program
      = std::filesystem::path(argc > 0 ? argv[0] : "fsai").filename().string();
  std::vector<std::string> args(argv + std::min(argc, 1), argv + argc);
  std::tie(_app_args, _petsc_args) = split_arguments(args);

  _petsc_argv.push_back(argv[0]);
  for (std::string& a : _petsc_args)
    _petsc_argv.push_back(a.data());
  _petsc_argv.push_back(nullptr);

  _argc = argc;
  _argv = argv;
  // --help needs no library: the usage is printed without starting MPI,
  // PETSc and SLEPc (most of a second). When a "--help" token turns out
  // to be an option's value, the parser starts them after all
  // (start_deferred_libraries) before anything can call MPI
  _deferred = std::any_of(_app_args.begin(), _app_args.end(),
                          [](const std::string& a)
                          { return a == "--help" or a == "-h"; });
  instance = this;
  if (!_deferred)
    start();
}
//-----------------------------------------------------------------------------
void fsai::common::Runtime::start()
{
  _deferred = false;
  // A process started without mpirun is a singleton: Open MPI's default
  // point-to-point layer (UCX) spends 0.2 s probing network devices it
  // will never use; the shared-memory one starts in half the time. The
  // reduced voice runs hundreds of times in a sweep, so this counts. A
  // user's own choice (the variable set) wins.
  if (!std::getenv("OMPI_COMM_WORLD_SIZE"))
    setenv("OMPI_MCA_pml", "ob1", 0);
  dolfinx::init_logging(_argc, _argv);
  int petsc_argc = static_cast<int>(_petsc_argv.size()) - 1;
  char** petsc_argv = _petsc_argv.data();
  PetscErrorCode ierr
      = SlepcInitialize(&petsc_argc, &petsc_argv, nullptr, nullptr);
  if (ierr != 0)
  {
    std::cerr << _program << ": error: SlepcInitialize failed (" << ierr << ")"
              << std::endl;
    std::exit(1);
  }
  _started = true;
  MPI_Comm_rank(MPI_COMM_WORLD, &_rank);
  MPI_Comm_size(MPI_COMM_WORLD, &_size);
  MPI_Comm_dup(MPI_COMM_WORLD, &_error_comm);
}
//-----------------------------------------------------------------------------
void fsai::common::start_deferred_libraries()
{
  if (Runtime::instance and Runtime::instance->_deferred)
    Runtime::instance->start();
}
//-----------------------------------------------------------------------------
fsai::common::Runtime::~Runtime()
{
  instance = nullptr;
  if (!_started)
    return;
  MPI_Comm_free(&_error_comm);
  SlepcFinalize();
}
//-----------------------------------------------------------------------------
bool fsai::common::all_ranks_arrive(MPI_Comm comm, double timeout_s)
{
  MPI_Request request;
  MPI_Ibarrier(comm, &request);
  const auto deadline = std::chrono::steady_clock::now()
                        + std::chrono::duration<double>(timeout_s);
  int done = 0;
  while (true)
  {
    MPI_Test(&request, &done, MPI_STATUS_IGNORE);
    if (done)
      return true;
    if (std::chrono::steady_clock::now() > deadline)
      return false; // The request stays pending: the caller aborts
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
}
//-----------------------------------------------------------------------------
void fsai::common::set_option_default(const std::string& name,
                                      const std::string& value)
{
  const std::string key = "-" + name;
  PetscBool has = PETSC_FALSE;
  PetscOptionsHasName(nullptr, nullptr, key.c_str(), &has);
  if (!has)
    PetscOptionsSetValue(nullptr, key.c_str(), value.c_str());
}
//-----------------------------------------------------------------------------
int fsai::common::run_main(int argc, char* argv[],
                           const std::function<void(Runtime&)>& body)
{
  Runtime runtime(argc, argv);
  std::string message;
  int status = 0;
  try
  {
    body(runtime);
    print_timings(runtime.comm());
    return 0;
  }
  catch (const HelpRequested&)
  {
    return 0;
  }
  catch (const InputError& e)
  {
    message = e.what();
    status = 2;
  }
  catch (const std::exception& e)
  {
    message = e.what();
    status = 1;
  }

  const std::string& prog = runtime.program();
  if (runtime.size() == 1 or all_ranks_arrive(runtime.error_comm(), 10.0))
  {
    if (runtime.rank() == 0)
      std::cerr << prog << ": error: " << message << std::endl;
    return status;
  }
  std::cerr << prog << ": error [rank " << runtime.rank() << "]: " << message
            << std::endl;
  MPI_Abort(MPI_COMM_WORLD, status);
  return status;
}
//-----------------------------------------------------------------------------
