// Copyright (C) 2026 fsai developers
//
// The 2-DOF vocal fold of the closure scene (docs/model.md G1; Horáček & Švec
// 2002): the rigid profile of FoldProfile on a translational spring (h) and a
// torsional spring (φ) about the elastic axis X_EA,
//   m ḧ + S φ̈ + d_h ḣ + k_h h = Q_h,   S ḧ + I φ̈ + d_φ φ̇ + k_φ φ = Q_φ,
// Q the generalised aerodynamic (and contact) forces. With the
// displacement u = (0, −h) + (R(φ) − I)(X − X_EA) of FoldProfile, Q_h = −L
// (L the upward lift) and Q_φ = M (the counter-clockwise moment about
// X_EA), as in the design's equations; S = −m (x_cg − x_EA).
//
// Mass m and inertia I come from the profile area, ρ = 1000 kg/m³ and the
// depth L_g; the two springs are chosen so that the in-vacuo
// eigenfrequencies are f1 and f2 (≈ 100 and 160 Hz), and the damping is
// modal (ratios ζ1, ζ2). Time integration: Newmark (β = ¼, γ = ½, energy
// conserving), one implicit step per call with the given load.
#pragma once
#include "FoldProfile.h"
#include <array>
#include <string>

namespace fsai::common
{
class Parameters;
}

namespace fsai::glottis
{
/// [vf] section
struct TwoDofParameters
{
  double density = 1000; ///< tissue density [kg/m³]
  double f1 = 100;       ///< first in-vacuo eigenfrequency [Hz]
  double f2 = 160;       ///< second in-vacuo eigenfrequency [Hz]
  double zeta1 = 0.05;   ///< modal damping ratio of mode 1
  double zeta2 = 0.05;   ///< modal damping ratio of mode 2
  /// x of the elastic axis relative to the profile centroid [m] (0: at the
  /// centroid, S = 0: translation and rotation decouple in vacuo). The
  /// default, 1 mm upstream, couples them through the mass (S ≠ 0), which
  /// the flow needs to synchronise the two modes (coalescence flutter):
  /// with S = 0 the quasi-steady load only stiffens both modes and no
  /// p_sub up to 3.2 kPa makes the fold oscillate (onset sweep).
  double axis_dx = -1e-3;
  /// y of the elastic axis relative to the profile centroid [m]; it does
  /// not enter S, only the inertia and how far a rotation slides the medial
  /// surface along the axis. At the medial-surface level (−2.5 mm, with
  /// axis_dx −1.3 mm) the reduced model still closes every cycle above
  /// 800 Pa, but the FE flow model's oscillation decays at 1000 Pa.
  double axis_dy = 0.0;
  /// Which motion the lower frequency f1 belongs to: "translation" (h) or
  /// "rotation" (φ)
  std::string first_mode = "translation";
  double h0 = 0.0; ///< initial displacement h (a small perturbation) [m]
  /// Hold the fold at (h0, 0) whatever the load: a static glottis of half-gap
  /// g0 − h0 (steady-flow studies, e.g. the mesh convergence of the
  /// glottal flow rate without the oscillation's sensitivity to it)
  bool held = false;
  void bind(fsai::common::Parameters& p);
  void validate() const;
};

using Vec2 = std::array<double, 2>;
using Mat2 = std::array<std::array<double, 2>, 2>;

/// Solve the 2×2 system A x = b
Vec2 solve2(const Mat2& A, const Vec2& b);

/// Eigenfrequencies [Hz] and mass-normalised mode shapes of K x = ω² M x
struct Modes2
{
  Vec2 frequency_hz;
  Mat2 shape; ///< shape[k] = mode k (h, φ)
};
Modes2 modes(const Mat2& K, const Mat2& M);

class TwoDofFold
{
public:
  TwoDofFold(const FoldProfile& profile, const TwoDofParameters& p);

  const Mat2& mass() const { return _M; }
  const Mat2& stiffness() const { return _K; }
  const Mat2& damping() const { return _D; }
  /// Elastic axis X_EA (reference configuration)
  Vec2 axis() const { return _axis; }
  /// The rigid motion of the current state
  RigidMotion motion() const { return RigidMotion(_q[0], _q[1], _axis); }
  const Vec2& q() const { return _q; }     ///< (h, φ)
  const Vec2& qdot() const { return _v; }  ///< (ḣ, φ̇)
  const Vec2& qddot() const { return _a; } ///< (ḧ, φ̈)

  /// Accelerations consistent with the load Q at the current state (call
  /// once before the first step)
  void initialise(const Vec2& Q);
  /// Newmark step of length dt from the saved state with the load Q at the
  /// new time; may be repeated (coupling iterations) until accept()
  void step(double dt, const Vec2& Q);
  /// Make the last step the start of the next one
  void accept();
  /// The state the next step() starts from
  const Vec2& q_start() const { return _q0; }
  /// The accepted state (q, q̇, q̈) (checkpoints)
  std::array<Vec2, 3> state() const { return {_q0, _v0, _a0}; }
  /// Set the accepted and current state (restart from a checkpoint)
  void set_state(const std::array<Vec2, 3>& s)
  {
    _q0 = _q = s[0];
    _v0 = _v = s[1];
    _a0 = _a = s[2];
  }
  /// Total mechanical energy ½ q̇ᵀMq̇ + ½ qᵀKq
  double energy() const;

private:
  Mat2 _M, _K, _D;
  Vec2 _axis;
  bool _held = false;
  Vec2 _q{}, _v{}, _a{};    // current (trial) state
  Vec2 _q0{}, _v0{}, _a0{}; // accepted state
};
} // namespace fsai::glottis
