// Copyright (C) 2026 fsai developers
//
// The glottis scene with the elastic fold (ElasticFold) and the
// quasi-steady Bernoulli flow with viscous loss (BernoulliFlow:
// viscous_surface_pressure on the moved surface polyline):
// `fsai_glottis --flow bernoulli --fold elastic`. The viscous term makes
// the load continuous through closure (see there); without it the strongly
// coupled step stalled or diverged at closures (IQN-ILS residuals up to
// 1e79 at p_sub 1.2 kPa, ζ 0.01).
//
// Each Newmark step: the interface variable is the surface displacement
// (owned dofs of each rank); the map H moves the surface by it, evaluates
// the Bernoulli pressure there, and solves the fold's step under that
// pressure (contact with the axis inside the step's Newton solve). First
// guess: the Newmark predictor u + Δt v + ½Δt² a. elastic.coupling =
// "explicit" (default) applies H once; "implicit" iterates it to its fixed
// point with FixedPointCoupling (IQN-ILS by default; see ElasticFold.h for
// why explicit is the default). p_sub ramps up smoothly over `ramp` (a step in
// p_sub would ring the fold's higher modes).
#pragma once
#include "BernoulliGlottis.h"
#include "ElasticFold.h"
#include "GlottisModel.h"
#include "Sample.h"
#include <coupling/FixedPointCoupling.h>
#include <memory>

namespace fsai::glottis
{
class ElasticBernoulliGlottis : public GlottisModel
{
public:
  ElasticBernoulliGlottis(MPI_Comm comm, const FoldProfile& profile,
                          const ElasticFoldParameters& ep,
                          const ContactParameters& contact,
                          const BernoulliGlottisParameters& bp, double ramp,
                          const coupling::CouplingParameters& cp,
                          const std::string& coupling_csv,
                          std::size_t coupling_rows_kept = std::string::npos);
  /// One coupled time step
  Sample step() override;
  /// The accepted state (fold, time) for a checkpoint (this rank's part);
  /// load() continues from the parts of all the checkpoint's ranks
  /// (coupling_rows_kept = the checkpoint's step keeps coupling.csv's
  /// rows). The coupling's history of earlier steps (IQN-ILS columns) is
  /// not kept: its unknowns, the fold surface's owned dofs, depend on the
  /// partition. Saving forgets it in this run too, so a run and its
  /// restart continue identically.
  io::RankState save();
  void load(const std::vector<io::RankState>& ranks);
  double time() const override { return _t; }
  void checkpoint(nlohmann::json& scalars,
                  std::optional<io::RankState>& fields) override;
  void restore(const nlohmann::json& checkpoint,
               const std::vector<io::RankState>& fields) override;
  std::vector<io::TimeSeriesWriter::Field> fold_fields() override;
  void describe(io::RunSummary& summary) override;
  ElasticFold& fold() { return _fold; }
  ElasticFold* elastic_fold() override { return &_fold; }
  const ElasticFold* elastic_fold() const override { return &_fold; }

private:
  /// Flow and pressure along the moved surface x at time t (p_sub ramped)
  SurfacePressure pressure(double t,
                           const std::vector<std::array<double, 2>>& x) const;
  BernoulliGlottisParameters _par;
  double _ramp;
  ElasticFold _fold;
  bool _explicit;
  coupling::FixedPointCoupling _loop;
  double _t = 0;
};
} // namespace fsai::glottis
