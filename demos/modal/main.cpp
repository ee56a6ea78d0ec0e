// Copyright (C) 2026 fsai developers
//
// fsai_modal: natural modes of a 3D vocal fold (docs/model.md §1): linear
// elasticity, generalized eigenproblem K x = ω² M x by SLEPc
// (shift-and-invert about 0), fold fixed on its lateral, anterior and
// posterior faces; homogeneous or body–cover (two layers). `--dim 2` takes
// the fold's coronal section instead, fixed on its lateral line: plane
// strain, or with --solid.clamped_length L the section of a fold clamped at
// z = 0, L (first anterior–posterior harmonic, forms/structure.py), the 2D
// model of the glottis scene's elastic fold set against this 3D fold.
//
// Sample runs:
//   ./fsai_modal                                  # 1 layer, P2, 10 modes
//   ./fsai_modal --layers 2 --cover.E 2000
//   mpirun -n 2 ./fsai_modal --fold.h 0.0007 -modal_eps_monitor
//   ./fsai_modal --dim 2 --solid.clamped_length 0.016   # clamped section
//
// Outputs in --output (default results/fsai_modal): modes.csv, modes.xdmf
// (mode k as "time" k, for ParaView), summary.json (frequencies_hz, dofs).

#include <common/Parameters.h>
#include <common/Runtime.h>
#include <common/errors.h>
#include <common/log.h>
#include <common/timer.h>
#include <io/CsvWriter.h>
#include <io/PointProbes.h>
#include <io/RunSummary.h>
#include <io/TimeSeriesWriter.h>
#include <io/output_dir.h>
#include <mesh/vocal_fold.h>
#include <structure/ElasticSolver.h>
#include <structure/modal.h>

#include <chrono>
#include <cmath>

namespace
{
struct ModalParameters
{
  std::string output = "results/fsai_modal";
  int dim = 3;
  int layers = 1;
  int order = 2;
  int modes = 10;
  bool check_result = false;
  fsai::structure::Material cover{2e3, 0.4, 1000.0};

  void bind(fsai::common::Parameters& p)
  {
    p.add("output", output, "output folder");
    p.add("dim", dim,
          "3 (the fold) or 2 (its coronal section, fixed on the lateral "
          "line; see --solid.clamped_length)");
    p.add("layers", layers, "1 (homogeneous) or 2 (body and cover)");
    p.add("order", order, "Lagrange degree of the displacement (1 or 2)");
    p.add("modes", modes, "number of modes");
    p.add("check-result", check_result,
          "fail unless f1 is in the male phonation range 85-155 Hz "
          "(docs/validation.md)");
    p.add("cover.E", cover.E, "Young's modulus of the cover [Pa]");
    p.add("cover.nu", cover.nu, "Poisson's ratio of the cover");
    p.add("cover.rho", cover.rho, "density of the cover [kg/m^3]");
  }
  void validate() const
  {
    fsai::require(dim == 2 or dim == 3, "--dim", "2 or 3", dim);
    fsai::require(layers == 1 or layers == 2, "--layers", "1 or 2", layers);
    fsai::require(order == 1 or order == 2, "--order", "1 or 2", order);
    fsai::require(modes >= 1 and modes <= 50, "--modes", "in [1, 50]", modes);
    cover.validate("--cover");
  }
};

const char* direction_word(int d)
{
  return d == 0   ? "medial-lateral"
         : d == 1 ? "inferior-superior"
                  : "anterior-posterior";
}
} // namespace

int main(int argc, char* argv[])
{
  return fsai::common::run_main(
      argc, argv,
      [](fsai::common::Runtime& rt)
      {
        const auto wall0 = std::chrono::steady_clock::now();
        // 1. Parameters (E = 8 kPa, ν = 0.4, ρ = 1000 kg/m³ by default)
        ModalParameters mp;
        fsai::structure::SolidParameters sp;
        fsai::mesh::VocalFoldGeometry geo;
        fsai::common::Parameters params(
            rt.program(), "Natural modes of a 3D vocal fold or its section");
        mp.bind(params);
        sp.bind(params);
        geo.bind(params);
        params.parse(rt.app_args());
        mp.validate();
        sp.degree = mp.order;
        sp.validate();
        geo.validate();
        params.print();
        fsai::io::prepare_output_dir(rt.comm(), mp.output);
        // Created first: its wall_s covers mesh, assembly and eigensolve
        fsai::io::RunSummary summary(rt.comm(), rt.program());
        summary.set_parameters(params.to_json());

        // 2. Mesh and materials
        fsai::mesh::MeshData m = [&]
        {
          fsai::common::ScopedTimer t("modal: mesh");
          return fsai::mesh::vocal_fold(rt.comm(), geo, mp.dim);
        }();
        fsai::structure::ElasticSolver solid(
            m.mesh, fsai::mesh::attached_facets(m), {}, sp, 1.0);
        if (mp.layers == 2)
          solid.set_material(fsai::mesh::cover_cells(*m.mesh, geo), mp.cover);

        // 3. Eigenmodes
        auto modes = fsai::structure::modal_analysis(solid, mp.modes);

        // 4. Describe each mode: dominant direction and the number of
        //    anterior-posterior half-waves of that component along the
        //    medial surface (a clamped section has one by construction,
        //    plane strain none)
        const int nz = 41;
        std::vector<std::array<double, 3>> line;
        const double xm = geo.depth - 0.25 * geo.a;
        const double ym = geo.height - geo.b - 0.5 * geo.t_medial;
        for (int i = 1; i < nz and mp.dim == 3; ++i)
          line.push_back({xm, ym, geo.length * i / nz});
        fsai::io::PointProbes probes(m.mesh, line);
        auto half_waves = [&](const fsai::structure::Mode& md)
        {
          if (mp.dim == 2)
            return sp.clamped_length > 0 ? 1 : 0;
          auto v = probes.values(*md.shape);
          int changes = 0;
          double last = 0.0, peak = 0.0;
          for (std::size_t i = 0; i < line.size(); ++i)
            peak = std::max(peak, std::abs(v[3 * i + md.dominant]));
          for (std::size_t i = 0; i < line.size(); ++i)
          {
            const double c = v[3 * i + md.dominant];
            if (std::abs(c) < 0.05 * peak)
              continue; // ignore near-nodes
            if (last != 0.0 and c * last < 0)
              ++changes;
            last = c;
          }
          return changes + 1;
        };
        fsai::io::CsvWriter csv(
            rt.comm(), mp.output + "/modes.csv",
            {"mode", "f_hz", "share_x", "share_y", "share_z", "ap_half_waves"});
        fsai::io::TimeSeriesWriter xdmf(
            mp.output + "/modes.xdmf",
            {modes.empty() ? nullptr : modes[0].shape});
        std::vector<double> freqs;
        std::vector<std::string> words;
        fsai::log::info("{:>4} {:>10}  {:<34} {:>22}", "mode", "f [Hz]",
                        "description", "energy share x/y/z");
        for (std::size_t k = 0; k < modes.size(); ++k)
        {
          const auto& md = modes[k];
          const int waves = half_waves(md);
          const std::string word
              = waves == 0 ? fmt::format("{} (plane strain)",
                                         direction_word(md.dominant))
                           : fmt::format("{} ({} a-p half-wave{})",
                                         direction_word(md.dominant), waves,
                                         waves == 1 ? "" : "s");
          freqs.push_back(md.frequency_hz);
          words.push_back(word);
          fsai::log::info("{:>4} {:>10.2f}  {:<34} {:>6.2f} {:>6.2f} {:>6.2f}",
                          k + 1, md.frequency_hz, word, md.direction_share[0],
                          md.direction_share[1], md.direction_share[2]);
          csv.row({double(k + 1), md.frequency_hz, md.direction_share[0],
                   md.direction_share[1], md.direction_share[2],
                   double(waves)});
          // One XDMF "time" per mode: copy the shape into the first field
          if (k > 0)
          {
            std::copy(md.shape->x()->array().begin(),
                      md.shape->x()->array().end(),
                      modes[0].shape->x()->mutable_array().begin());
          }
          xdmf.write(double(k + 1));
        }

        // 5. Summary
        summary.set("frequencies_hz", freqs);
        summary.set("descriptions", words);
        summary.set("dofs", solid.space()->dofmap()->index_map->size_global()
                                * solid.space()->dofmap()->index_map_bs());
        summary.set("cells",
                    m.mesh->topology().index_map(mp.dim)->size_global());
        summary.write(mp.output + "/summary.json");
        const double wall = std::chrono::duration<double>(
                                std::chrono::steady_clock::now() - wall0)
                                .count();
        fsai::log::info("Wall time {:.2f} s; wrote {}/summary.json", wall,
                        mp.output);

        // 6. Self-check: the fold's lowest mode in the male F0 range
        if (mp.check_result
            and (freqs.empty() or freqs[0] < 85.0 or freqs[0] > 155.0))
        {
          throw std::runtime_error(
              fmt::format("check failed: f1 = {:.2f} Hz is outside the male "
                          "range 85-155 Hz",
                          freqs.empty() ? NAN : freqs[0]));
        }
      });
}
