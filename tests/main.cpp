// Copyright (C) 2026 fsai developers
// Catch2 main for the fsai test binary: initialises MPI/PETSc/SLEPc once
// (fsai::common::Runtime) and combines the result over all ranks, so a
// failure on any rank fails the run. Catch2's own options (-s, -r, [tag])
// are not passed to PETSc.
#define CATCH_CONFIG_RUNNER
#include "catch.h"
#include <common/Runtime.h>

int main(int argc, char* argv[])
{
  int status = 0;
  {
    char* prog[] = {argv[0], nullptr};
    fsai::common::Runtime runtime(1, prog);
    status = Catch::Session().run(argc, argv);
    int global = 0;
    MPI_Allreduce(&status, &global, 1, MPI_INT, MPI_MAX, runtime.comm());
    status = global;
  }
  return status;
}
