// Copyright (C) 2026 fsai developers
#include "VoiceAcoustics.h"
#include "VoiceScene.h"
#include "VoiceSource.h"
#include <acoustics/MonopoleMicrophone.h>
#include <acoustics/TubeTract.h>
#include <cmath>
#include <common/errors.h>
#include <common/timer.h>
#include <fmt/format.h>
#include <glottis/ElasticFold.h>
#include <glottis/FlowChannel.h>
#include <glottis/TwoDofFold.h>
#include <io/PointProbes.h>
#include <stdexcept>

namespace
{
using fsai::glottis::GlottisModel;
using fsai::glottis::Sample;

/// --acoustics 1d (A9): the glottal flow drives the line; a step whose
/// coupling did not converge has a meaningless Q (the FE path's monopole
/// holds it too, A6), so the line sees the last converged one
class TubeAcoustics : public fsai::voice::VoiceAcoustics
{
public:
  TubeAcoustics(const fsai::mesh::AreaFunction& area,
                const fsai::acoustics::TubeTractParameters& p, double dt)
      : _tract(area, p, dt)
  {
  }
  void start(const GlottisModel&, double q_last) override { _q = q_last; }
  void step(const GlottisModel&, const Sample& s) override
  {
    fsai::common::ScopedTimer timer("demo: sound step");
    if (s.converged)
      _q = s.Q;
    _tract.step(_q);
  }
  double p_lips() const override { return _tract.p_lips(); }
  double p_mic() const override { return _tract.p_mic(); }
  std::int64_t dofs() const override
  {
    return std::int64_t(2 * _tract.sections() + 1);
  }
  void checkpoint(nlohmann::json& scalars,
                  std::optional<fsai::io::RankState>&) const override
  {
    scalars["tract1d"] = _tract.save();
    scalars["tract1d_q"] = _q;
  }
  void restore(const nlohmann::json& checkpoint,
               const std::vector<fsai::io::RankState>&) override
  {
    _tract.load(checkpoint.at("tract1d"));
    _q = checkpoint.at("tract1d_q");
  }

private:
  fsai::acoustics::TubeTract _tract;
  double _q = 0;
};

/// --acoustics fe: the wave equation with VoiceSource's sources; the
/// fold (2-DOF or elastic) moves the slit and the fold's wall
class FeAcoustics : public fsai::voice::VoiceAcoustics
{
public:
  FeAcoustics(MPI_Comm comm, const fsai::voice::VoiceScene& s,
              const fsai::glottis::FoldProfile& profile,
              const fsai::voice::VoiceTract& tract, const GlottisModel& glottis)
      : _profile(profile),
        _sound(fsai::voice::make_sound(comm, s, profile, tract)),
        _source(comm, s.source, s.glottis, profile, glottis.flow_channel(),
                _sound.mesh, *_sound.solver, s.voice.dt),
        _probes(_sound.mesh.mesh, probe_points(s, _sound.x_lips))
  {
    if (!s.domain.radiation_region)
    {
      // The half planar model's lip flow per unit depth, times 2 L_g
      _depth = 2 * s.glottis.geometry.depth;
      _mic.emplace(s.voice.mic_distance, s.wave.c0, s.wave.rho0, s.voice.dt,
                   0.0);
    }
  }
  void start(const GlottisModel& glottis, double q_last) override
  {
    _source.start(wall(glottis), q_last);
  }
  void step(const GlottisModel& glottis, const Sample& s) override
  {
    fsai::common::ScopedTimer timer("demo: sound step");
    _source.apply(wall(glottis), glottis.flow_channel(), s);
    _sound.solver->step();
    _p = _probes.values(*_sound.solver->pressure());
    if (_mic)
      _mic->record(_depth * _sound.solver->radiated_flow_rate());
  }
  double p_lips() const override { return _p[0]; }
  double p_mic() const override { return _mic ? _mic->pressure() : _p[1]; }
  std::int64_t dofs() const override { return _sound.solver->dofs(); }
  void checkpoint(nlohmann::json& scalars,
                  std::optional<fsai::io::RankState>& fields) const override
  {
    if (!fields)
      fields.emplace();
    _sound.solver->save(*fields, "sound.");
    _source.save(*fields);
    if (_mic)
      scalars["mic"] = _mic->save();
  }
  void restore(const nlohmann::json& checkpoint,
               const std::vector<fsai::io::RankState>& fields) override
  {
    _sound.solver->load(fields, "sound.");
    _source.load(fields);
    if (_mic)
      _mic->load(checkpoint.at("mic"));
  }
  std::vector<fsai::io::TimeSeriesWriter::Field> fields() const override
  {
    return {_sound.solver->pressure()};
  }

private:
  /// The lips, and the microphone when it is in the radiation region
  static std::vector<std::array<double, 3>>
  probe_points(const fsai::voice::VoiceScene& s, double x_lips)
  {
    std::vector<std::array<double, 3>> x = {{x_lips, 0.0, 0.0}};
    if (s.domain.radiation_region)
      x.push_back({x_lips + s.voice.mic_distance, 0.0, 0.0});
    return x;
  }
  /// The fold's wall as the sources see it (collective for the elastic
  /// fold)
  fsai::voice::FoldWall wall(const GlottisModel& glottis) const
  {
    if (const auto* f = glottis.two_dof_fold())
      return fsai::voice::fold_wall(*f, _profile);
    if (const auto* f = glottis.elastic_fold())
      return fsai::voice::fold_wall(*f);
    throw std::logic_error("FE acoustics: a glottis without a fold");
  }
  const fsai::glottis::FoldProfile& _profile;
  fsai::voice::Sound _sound;
  fsai::voice::VoiceSource _source;
  fsai::io::PointProbes _probes;
  std::vector<double> _p{0.0, 0.0};
  /// With the piston load (A11): the monopole of the lip flow
  std::optional<fsai::acoustics::MonopoleMicrophone> _mic;
  double _depth = 0;
};
} // namespace

//-----------------------------------------------------------------------------
std::unique_ptr<fsai::voice::VoiceAcoustics> fsai::voice::make_acoustics(
    MPI_Comm comm, const VoiceScene& s, const glottis::FoldProfile& profile,
    const VoiceTract& tract, const glottis::GlottisModel& glottis)
{
  if (s.voice.acoustics == "fe")
  {
    return std::make_unique<FeAcoustics>(comm, s, profile, tract, glottis);
  }
  acoustics::TubeTractParameters p;
  p.c0 = s.wave.c0;
  p.rho0 = s.wave.rho0;
  p.wall = tract.wall;
  p.mic_distance = s.voice.mic_distance;
  return std::make_unique<TubeAcoustics>(tract.area, p, s.voice.dt);
}
