// Copyright (C) 2026 fsai developers
//
// One interface for the glottis scene's four variants (docs/model.md §5):
// the fold (2-DOF rigid or elastic) times the flow (quasi-steady Bernoulli
// or ALE Navier–Stokes). A demo holds one pointer and steps it; the run
// loop (io/RunLoop) saves and restores it through the same interface.
#pragma once
#include "Sample.h"
#include <io/TimeSeriesWriter.h>
#include <io/run_state.h>
#include <memory>
#include <mpi.h>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

namespace fsai::io
{
class RunSummary;
}

namespace fsai::glottis
{
class ElasticFold;
class FlowChannel;
class TwoDofFold;

class GlottisModel
{
public:
  virtual ~GlottisModel() = default;
  /// Advance one time step
  virtual Sample step() = 0;
  /// Time of the last accepted step [s]
  virtual double time() const = 0;
  /// The state for a restart: scalars (into checkpoint.json) and, for FE
  /// variants, this rank's fields by mesh node
  virtual void checkpoint(nlohmann::json& scalars,
                          std::optional<io::RankState>& fields)
      = 0;
  /// Back from a checkpoint's JSON and the fields of all its ranks
  virtual void restore(const nlohmann::json& checkpoint,
                       const std::vector<io::RankState>& fields)
      = 0;
  /// After a failed step: the last good state's fields into `path`, and
  /// their time (nullopt for the Bernoulli variants, which have no fields)
  virtual std::optional<double> write_last_good(const std::string& path)
  {
    (void)path;
    return std::nullopt;
  }
  /// Fields of the flow (empty for the Bernoulli flow) and of the fold
  /// (empty for the 2-DOF fold), for XDMF output
  virtual std::vector<io::TimeSeriesWriter::Field> flow_fields() const
  {
    return {};
  }
  virtual std::vector<io::TimeSeriesWriter::Field> fold_fields() { return {}; }
  /// The elastic fold of the elastic variants (nullptr for the 2-DOF fold)
  virtual ElasticFold* elastic_fold() { return nullptr; }
  virtual const ElasticFold* elastic_fold() const { return nullptr; }
  /// The 2-DOF fold of the 2-DOF variants (nullptr for the elastic fold)
  virtual const TwoDofFold* two_dof_fold() const { return nullptr; }
  /// The FE flow's channel (nullptr for the Bernoulli flow)
  virtual const FlowChannel* flow_channel() const { return nullptr; }
  /// How often the flow mesh was built anew (remeshing): a new count starts
  /// a new flow output file
  virtual int remeshes() const { return 0; }
  /// Figures of the whole run, after the time loop, into the summary
  virtual void report(io::RunSummary& summary) const { (void)summary; }
  /// Log the fold (mass, stiffness or dofs, in-vacuo modes) and the flow
  /// (unknowns), and put them in the summary
  virtual void describe(io::RunSummary& summary) = 0;
};
} // namespace fsai::glottis
