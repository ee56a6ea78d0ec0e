// Copyright (C) 2026 fsai developers
//
// One interface for the voice's acoustics (docs/model.md §4), driven one
// way by the glottis after each of its steps:
//  - TubeAcoustics (--acoustics 1d, A9): the vowel's tract as a 1D
//    transmission line in time, fed by the glottal flow Q(t), radiating
//    from the lips to the microphone;
//  - FeAcoustics (--acoustics fe, E14/E21, A1–A6): the wave equation on a
//    fixed planar domain that holds the flow domain and continues it by
//    the tract and a radiation region, with the sources of VoiceSource.
#pragma once
#include <cstdint>
#include <glottis/GlottisModel.h>
#include <io/TimeSeriesWriter.h>
#include <io/run_state.h>
#include <memory>
#include <mpi.h>
#include <nlohmann/json.hpp>
#include <optional>
#include <vector>

namespace fsai::glottis
{
class FoldProfile;
}

namespace fsai::voice
{
struct VoiceScene;
struct VoiceTract;

class VoiceAcoustics
{
public:
  virtual ~VoiceAcoustics() = default;
  /// Start (or continue after a restart) from the glottis's state, with
  /// the last converged glottal flow q_last [m³/s]
  virtual void start(const glottis::GlottisModel& glottis, double q_last) = 0;
  /// One step of the sound after the glottis's step `s`
  virtual void step(const glottis::GlottisModel& glottis,
                    const glottis::Sample& s)
      = 0;
  /// Pressure at the lips and at the microphone after the step [Pa]
  virtual double p_lips() const = 0;
  virtual double p_mic() const = 0;
  /// Unknowns of the acoustic model
  virtual std::int64_t dofs() const = 0;
  /// The state for a checkpoint (scalars into checkpoint.json; fields added
  /// to this rank's), and back
  virtual void checkpoint(nlohmann::json& scalars,
                          std::optional<io::RankState>& fields) const = 0;
  virtual void restore(const nlohmann::json& checkpoint,
                       const std::vector<io::RankState>& fields)
      = 0;
  /// Fields for XDMF output (none for the 1D tract)
  virtual std::vector<io::TimeSeriesWriter::Field> fields() const { return {}; }
};

/// The scene's acoustics (--acoustics) for its tract and glottis
std::unique_ptr<VoiceAcoustics>
make_acoustics(MPI_Comm comm, const VoiceScene& s,
               const glottis::FoldProfile& profile, const VoiceTract& tract,
               const glottis::GlottisModel& glottis);
} // namespace fsai::voice
