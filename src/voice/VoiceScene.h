// Copyright (C) 2026 fsai developers
//
// The voice scene (fsai_demo, docs/model.md §4): its options, the vocal
// tract it is built on and that tract's 1D formants, the acoustic domain
// with its boundary roles, and the analysis of the sound at the
// microphone (f0, LPC formants of the periodic part, SPL, spectrum, WAV).
#pragma once
#include "VoiceSource.h"
#include <acoustics/WaveSolver.h>
#include <acoustics/tube_model.h>
#include <glottis/BernoulliGlottis.h>
#include <glottis/ElasticFold.h>
#include <glottis/FlowGlottis.h>
#include <glottis/waveform.h>
#include <io/Checkpointer.h>
#include <memory>
#include <mesh/MeshData.h>
#include <mesh/area_function.h>
#include <mesh/voice_domain.h>
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

namespace fsai::voice
{
/// The scene's own options (top level of fsai_demo)
struct VoiceParameters
{
  std::string output = "results/fsai_demo";
  /// The fidelity (docs/voice.md, "Three fidelities"): flow fe|bernoulli,
  /// acoustics fe|1d, fold 2dof|elastic
  std::string flow = "fe";
  std::string acoustics = "fe";
  std::string fold = "2dof";
  double ramp = 5e-3; ///< --fold elastic --flow bernoulli: p_sub ramp [s]
  std::string vowel = "u";
  std::string area_function; ///< overrides vowel
  std::string tract = "vowel";
  /// --acoustics fe: the vowel's area function from the glottis on (the
  /// acoustic tract is the vowel's; the flow domain's channel overlaps
  /// it) or from the flow domain's outlet (its channel, 2.88 cm², replaces
  /// the tract's first 40 mm)
  std::string tract_start = "glottis";
  double tube_length = 0.04; ///< --tract tube [m]
  double tube_area = 3e-4;   ///< [m²]
  double p_sub = 1200;       ///< [Pa]
  double duration = 0.1;     ///< [s]
  double dt = 2e-5;          ///< [s]
  bool quick = false;
  /// --acoustics fe: "piston" (the tract ends at the lips under the
  /// flanged piston's load, A11: its formants are the area function's) or
  /// a planar radiation region ("sommerfeld", "pml"), whose 2D radiation
  /// detunes wide-mouthed vowels ([a] F1/F2 merge, docs/voice.md)
  std::string radiation = "piston";
  std::string subglottal = "absorbing";
  bool yielding_walls = true;
  double layer = 0.02;        ///< [m]
  double mic_distance = 0.03; ///< [m] beyond the lips, on the axis
  double stats_from = 0.5;
  int write_every = 100;
  int wav_rate = 44100;
  bool check_result = false;
  bool report = true; ///< draw report.png (Python, about a second)
  /// Analyse the series.csv of the run in --output again (no time loop):
  /// the voice measures into reanalysis.json
  bool reanalyse = false;
  double check_f0_tolerance = 0.01;   ///< relative
  double check_formant_tolerance = 0; ///< relative, F1 and F2 (0: none)
  io::RestartOptions run;

  void bind(fsai::common::Parameters& p);
  void validate() const;
};

/// Every option of fsai_demo: the scene's, the coupling's, the glottis
/// scene's (FE flow), the sound's and the acoustic domain's
struct VoiceScene
{
  VoiceParameters voice;
  VoiceSourceParameters source;
  glottis::FlowGlottisSetup glottis;
  glottis::BernoulliGlottisParameters bernoulli;
  glottis::ElasticFoldParameters elastic;
  acoustics::WaveParameters wave;
  mesh::VoiceDomainGeometry domain;

  VoiceScene();
  void bind(fsai::common::Parameters& p);
  /// --quick: coarse defaults, set before parsing so that any option given
  /// with it still overrides them
  void apply_quick(const std::vector<std::string>& args);
  /// Checks and fold-dependent defaults (after parsing): the elastic fold
  /// in the FE flow on the glottis preset's settings
  /// (glottis::apply_elastic_fe_defaults) and flow mesh
  void validate(const fsai::common::Parameters& p);
  /// The glottis (--flow × --fold), its coupling log continued after
  /// `rows_kept` rows on a restart
  std::unique_ptr<glottis::GlottisModel>
  make_glottis(MPI_Comm comm, const glottis::FoldProfile& profile,
               std::size_t rows_kept) const;
};

/// The tract the voice sounds in: the vowel's area function (or a tube),
/// for the FE acoustics with its first part replaced by the flow domain's
/// channel, and its 1D transfer-function formants (A7) with the walls
struct VoiceTract
{
  std::string label;
  mesh::AreaFunction area;
  acoustics::TubeWall wall;
  std::vector<double> formants, bandwidths; ///< closed glottis
  std::vector<double> domain_formants;      ///< the acoustic domain as built
  /// |P_lips/U_g| of the closed-glottis 1D model every 10 Hz [Hz, dB]
  std::vector<double> response_f, response_db;
};
VoiceTract make_tract(const VoiceScene& s, const glottis::FoldProfile& profile);

/// The acoustic domain and its wave solver with the scene's boundary roles
/// (A2–A4); the lips' x and the microphone's
struct Sound
{
  mesh::MeshData mesh;
  std::unique_ptr<acoustics::WaveSolver> solver;
  double x_lips = 0;
};
Sound make_sound(MPI_Comm comm, const VoiceScene& s,
                 const glottis::FoldProfile& profile, const VoiceTract& tract);

/// What --check-result checks
struct VoiceMeasures
{
  double f0_hz, f0_fold_hz, spl_db;
  std::vector<double> formants_hz, tract_formants_hz;
};
/// The fold's cycle and the sound's analysis over t ≥ stats_from·duration:
/// summary keys, spectrum.csv, sound.wav
VoiceMeasures
analyse_voice(MPI_Comm comm, const VoiceScene& s, const VoiceTract& tract,
              const std::vector<double>& t, const std::vector<double>& g,
              const std::vector<double>& Q, const std::vector<double>& p_mic,
              io::RunSummary& summary);
/// --check-result: throws unless the sound is audible, the fold's f0 in
/// the male range and the sound's f0 the fold's
void check_voice(const VoiceScene& s, const VoiceMeasures& m);
} // namespace fsai::voice
