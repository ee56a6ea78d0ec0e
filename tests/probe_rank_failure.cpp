// Copyright (C) 2026 fsai developers
// An error raised on one rank only, while the other rank waits in a
// collective: run_main must report it and end the job (MPI_Abort) instead
// of hanging. Run under mpirun -n 2 by ctest (test rank_failure_no_hang).
#include <common/Runtime.h>
#include <stdexcept>

int main(int argc, char* argv[])
{
  return fsai::common::run_main(
      argc, argv,
      [](fsai::common::Runtime& rt)
      {
        if (rt.rank() == 1)
          throw std::runtime_error("injected failure on rank 1");
        MPI_Barrier(rt.comm()); // Never completes: rank 1 is gone
      });
}
