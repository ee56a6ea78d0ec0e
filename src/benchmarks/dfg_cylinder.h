// Copyright (C) 2026 fsai developers
//
// The DFG flow-around-a-cylinder benchmark (Schäfer & Turek 1996;
// references/dfg_cylinder.csv) for the stabilised P1/P1 Navier–Stokes
// solver (docs/model.md §2, E8–E11, E19, E20). 2D-1 is steady (Re = 20,
// Picard iteration); 2D-2 (Re = 100) periodic and 2D-3 (U_m(t) = 1.5
// sin(πt/8)) transient, stepped with BDF2 from rest. The defaults are the
// validated setting (level 2; the transient cases with the fieldsplit/ILU
// solver); --quick is level 1.
#pragma once
#include <fluid/FluidSolver.h>
#include <mpi.h>
#include <string>

namespace fsai::common
{
class Parameters;
}
namespace fsai::io
{
class RunSummary;
}

namespace fsai::benchmarks::dfg_cylinder
{
struct CylinderParameters
{
  std::string output = "results/fsai_cylinder";
  std::string dfg_case = "2D-1";
  int level = 2;        ///< h = 0.04 / 2^level, cylinder h / 8
  double dt = 0.005;    ///< transient cases: time step [s]
  double t_end = 8.0;   ///< transient cases: simulated time [s]
  double t_stats = 6.0; ///< 2D-2: statistics from this time on
  int write_every = 20;
  bool quick = false;
  bool check_result = false;
  double ale_amplitude = 0.0; ///< 2D-1 on an oscillating mesh [m]
  double ale_frequency = 2.0; ///< [Hz]

  void bind(fsai::common::Parameters& p);
  void validate() const;
};

/// Every option of fsai_cylinder
struct DfgCylinder
{
  CylinderParameters bench;
  fluid::FluidParameters fluid;

  DfgCylinder();
  void bind(fsai::common::Parameters& p);
  /// The validated setting (or --quick's) for every option not given
  void configure(const fsai::common::Parameters& p);
};

/// Run the case: forces.csv, flow.xdmf and the summary's keys (cd, cl, dp;
/// cd_max, cl_max, strouhal, wall_per_sim_s); throws if --check-result
/// is given and a band is missed
void run(MPI_Comm comm, const DfgCylinder& s, io::RunSummary& summary);
} // namespace fsai::benchmarks::dfg_cylinder
