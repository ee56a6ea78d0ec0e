// Copyright (C) 2026 fsai developers
#include "GlottisModel.h"
#include "BernoulliGlottis.h"
#include "ElasticBernoulliGlottis.h"
#include "ElasticFlowGlottis.h"
#include "FlowGlottis.h"
#include <common/log.h>
#include <io/RunSummary.h>
#include <structure/modal.h>

namespace
{
using fsai::glottis::FoldProfile;

/// The 2-DOF fold: geometry, mass, stiffness, in-vacuo modes, Hertz k_H
void describe_two_dof(const FoldProfile& profile,
                      const fsai::glottis::TwoDofFold& fold,
                      const fsai::glottis::ContactParameters& contact,
                      fsai::io::RunSummary& summary)
{
  const auto mp = profile.mass_properties(1.0); // area and centroid only
  const auto md = fsai::glottis::modes(fold.stiffness(), fold.mass());
  fsai::log::info(
      "fold: area {:.2f} mm², centroid ({:.3f}, {:.3f}) mm, mass {:.3f} g, "
      "I_EA {:.3e} kg m², k_h {:.1f} N/m, k_phi {:.3e} N m; in-vacuo {:.1f} / "
      "{:.1f} Hz; Hertz k_H {:.3e} N/m^1.5",
      mp.area * 1e6, mp.centroid[0] * 1e3, mp.centroid[1] * 1e3,
      fold.mass()[0][0] * 1e3, fold.mass()[1][1], fold.stiffness()[0][0],
      fold.stiffness()[1][1], md.frequency_hz[0], md.frequency_hz[1],
      fsai::glottis::hertz_stiffness(contact,
                                     profile.geometry().medial_radius));
  summary.set("fold_mass_kg", fold.mass()[0][0]);
  summary.set("invacuo_frequencies_hz",
              std::vector<double>{md.frequency_hz[0], md.frequency_hz[1]});
}

/// The elastic fold: dofs and its first three in-vacuo modes
void describe_elastic(fsai::glottis::ElasticFold& fold,
                      fsai::io::RunSummary& summary)
{
  std::vector<double> f;
  for (const auto& m : fsai::structure::modal_analysis(fold.solver(), 3))
    f.push_back(m.frequency_hz);
  fsai::log::info("elastic fold: {} dofs, {} surface points; in-vacuo modes "
                  "{:.1f} / {:.1f} / {:.1f} Hz",
                  fold.dofs(), fold.surface_size(), f.at(0), f.at(1), f.at(2));
  std::int64_t cover = 0;
  for (auto c : fold.cover_cells())
    cover += c < fold.mesh().mesh->topology().index_map(2)->size_local();
  MPI_Allreduce(MPI_IN_PLACE, &cover, 1, MPI_INT64_T, MPI_SUM, fold.comm());
  if (cover > 0)
    fsai::log::info("elastic fold: body-cover, {} cover cells", cover);
  summary.set("fold_dofs", fold.dofs());
  summary.set("fold_cover_cells", cover);
  summary.set("invacuo_frequencies_hz", f);
}

std::vector<fsai::io::TimeSeriesWriter::Field>
fold_fields_of(fsai::glottis::ElasticFold& fold)
{
  return {fold.solver().displacement(), fold.solver().velocity()};
}
} // namespace

// Reduced model: the state is three pairs and the load, in the JSON
//-----------------------------------------------------------------------------
void fsai::glottis::BernoulliGlottis::checkpoint(nlohmann::json& scalars,
                                                 std::optional<io::RankState>&)
{
  const auto st = state();
  scalars["state"] = {{"t", st.t}, {"fold", st.fold}, {"load", st.load}};
}
//-----------------------------------------------------------------------------
void fsai::glottis::BernoulliGlottis::restore(const nlohmann::json& checkpoint,
                                              const std::vector<io::RankState>&)
{
  const auto& st = checkpoint.at("state");
  set_state({st.at("t").get<double>(),
             st.at("fold").get<std::array<std::array<double, 2>, 3>>(),
             st.at("load").get<std::array<double, 2>>()});
}
//-----------------------------------------------------------------------------
void fsai::glottis::BernoulliGlottis::describe(io::RunSummary& summary)
{
  describe_two_dof(_profile, _fold, _contact, summary);
}

// FE flow, 2-DOF fold
//-----------------------------------------------------------------------------
void fsai::glottis::FlowGlottis::checkpoint(nlohmann::json&,
                                            std::optional<io::RankState>& f)
{
  f = save();
}
//-----------------------------------------------------------------------------
void fsai::glottis::FlowGlottis::restore(const nlohmann::json&,
                                         const std::vector<io::RankState>& f)
{
  load(f);
}
//-----------------------------------------------------------------------------
std::vector<fsai::io::TimeSeriesWriter::Field>
fsai::glottis::FlowGlottis::flow_fields() const
{
  return _channel.fields();
}
//-----------------------------------------------------------------------------
void fsai::glottis::FlowGlottis::describe(io::RunSummary& summary)
{
  summary.set("flow_dofs", _channel.describe());
  describe_two_dof(_profile, _fold, _contact, summary);
}
//-----------------------------------------------------------------------------
void fsai::glottis::FlowGlottis::report(io::RunSummary& summary) const
{
  // The iterative flow solver's Krylov iterations per solve
  const auto& flow = _channel.flow();
  if (flow.krylov_solves() > 0)
  {
    summary.set("krylov_iterations_mean", flow.krylov_iterations_mean());
  }
}

// Bernoulli flow, elastic fold
//-----------------------------------------------------------------------------
void fsai::glottis::ElasticBernoulliGlottis::checkpoint(
    nlohmann::json&, std::optional<io::RankState>& f)
{
  f = save();
}
//-----------------------------------------------------------------------------
void fsai::glottis::ElasticBernoulliGlottis::restore(
    const nlohmann::json&, const std::vector<io::RankState>& f)
{
  load(f);
}
//-----------------------------------------------------------------------------
std::vector<fsai::io::TimeSeriesWriter::Field>
fsai::glottis::ElasticBernoulliGlottis::fold_fields()
{
  return fold_fields_of(_fold);
}
//-----------------------------------------------------------------------------
void fsai::glottis::ElasticBernoulliGlottis::describe(io::RunSummary& summary)
{
  describe_elastic(_fold, summary);
}

// FE flow, elastic fold
//-----------------------------------------------------------------------------
void fsai::glottis::ElasticFlowGlottis::checkpoint(
    nlohmann::json&, std::optional<io::RankState>& f)
{
  f = save();
}
//-----------------------------------------------------------------------------
void fsai::glottis::ElasticFlowGlottis::restore(
    const nlohmann::json&, const std::vector<io::RankState>& f)
{
  load(f);
}
//-----------------------------------------------------------------------------
std::vector<fsai::io::TimeSeriesWriter::Field>
fsai::glottis::ElasticFlowGlottis::flow_fields() const
{
  return _channel->fields();
}
//-----------------------------------------------------------------------------
std::vector<fsai::io::TimeSeriesWriter::Field>
fsai::glottis::ElasticFlowGlottis::fold_fields()
{
  return fold_fields_of(_fold);
}
//-----------------------------------------------------------------------------
void fsai::glottis::ElasticFlowGlottis::describe(io::RunSummary& summary)
{
  summary.set("flow_dofs", _channel->describe());
  describe_elastic(_fold, summary);
}
