// Copyright (C) 2026 fsai developers
//
// The glottis scene's options and what fsai_glottis does besides stepping:
// choosing the variant (GlottisModel), the linear-stability sweep of the
// reduced model, the mesh-motion replay of a computed trajectory, and the
// limit-cycle report (docs/model.md §5, G1–G7).
#pragma once
#include "BernoulliGlottis.h"
#include "ElasticFold.h"
#include "FlowGlottis.h"
#include "GlottisModel.h"
#include <io/Checkpointer.h>
#include <memory>
#include <mpi.h>
#include <string>
#include <vector>

namespace fsai::common
{
class Parameters;
}
namespace fsai::io
{
class RunSummary;
}

namespace fsai::glottis
{
/// The scene's own options ([top level] of fsai_glottis)
struct GlottisSceneParameters
{
  std::string output = "results/fsai_glottis";
  std::string flow = "bernoulli";
  std::string fold = "2dof";
  double p_sub = 1200;    ///< [Pa]: normal-to-loud speech (0.5–2 kPa)
  double duration = 0.25; ///< [s]
  double dt = 2e-5;       ///< [s]
  BernoulliGlottisParameters bernoulli; ///< --flow bernoulli's options
  double stats_from = 0.5; ///< statistics over t ≥ stats_from · duration
  int write_every = 50;    ///< XDMF every N steps (0: none)
  /// --fold elastic: fold_surface.csv every N steps (0: none)
  int surface_every = 0;
  std::vector<double> onset_sweep; ///< p_sub values of the stability sweep
  std::string replay; ///< fe: a series.csv whose fold states move the mesh
  double ramp = 5e-3; ///< elastic + Bernoulli: p_sub ramp [s]
  io::RestartOptions run;

  void bind(fsai::common::Parameters& p);
  void validate() const;
};

/// Every option of fsai_glottis: the scene's, the FE flow's, the folds'
struct GlottisScene
{
  GlottisSceneParameters scene;
  FlowGlottisSetup setup;
  ElasticFoldParameters elastic;

  void bind(fsai::common::Parameters& p);
  /// Checks and variant-dependent defaults (after parsing)
  void validate(const fsai::common::Parameters& p);
  /// The reduced flow's parameters
  BernoulliGlottisParameters bernoulli() const;
  /// The chosen variant (--flow × --fold), its coupling log continued after
  /// `rows_kept` rows on a restart
  std::unique_ptr<GlottisModel> make_model(MPI_Comm comm,
                                           const FoldProfile& profile,
                                           std::size_t rows_kept) const;
};

/// The glottis variant `flow` (fe, bernoulli) × `fold` (2dof, static,
/// elastic), its coupling log `coupling_csv` continued after `rows_kept`
/// rows on a restart; `ramp` the p_sub ramp of the elastic Bernoulli variant
std::unique_ptr<GlottisModel>
make_glottis(MPI_Comm comm, const FoldProfile& profile, const std::string& flow,
             const std::string& fold, const FlowGlottisSetup& setup,
             const ElasticFoldParameters& elastic,
             const BernoulliGlottisParameters& bernoulli, double ramp,
             const std::string& coupling_csv, std::size_t rows_kept);

/// The elastic fold in the FE flow (--fold elastic --flow fe) through
/// closure: the settings its validation was run with (docs/glottis.md, "The
/// elastic fold in the FE flow"), put in for every one of them not given
/// on the command line or in the config file (fsai_glottis and fsai_demo;
/// the values bound in `p`)
void apply_elastic_fe_defaults(const fsai::common::Parameters& p);

/// Those settings for the options' help (which lists each option's
/// scene-wide default): "; with --flow fe ... unless given: --key value, …"
std::string elastic_fe_defaults_help();

/// --onset_sweep: linear stability of the reduced model at each p_sub
/// (printed and written to DIR/onset.csv)
void onset_sweep(MPI_Comm comm, const GlottisScene& s,
                 const FoldProfile& profile);

/// --replay: the FE mesh moved through a run's fold states, its quality
void replay_mesh_motion(FlowGlottis& fem, const std::string& path,
                        io::RunSummary& summary);

/// Limit-cycle statistics of the series (t, g, Q) after stats_from, logged
/// and put in the summary (f0, open quotient, peak flow, leakage, …)
void report_limit_cycle(const GlottisScene& s, const std::vector<double>& t,
                        const std::vector<double>& g,
                        const std::vector<double>& Q, double max_penetration,
                        double loop_wall, io::RunSummary& summary);
} // namespace fsai::glottis
