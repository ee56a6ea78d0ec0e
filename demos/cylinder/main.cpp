// Copyright (C) 2026 fsai developers
//
// fsai_cylinder: the DFG flow-around-a-cylinder benchmark (Schäfer & Turek
// 1996; benchmarks::dfg_cylinder) for the stabilised P1/P1 Navier–Stokes
// solver (docs/model.md §2). 2D-1 steady (Re = 20), 2D-2 periodic
// (Re = 100), 2D-3 transient. The defaults are the validated setting
// (mesh level 2, the fieldsplit/ILU solver for the transient cases);
// --quick is level 1.
//
// Sample runs:
//   ./fsai_cylinder --case 2D-1
//   mpirun -n 2 ./fsai_cylinder --case 2D-2
//   ./fsai_cylinder --case 2D-1 --level 0 --ale_amplitude 0.002 --dt 0.01
//   --t_end 1
//
// Outputs in --output (default results/fsai_cylinder): forces.csv (t, c_D,
// c_L, Δp), flow.xdmf, summary.json (case, cd, cl, dp; cd_max, cl_max,
// strouhal, wall_per_sim_s).

#include <benchmarks/dfg_cylinder.h>
#include <common/Parameters.h>
#include <common/Runtime.h>
#include <io/RunSummary.h>
#include <io/output_dir.h>

int main(int argc, char* argv[])
{
  return fsai::common::run_main(
      argc, argv,
      [](fsai::common::Runtime& rt)
      {
        namespace dfg = fsai::benchmarks::dfg_cylinder;
        dfg::DfgCylinder s;
        fsai::common::Parameters params(rt.program(),
                                        "DFG flow around a cylinder");
        s.bind(params);
        params.parse(rt.app_args());
        s.configure(params);
        params.print();
        fsai::io::prepare_output_dir(rt.comm(), s.bench.output);
        fsai::io::RunSummary summary(rt.comm(), rt.program());
        summary.set_parameters(params.to_json());
        summary.set("case", s.bench.dfg_case);
        dfg::run(rt.comm(), s, summary);
        summary.write(s.bench.output + "/summary.json");
      });
}
