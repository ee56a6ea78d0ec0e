// Copyright (C) 2026 fsai developers
#pragma once

#include <mpi.h>
#include <petscksp.h>
#include <string>

namespace fsai::common
{
/// LU package for a direct solve: PETSc's own for small serial 2D systems
/// (it is ~8x faster per solve than MUMPS there), MUMPS in 3D (less fill)
/// or in parallel (PETSc's LU is serial only)
std::string lu_package(MPI_Comm comm, int tdim);

/// Make `ksp` a direct solver (preonly + LU with lu_package) and switch
/// off PETSc's absolute zero-pivot test (2.2e-14), which rejects the
/// well-posed matrices of soft tissue or r-weighted axisymmetric forms.
/// These are defaults set on this KSP: call set_from_options afterwards
/// so that the command line (-prefix_pc_type ...) still overrides them.
/// `saddle_point`: always MUMPS, which pivots; PETSc's LU does not, and a
/// zero diagonal block (P1/P1 without PSPG) makes it fail.
void configure_direct_solver(KSP ksp, MPI_Comm comm, int tdim,
                             bool saddle_point = false);
} // namespace fsai::common
