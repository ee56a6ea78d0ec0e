// Copyright (C) 2026 fsai developers
//
// fsai_poisson: convergence study of a manufactured Poisson solution on
// gmsh-built unit squares/cubes. It checks the machinery every scene stands
// on: UFL form variants (triangle/tetrahedron, P1/P2) compiled by FFCx at
// build time, gmsh meshes with tagged boundaries distributed by DOLFINx,
// PETSc solvers tuned from the command line, XDMF/CSV/JSON output.
//
// Sample runs:
//   ./fsai_poisson                                   # 2D, P1, 4 levels
//   ./fsai_poisson --dim 3 --degree 2 --h0 0.25 --levels 3
//   mpirun -n 2 ./fsai_poisson -poisson_ksp_monitor  # PETSc options pass
//   ./fsai_poisson --config poisson.toml --check-result
//
// Outputs in --output (default results/fsai_poisson): convergence.csv,
// solution.xdmf (finest level), summary.json (errors_l2, h, dofs, rates,
// rate_l2, wall_s).

#include <common/Parameters.h>
#include <common/Runtime.h>
#include <common/errors.h>
#include <common/log.h>
#include <io/CsvWriter.h>
#include <io/Progress.h>
#include <io/RunSummary.h>
#include <io/TimeSeriesWriter.h>
#include <io/output_dir.h>
#include <mesh/builders.h>
#include <verification/poisson_mms.h>

#include <cmath>

namespace
{
/// Parameters of this demo (section [study] in a config file)
struct StudyParameters
{
  std::string output = "results/fsai_poisson";
  int dim = 2;
  int degree = 1;
  double h0 = 0.2; // Mesh size of the coarsest level [unit lengths]
  int levels = 4;  // Number of meshes, h halved each time
  bool check_result = false;

  void bind(fsai::common::Parameters& p)
  {
    p.add("output", output, "output folder");
    p.add("study.dim", dim, "space dimension: 2 (triangles) or 3 (tets)");
    p.add("study.degree", degree, "Lagrange degree: 1 or 2");
    p.add("study.h0", h0, "mesh size of the coarsest level");
    p.add("study.levels", levels, "number of meshes (h halved each time)");
    p.add("check-result", check_result,
          "fail unless the finest rate is within 0.2 of degree + 1");
  }

  void validate() const
  {
    fsai::require(dim == 2 or dim == 3, "--study.dim", "2 or 3", dim);
    fsai::require(degree == 1 or degree == 2, "--study.degree", "1 or 2",
                  degree);
    fsai::require_positive("--study.h0", h0);
    fsai::require(levels >= 1 and levels <= 8, "--study.levels", "in [1, 8]",
                  levels);
  }
};
} // namespace

int main(int argc, char* argv[])
{
  return fsai::common::run_main(
      argc, argv,
      [](fsai::common::Runtime& rt)
      {
        // NOTE(DOLFINx 0.5.2): common/Scatterer.h has `using namespace
        // dolfinx`, so fsai's common/io/mesh are always fully qualified
        // 1. Parameters: defaults < --config file < command line
        StudyParameters sp;
        fsai::common::Parameters params(rt.program(),
                                        "Poisson manufactured-solution study");
        sp.bind(params);
        params.parse(rt.app_args());
        sp.validate();
        params.print();
        fsai::io::prepare_output_dir(rt.comm(), sp.output);

        fsai::io::RunSummary summary(rt.comm(), rt.program());
        summary.set_parameters(params.to_json());
        fsai::io::CsvWriter csv(
            rt.comm(), sp.output + "/convergence.csv",
            {"level", "h", "h_max", "dofs", "error_l2", "rate", "iterations"});

        // 2. Convergence study on successively halved meshes
        std::vector<double> hs, h_max, errors, rates;
        std::vector<std::int64_t> dofs;
        fsai::io::Progress progress("level", sp.levels, 0.0);
        fsai::verification::PoissonResult finest;
        for (int k = 0; k < sp.levels; ++k)
        {
          const double h = sp.h0 / std::pow(2.0, k);
          fsai::mesh::MeshData m
              = sp.dim == 2
                    ? fsai::mesh::rectangle(rt.comm(), {0, 0}, {1, 1}, h)
                    : fsai::mesh::box(rt.comm(), {0, 0, 0}, {1, 1, 1}, h);
          finest = fsai::verification::solve_poisson_mms(m.mesh, sp.degree);
          // Rates use the nominal (gmsh target) size: the largest cell of an
          // unstructured mesh fluctuates from level to level
          const double rate
              = k == 0 ? NAN
                       : fsai::verification::convergence_rate(
                           hs.back(), errors.back(), h, finest.error_L2);
          hs.push_back(h);
          h_max.push_back(finest.h);
          errors.push_back(finest.error_L2);
          dofs.push_back(finest.dofs);
          if (k > 0)
            rates.push_back(rate);
          csv.row({double(k), h, finest.h, double(finest.dofs), finest.error_L2,
                   rate, double(finest.iterations)});
          progress.update(k + 1,
                          fmt::format("h = {:.4f}  dofs = {}  L2 error = "
                                      "{:.3e}  rate = {:.2f}  ksp its = {}",
                                      h, finest.dofs, finest.error_L2, rate,
                                      finest.iterations));
        }

        // 3. Output: finest solution for ParaView, summary
        fsai::io::TimeSeriesWriter(sp.output + "/solution.xdmf", {finest.u})
            .write(0.0);
        summary.set("dim", sp.dim);
        summary.set("degree", sp.degree);
        summary.set("h", hs);
        summary.set("h_max", h_max);
        summary.set("dofs", dofs);
        summary.set("errors_l2", errors);
        summary.set("rates", rates);
        if (!rates.empty())
          summary.set("rate_l2", rates.back());
        summary.write(sp.output + "/summary.json");
        fsai::log::info("Wrote {}/summary.json", sp.output);

        // 4. Self-check
        if (sp.check_result)
        {
          if (rates.empty())
            throw fsai::InputError("--check-result needs --study.levels >= 2");
          const double expected = sp.degree + 1;
          if (std::abs(rates.back() - expected) > 0.2)
          {
            throw std::runtime_error(
                fmt::format("check failed: L2 rate {:.3f}, expected {} +- 0.2",
                            rates.back(), expected));
          }
          fsai::log::info("check passed: L2 rate {:.3f} (expected {})",
                          rates.back(), expected);
        }
      });
}
