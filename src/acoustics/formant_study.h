// Copyright (C) 2026 fsai developers
//
// Vocal-tract formants by the transfer-function method (docs/model.md §4,
// A7): a broadband volume-velocity pulse enters at the glottis of the FE
// tract (planar 2D channel of width A(x)/L_g, or axisymmetric tube); the
// pressure at the lips and at a microphone gives H(f) = P(f)/U(f); the
// formants are the peaks of |H|, the bandwidths their −3 dB widths. The
// 1D chain-matrix model of the same tract is the independent check.
#pragma once
#include <acoustics/WaveSolver.h>
#include <acoustics/pulse_response.h>
#include <acoustics/tube_model.h>
#include <mesh/area_function.h>
#include <mesh/vocal_tract.h>
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

namespace fsai::acoustics
{
/// Options of fsai_formants (program-level keys)
struct FormantParameters
{
  std::string output = "results/fsai_formants";
  std::string vowel = "u";
  std::string area_function; ///< overrides vowel
  std::string model = "planar";
  std::string radiation = "sommerfeld";
  double h = 0.0; // mesh size [m]; 0: from elements_per_wavelength
  double elements_per_wavelength = 10.0;
  double layer = 0.02;        // absorbing-layer thickness for pml [m]
  bool curvature = true;      // Bayliss-Turkel curvature term in Sommerfeld
  double mic_distance = 0.03; // microphone on the axis, beyond the lips [m]
  int formants = 4;
  int snapshots = 100; // p' snapshots in pressure.xdmf (0: none)
  bool check_result = false;
  bool yielding_walls = false;

  void bind(fsai::common::Parameters& p);
  void validate() const;
};

/// The 1D reference of the study: the tract resampled as the FE mesh's
/// wall, its lip end and observation point, its walls, its resonances
struct TractReference
{
  mesh::AreaFunction area, area1d;
  LipEnd lip = LipEnd::flanged;
  double x_obs = 0;
  TubeWall wall;
  std::vector<double> formants, bandwidths;
};
TractReference tract_reference(const FormantParameters& fp,
                               const WaveParameters& wave,
                               const PulseParameters& pulse,
                               const mesh::VocalTractGeometry& geo);

/// Formants and bandwidths of a study
struct Formants
{
  std::vector<double> f, bandwidth;
};
/// The 1D model's own (--model 1d): its transfer function to
/// DIR/transfer_function.csv
Formants formants_1d(MPI_Comm comm, const FormantParameters& fp,
                     const WaveParameters& wave, const PulseParameters& pulse,
                     const TractReference& ref);
/// The FE pulse run: mesh, pulse with progress and p' snapshots, transfer
/// functions (transfer_function.csv, time_series.csv) and their peaks
Formants formants_fe(MPI_Comm comm, const FormantParameters& fp,
                     const WaveParameters& wave, const PulseParameters& pulse,
                     mesh::VocalTractGeometry geo, const TractReference& ref,
                     io::RunSummary& summary);
/// --check-result: F1–F3 within 3 % of the 1D model (and B1 within 20 %
/// with yielding walls), else throws
void check_formants(const FormantParameters& fp, const Formants& fe,
                    const std::vector<double>& dev, const TractReference& ref);
} // namespace fsai::acoustics
