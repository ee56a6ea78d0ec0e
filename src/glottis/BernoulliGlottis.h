// Copyright (C) 2026 fsai developers
//
// The reduced glottis scene: the 2-DOF fold (TwoDofFold), the quasi-steady
// Bernoulli flow (BernoulliFlow) and the Hertz impact (HertzContact),
// coupled implicitly in each Newmark step by fixed-point iterations on
// (h, φ) (the load depends on the new position). Runs far faster than real
// time: the cheap end of the scene's speed/accuracy chart.
#pragma once
#include "BernoulliFlow.h"
#include "GlottisModel.h"
#include "HertzContact.h"
#include "Sample.h"
#include "TwoDofFold.h"
#include <vector>

namespace fsai::common
{
class Parameters;
}

namespace fsai::glottis
{
struct BernoulliGlottisParameters
{
  double p_sub = 800;            ///< subglottal (lung) pressure [Pa]
  double p_sup = 0;              ///< supraglottal pressure [Pa]
  double rho = 1.2;              ///< air density [kg/m³]
  double separation_ratio = 1.2; ///< k_s
  /// Elastic fold only (viscous_surface_pressure): air viscosity μ [Pa s]
  /// and the smallest gap the flow sees [m]
  double viscosity = 1.8e-5;
  double y_floor = 0.2e-6;
  double y_sep_min = 20e-6; ///< separation at ≥ k_s times this gap [m]
  double dt = 1e-5;         ///< time step [s]
  double tol = 1e-10;       ///< fixed point: |Δq| relative to |q| + 1e-6
  int max_iterations = 50;

  /// The flow model's options (--rho, --bernoulli.*); p_sub, p_sup and dt
  /// are the scene's
  void bind(fsai::common::Parameters& p);
  void validate() const;
};

/// Linear stability of the fold's static equilibrium under the
/// quasi-steady Bernoulli load at p_sub (contact excluded): eigenvalues λ of
/// the state matrix [[0, I], [M⁻¹(∂Q/∂q − K), −M⁻¹D]] with ∂Q/∂q by finite
/// differences. Re λ > 0: flutter (phonation onset); Im λ/2π: the
/// frequencies of the coupled fold–flow system.
struct StabilityResult
{
  std::array<double, 2> q_static{}; ///< (h, φ) at equilibrium
  double gap_static = 0;            ///< half-gap at equilibrium [m]
  std::vector<double> growth_rate;  ///< Re λ [1/s], largest first
  std::vector<double> frequency_hz; ///< |Im λ|/2π of the same λ
  bool closed = false; ///< the equilibrium closes the glottis (no analysis)
};
StabilityResult linear_stability(const FoldProfile& profile,
                                 const TwoDofParameters& vf,
                                 const BernoulliGlottisParameters& p);

class BernoulliGlottis : public GlottisModel
{
public:
  BernoulliGlottis(const FoldProfile& profile, const TwoDofParameters& vf,
                   const ContactParameters& contact,
                   const BernoulliGlottisParameters& p);
  /// Advance one step; throws std::runtime_error if the fixed point fails
  Sample step() override;
  const TwoDofFold& fold() const { return _fold; }
  const TwoDofFold* two_dof_fold() const override { return &_fold; }
  double time() const override { return _t; }
  void checkpoint(nlohmann::json& scalars,
                  std::optional<io::RankState>& fields) override;
  void restore(const nlohmann::json& checkpoint,
               const std::vector<io::RankState>& fields) override;
  void describe(io::RunSummary& summary) override;

  /// Everything the next step depends on: time, the fold's accepted state
  /// and the load that predicts the next step
  struct State
  {
    double t;
    std::array<std::array<double, 2>, 3> fold; // (q, q̇, q̈)
    std::array<double, 2> load;
  };
  State state() const { return {_t, _fold.state(), _Q}; }
  void set_state(const State& s)
  {
    _t = s.t;
    _fold.set_state(s.fold);
    _Q = s.load;
  }

private:
  Sample evaluate(const RigidMotion& m, const std::array<double, 2>& qdot,
                  std::array<double, 2>& Q) const;
  const FoldProfile& _profile;
  ContactParameters _contact;
  BernoulliGlottisParameters _par;
  TwoDofFold _fold;
  std::array<double, 2> _Q{}; // load of the accepted state
  double _t = 0;
};
} // namespace fsai::glottis
