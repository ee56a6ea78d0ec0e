// Copyright (C) 2026 fsai developers
//
// The voice's flow → sound coupling, one way, once per flow step
// (docs/model.md §4, A1–A6): the acoustic domain is fixed with the
// glottis at rest and contains the flow domain Ω^f_0.
//  - Lighthill's source ρ0 v v (E15) from the converged flow, transferred in
//    the reference configuration and tapered to zero before the flow outlet
//    and after the inlet (A1);
//  - the fold surface's acceleration, ∂p'/∂n = −ρ0 a·n (A2), while the slit
//    beside it is open;
//  - the glottal flow Q(t) as a ±Q volume-source pair either side of the
//    fold (A6: the valve's monopole, which incompressible flow does not put
//    into ρ0 v v);
//  - the slit law of the flow's current gap in the acoustic cells under the
//    fold (A5: inertia g0/g, viscous and jet resistance; closed when the
//    folds touch), applied by the wave solver's SlitLaw.
#pragma once
#include <acoustics/FlowSource.h>
#include <acoustics/SlitLaw.h>
#include <acoustics/WaveSolver.h>
#include <array>
#include <functional>
#include <glottis/FlowGlottis.h>
#include <io/run_state.h>
#include <memory>
#include <mesh/MeshData.h>
#include <vector>

namespace fsai::common
{
class Parameters;
}
namespace fsai::glottis
{
class ElasticFold;
}

namespace fsai::voice
{
/// Options of the coupling ([voice] section)
struct VoiceSourceParameters
{
  bool taper = true;          ///< taper Lighthill's source (A1)
  bool lighthill = true;      ///< Lighthill's source on
  bool wall = true;           ///< vibrating fold surface on
  bool source_average = true; ///< Lighthill velocity at the step midpoint
  // The glottal volume flow as a volume-source pair and the acoustic
  // glottis following the flow's (the slit law): both on, as together they
  // give the tract's F1/F2 (docs/voice.md)
  bool monopole = true;
  double monopole_length = 0.005; ///< [m] each source's extent along x
  bool glottal_slit = true;
  bool slit_lighthill = false; ///< Lighthill's force in the slit's law
  double taper_start = 0.02;   ///< ramp from here before the flow outlet [m]
  double taper_end = 0.005;    ///< to zero here before the outlet [m]
  double taper_inlet = 0.005;  ///< ramp up over this length after the inlet [m]

  void bind(fsai::common::Parameters& p);
  void validate() const;
};

/// The fold as the sound's sources see it (A2, A5): its moved surface,
/// ordered along the channel (the slit's height), and its wall's velocity
/// at a point X of the fold's rest surface
struct FoldWall
{
  std::vector<std::array<double, 2>> surface;
  std::function<std::array<double, 2>(const std::array<double, 2>& X)> velocity;
};
/// The 2-DOF fold's: its rigid motion, tapered by the profile's weight to
/// the fixed walls beside the fold (as the flow's boundary)
FoldWall fold_wall(const glottis::TwoDofFold& fold,
                   const glottis::FoldProfile& profile);
/// The elastic fold's (collective): its surface's own displacement and
/// velocity, linear between the surface's points, at the nearest point of
/// its rest surface
FoldWall fold_wall(const glottis::ElasticFold& fold);

class VoiceSource
{
public:
  /// Sets up the coupling on the acoustic domain `am` of `sound`: taper,
  /// monopole pair, slit, fold-surface nodes (collective). `channel` is
  /// the FE flow's, whose velocity gives Lighthill's source; nullptr for
  /// the Bernoulli flow, which has no velocity field (no Lighthill source:
  /// the monopole pair, the slit and the fold's wall carry the sound)
  VoiceSource(MPI_Comm comm, const VoiceSourceParameters& p,
              const glottis::FlowGlottisSetup& setup,
              const glottis::FoldProfile& profile,
              const glottis::FlowChannel* channel, const mesh::MeshData& am,
              acoustics::WaveSolver& sound, double dt);

  /// Start (or continue after a restart) from the fold's current state;
  /// `q_last` the last converged glottal flow [m³/s]
  void start(const FoldWall& fold, double q_last);
  /// The sound's source data for the step the flow just took (`s`) with
  /// the fold and, for the FE flow, its channel (after a remeshing a new
  /// one: the transfer is set up again on it)
  void apply(const FoldWall& fold, const glottis::FlowChannel* channel,
             const glottis::Sample& s);

  /// The source's last velocity in a checkpoint and back
  void save(io::RankState& state) const;
  void load(const std::vector<io::RankState>& ranks);

private:
  void set_slit_law(const std::vector<std::array<double, 2>>& surface,
                    const glottis::Sample& s);
  void set_wall_acceleration(const FoldWall& fold,
                             const std::vector<std::array<double, 2>>& surface);
  /// The fold wall's velocity at the fold dofs (2 per dof), faded by
  /// open_fraction, for the fold's current state
  std::vector<double>
  wall_velocity(const FoldWall& fold,
                const std::vector<std::array<double, 2>>& surface) const;
  /// The fold's surface for the slit law and the fade (empty without the
  /// slit law, which the fade then ignores)
  std::vector<std::array<double, 2>> slit_surface(const FoldWall& fold) const;
  double open_fraction(double x,
                       const std::vector<std::array<double, 2>>& surface) const;

  VoiceSourceParameters _par;
  const glottis::FoldProfile& _profile;
  acoustics::WaveSolver& _sound;
  double _dt, _g_min, _mu, _rho;
  MPI_Comm _comm;
  std::unique_ptr<acoustics::FlowSource> _transfer;
  /// The channel _transfer reads: a remeshed flow (E13a) is a new channel
  /// (made while the old one still exists, so never at the same address)
  const glottis::FlowChannel* _transfer_channel = nullptr;
  std::shared_ptr<dolfinx::fem::Function<double>> _v_new, _v_old;
  std::array<std::size_t, 2> _monopole{};
  std::shared_ptr<acoustics::SlitLaw> _slit;
  std::vector<double> _slit_x, _slit_g0, _inertia, _resistance;
  std::vector<std::int32_t> _fold_dofs;
  std::vector<std::array<double, 2>> _fold_X;
  std::vector<double> _u_wall_prev; // wall_velocity of the last step
  double _q_monopole = 0;
};

/// Height of the polyline `surface` (points ordered along x) above x: the
/// lowest crossing of the vertical line at x (+∞ if none)
double surface_height(const std::vector<std::array<double, 2>>& surface,
                      double x);
} // namespace fsai::voice
