// Copyright (C) 2026 fsai developers
#include "petsc_solver.h"

//-----------------------------------------------------------------------------
std::string fsai::common::lu_package(MPI_Comm comm, int tdim)
{
  int size;
  MPI_Comm_size(comm, &size);
  return size == 1 and tdim == 2 ? MATSOLVERPETSC : MATSOLVERMUMPS;
}
//-----------------------------------------------------------------------------
void fsai::common::configure_direct_solver(KSP ksp, MPI_Comm comm, int tdim,
                                           bool saddle_point)
{
  KSPSetType(ksp, KSPPREONLY);
  PC pc;
  KSPGetPC(ksp, &pc);
  PCSetType(pc, PCLU);
  PCFactorSetMatSolverType(pc, saddle_point ? MATSOLVERMUMPS
                                            : lu_package(comm, tdim).c_str());
  PCFactorSetZeroPivot(pc, 0.0);
}
//-----------------------------------------------------------------------------
