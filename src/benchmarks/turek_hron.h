// Copyright (C) 2026 fsai developers
//
// The Turek & Hron (2006) benchmark family (references/turek_hron_setup.csv,
// turek_hron_results.csv): an elastic St.Venant–Kirchhoff beam behind a
// rigid cylinder in a channel flow.
//   CFD1–3  flow only, the beam rigid (docs/model.md §2): CFD1 and CFD2
//           steady (Picard), CFD3 periodic (BDF2);
//   CSM1–3  structure only under gravity g = 2 m/s² (P2 SVK, §1): CSM1 and
//           CSM2 static (Newton with load steps), CSM3 dynamic (Newmark);
//   FSI1–3  the strongly coupled partitioned scheme (§3).
// Each case's defaults are its validated setting (docs/validation.md);
// --quick gives a coarse, fast one.
#pragma once
#include <ale/MeshMotion.h>
#include <coupling/FixedPointCoupling.h>
#include <fluid/FluidSolver.h>
#include <io/CsvWriter.h>
#include <map>
#include <string>
#include <structure/ElasticSolver.h>
#include <vector>

namespace fsai::common
{
class Parameters;
class Runtime;
} // namespace fsai::common
namespace fsai::io
{
class RunSummary;
}

namespace fsai::benchmarks::turek_hron
{
/// The benchmark's own options
struct TurekHronParameters
{
  std::string output = "results/fsai_turek_hron";
  std::string bench_case = "FSI1";
  double h = 0.04;     ///< far-field mesh size [m]
  double h_i = 0.004;  ///< mesh size at the cylinder and the beam [m]
  double dt = 0.05;    ///< [s]
  double t_end = 6.0;  ///< [s]
  double window = 1.0; ///< periodic statistics over the last `window` s
  int load_steps = 4;  ///< CSM1/CSM2
  int write_every = 10;
  bool quick = false;
  bool check_result = false;

  void bind(fsai::common::Parameters& p);
  void validate() const;
  bool steady() const;
  bool periodic() const;
};

/// Every option of fsai_turek_hron: the benchmark's and its solvers'
struct TurekHron
{
  TurekHronParameters bench;
  fluid::FluidParameters fluid;
  structure::SolidParameters solid;
  ale::MeshMotionParameters ale;
  coupling::CouplingParameters coupling;

  TurekHron();
  void bind(fsai::common::Parameters& p);
  /// The case's validated setting (or --quick's) for every option not
  /// given, its material, then the checks
  void configure(const fsai::common::Parameters& p);
};

/// The series of point A and the forces, kept in memory and written row by
/// row (a stopped run leaves a readable CSV)
struct Series
{
  Series(MPI_Comm comm, const std::string& path);
  io::CsvWriter csv;
  std::vector<double> t, ux, uy, drag, lift;
  std::vector<int> iterations;
  void add(double time, std::array<double, 2> u, std::array<double, 3> F,
           int its);
  const std::vector<double>& column(const std::string& name) const;
};

/// Run the case (CFD, CSM or FSI family) into `series`
void run(fsai::common::Runtime& rt, const TurekHron& s, Series& series);

/// The summary (the same keys for every case: <q>_mean, <q>_amp, <q>_freq
/// for q = ux, uy, drag, lift, and their deviation from the reference),
/// logged; returns the deviations, "<column> <statistic>" → %
std::map<std::string, double> report(const TurekHron& s, const Series& series,
                                     double wall, io::RunSummary& summary);
/// --check-result: throws if a deviation is outside the case's band
void check(const TurekHron& s, const std::map<std::string, double>& error);
} // namespace fsai::benchmarks::turek_hron
