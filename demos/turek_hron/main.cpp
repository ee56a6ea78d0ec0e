// Copyright (C) 2026 fsai developers
//
// fsai_turek_hron: the benchmark family of Turek & Hron (2006)
// (benchmarks::turek_hron): an elastic St.Venant–Kirchhoff beam behind a
// rigid cylinder in a channel flow.
//   CFD1–3  flow only, the beam rigid (CFD1, CFD2 steady; CFD3 periodic);
//   CSM1–3  structure only under gravity (CSM1, CSM2 static; CSM3 dynamic);
//   FSI1–3  the strongly coupled partitioned scheme (ALE mesh motion, flow,
//           solid, Aitken or IQN-ILS).
// Each case's defaults are its validated setting (docs/validation.md);
// --quick is a coarse look.
//
// Sample runs:
//   ./fsai_turek_hron --case FSI1
//   mpirun -n 2 ./fsai_turek_hron --case FSI3
//   ./fsai_turek_hron --case CSM1 --check-result
//   ./fsai_turek_hron --case FSI2 --quick
//
// Outputs in --output (default results/fsai_turek_hron): series.csv (t,
// ux(A), uy(A), drag, lift, iterations), coupling.csv (FSI), flow.xdmf or
// solid.xdmf, summary.json (case; ux/uy/drag/lift as _mean, _amp, _freq
// and their % deviation from the reference; wall_per_sim_s;
// coupling_iters_mean).

#include <benchmarks/turek_hron.h>
#include <common/Parameters.h>
#include <common/Runtime.h>
#include <io/RunSummary.h>
#include <io/output_dir.h>

#include <chrono>

int main(int argc, char* argv[])
{
  return fsai::common::run_main(
      argc, argv,
      [](fsai::common::Runtime& rt)
      {
        namespace th = fsai::benchmarks::turek_hron;
        th::TurekHron s;
        fsai::common::Parameters params(rt.program(),
                                        "Turek-Hron CFD/CSM/FSI benchmark");
        s.bind(params);
        params.parse(rt.app_args());
        s.configure(params);
        params.print();
        fsai::io::prepare_output_dir(rt.comm(), s.bench.output);
        fsai::io::RunSummary summary(rt.comm(), rt.program());
        summary.set_parameters(params.to_json());
        summary.set("case", s.bench.bench_case);

        th::Series series(rt.comm(), s.bench.output + "/series.csv");
        const auto wall0 = std::chrono::steady_clock::now();
        th::run(rt, s, series);
        const double wall = std::chrono::duration<double>(
                                std::chrono::steady_clock::now() - wall0)
                                .count();

        const auto error = th::report(s, series, wall, summary);
        summary.write(s.bench.output + "/summary.json");
        th::check(s, error);
      });
}
