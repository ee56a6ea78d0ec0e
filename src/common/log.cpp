// Copyright (C) 2026 fsai developers
#include "log.h"

int fsai::log::rank()
{
  int initialized = 0;
  MPI_Initialized(&initialized);
  if (!initialized)
    return 0;
  int r = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &r);
  return r;
}
