// Copyright (C) 2026 fsai developers
#pragma once

#include <cstdint>
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
/// `unknowns` (global size, if known): a small 2D system (at most
/// small_system_unknowns) is factorised by PETSc's LU in reverse
/// Cuthill–McKee order, and in parallel redundantly on every rank
/// (PCREDUNDANT) instead of by MUMPS across ranks. Measured on the
/// Turek–Hron beam (P2, 3934 unknowns, 2 ranks): 2.7 ms per factorisation
/// and solve against MUMPS's 6.0 ms; serially RCM 2.3 ms against nested
/// dissection's 3.7 ms. Set the KSP's options prefix before the call: the
/// redundant solver's inner KSP takes it (prefix + "redundant_").
void configure_direct_solver(KSP ksp, MPI_Comm comm, int tdim,
                             bool saddle_point = false,
                             std::int64_t unknowns = -1);

/// Largest system that configure_direct_solver treats as small
constexpr std::int64_t small_system_unknowns = 20000;
} // namespace fsai::common
