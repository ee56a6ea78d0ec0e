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
                                           bool saddle_point,
                                           std::int64_t unknowns)
{
  KSPSetType(ksp, KSPPREONLY);
  PC pc;
  KSPGetPC(ksp, &pc);
  const bool small = tdim == 2 and !saddle_point and unknowns > 0
                     and unknowns <= small_system_unknowns;
  int size;
  MPI_Comm_size(comm, &size);
  if (small and size > 1)
  {
    // Every rank factorises the whole (gathered) matrix: for a few
    // thousand unknowns MUMPS's communication costs more than the work
    PCSetType(pc, PCREDUNDANT);
    KSP inner;
    PCRedundantGetKSP(pc, &inner);
    KSPSetType(inner, KSPPREONLY);
    KSPGetPC(inner, &pc);
  }
  PCSetType(pc, PCLU);
  PCFactorSetMatSolverType(pc, small          ? MATSOLVERPETSC
                               : saddle_point ? MATSOLVERMUMPS
                                              : lu_package(comm, tdim).c_str());
  if (small)
    PCFactorSetMatOrderingType(pc, MATORDERINGRCM);
  PCFactorSetZeroPivot(pc, 0.0);
}
//-----------------------------------------------------------------------------
