// Copyright (C) 2026 fsai developers
//
// fsai_formants: resonances (formants) of a vocal tract by the
// transfer-function method (docs/model.md §4, A7; acoustics::formant_study).
// A broadband volume-velocity pulse enters at the glottis; the pressure at
// the lips and at a microphone gives H(f) = P(f)/U(f); formants are the
// peaks of |H|, bandwidths their -3 dB widths. Models: "planar" (2D
// channel of width A(x)/L_g), "axisym" (tube of radius sqrt(A/π)), "1d"
// (chain matrices, no FE). Each FE run also prints the 1D model of the
// same area function and lip condition as an independent check.
//
// Sample runs:
//   ./fsai_formants --vowel u
//   ./fsai_formants --vowel a --model axisym --radiation pml
//   ./fsai_formants --area-function my_tract.csv --radiation pressure-release
//   mpirun -n 2 ./fsai_formants --vowel i --h 0.003
//
// Outputs in --output (default results/fsai_formants): transfer_function.csv,
// time_series.csv, pressure.xdmf (p' snapshots), transfer_function.png,
// summary.json (vowel, model, formants_hz, bandwidths_hz, ...).

#include <acoustics/formant_study.h>
#include <common/Parameters.h>
#include <common/Runtime.h>
#include <common/log.h>
#include <io/RunSummary.h>
#include <io/output_dir.h>

#include <chrono>
#include <cmath>
#include <fmt/ranges.h>

int main(int argc, char* argv[])
{
  return fsai::common::run_main(
      argc, argv,
      [](fsai::common::Runtime& rt)
      {
        namespace ac = fsai::acoustics;
        const auto wall0 = std::chrono::steady_clock::now();

        // 1. Parameters: defaults < --config file < command line
        ac::FormantParameters fp;
        ac::WaveParameters wave;
        ac::PulseParameters pulse;
        fsai::mesh::VocalTractGeometry geo;
        fsai::common::Parameters params(rt.program(),
                                        "Vocal-tract formants by the "
                                        "transfer-function method");
        fp.bind(params);
        wave.bind(params);
        pulse.bind(params);
        geo.bind(params);
        params.parse(rt.app_args());
        fp.validate();
        wave.validate();
        pulse.validate();
        params.print();
        fsai::io::prepare_output_dir(rt.comm(), fp.output);

        // 2. The area function and its 1D reference (always: it is cheap)
        const auto ref = ac::tract_reference(fp, wave, pulse, geo);
        const std::size_t n = std::size_t(fp.formants);
        auto first = [n](const std::vector<double>& v)
        {
          return std::vector<double>(v.begin(),
                                     v.begin() + long(std::min(n, v.size())));
        };
        fsai::log::info("Area function {}: {} sections, L = {:.2f} cm",
                        fp.area_function.empty()
                            ? fsai::mesh::vowel_file(fp.vowel)
                            : fp.area_function,
                        ref.area.size(), 100 * ref.area.length());
        fsai::log::info("1D model ({} lip end): F = {::.0f} Hz",
                        fp.radiation == "pressure-release" ? "p = 0"
                        : geo.baffle                       ? "flanged"
                                                           : "unflanged",
                        first(ref.formants));
        fsai::io::RunSummary summary(rt.comm(), rt.program());
        summary.set_parameters(params.to_json());
        summary.set("vowel",
                    fp.area_function.empty() ? fp.vowel : fp.area_function);
        summary.set("model", fp.model);
        summary.set("radiation", fp.radiation);
        summary.set("tract_length_m", ref.area.length());
        summary.set("formants_1d_hz", first(ref.formants));
        summary.set("bandwidths_1d_hz", first(ref.bandwidths));

        // 3. The study: 1D model, or the FE pulse run
        const ac::Formants fe
            = fp.model == "1d"
                  ? ac::formants_1d(rt.comm(), fp, wave, pulse, ref)
                  : ac::formants_fe(rt.comm(), fp, wave, pulse, geo, ref,
                                    summary);

        // 4. Report, chart, self-check against the 1D model
        summary.set("formants_hz", fe.f);
        summary.set("bandwidths_hz", fe.bandwidth);
        std::vector<double> dev;
        for (std::size_t k = 0; k < fe.f.size() and k < ref.formants.size();
             ++k)
          dev.push_back(100.0 * (fe.f[k] - ref.formants[k]) / ref.formants[k]);
        summary.set("deviation_from_1d_percent", dev);
        const double wall = std::chrono::duration<double>(
                                std::chrono::steady_clock::now() - wall0)
                                .count();
        summary.write(fp.output + "/summary.json");
        fsai::log::info("{:>4} {:>10} {:>10} {:>10} {:>8}", "", "F [Hz]",
                        "B [Hz]", "1D F [Hz]", "dev [%]");
        for (std::size_t k = 0; k < fe.f.size(); ++k)
        {
          fsai::log::info("F{:<3} {:>10.1f} {:>10.1f} {:>10.1f} {:>8.2f}",
                          k + 1, fe.f[k], fe.bandwidth[k],
                          k < ref.formants.size() ? ref.formants[k] : NAN,
                          k < dev.size() ? dev[k] : NAN);
        }
        fsai::log::info("Wall time {:.2f} s; wrote {}/summary.json", wall,
                        fp.output);
        fsai::io::draw_chart(rt.comm(), "plot_transfer_function.py", fp.output);
        ac::check_formants(fp, fe, dev, ref);
      });
}
