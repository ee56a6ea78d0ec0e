// Copyright (C) 2026 fsai developers
#include "BernoulliGlottis.h"
#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <common/Parameters.h>
#include <common/errors.h>
#include <fmt/format.h>
#include <stdexcept>

//-----------------------------------------------------------------------------
void fsai::glottis::BernoulliGlottisParameters::bind(
    fsai::common::Parameters& p)
{
  p.add("rho", rho, "air density of the Bernoulli flow [kg/m^3]");
  p.add("bernoulli.separation_ratio", separation_ratio,
        "flow separates where the gap reaches this multiple of its minimum");
  p.add("bernoulli.viscosity", viscosity,
        "--fold elastic: air viscosity of the Poiseuille loss [Pa s]");
  p.add("bernoulli.y_floor", y_floor,
        "--fold elastic: smallest gap the flow sees [m]");
  p.add("bernoulli.separation_min_gap", y_sep_min,
        "--fold elastic: the flow separates at separation_ratio times the "
        "smallest gap or this gap, the larger [m]");
}
//-----------------------------------------------------------------------------
void fsai::glottis::BernoulliGlottisParameters::validate() const
{
  fsai::require_positive("--rho", rho);
  fsai::require(separation_ratio >= 1, "--bernoulli.separation_ratio", ">= 1",
                separation_ratio);
  fsai::require_positive("--bernoulli.viscosity", viscosity);
  fsai::require_positive("--bernoulli.y_floor", y_floor);
  fsai::require(y_sep_min >= 0, "--bernoulli.separation_min_gap", ">= 0",
                y_sep_min);
}
//-----------------------------------------------------------------------------

fsai::glottis::BernoulliGlottis::BernoulliGlottis(
    const FoldProfile& profile, const TwoDofParameters& vf,
    const ContactParameters& contact, const BernoulliGlottisParameters& p)
    : _profile(profile), _contact(contact), _par(p), _fold(profile, vf)
{
  evaluate(_fold.motion(), _fold.qdot(), _Q);
  _fold.initialise(_Q);
}

fsai::glottis::Sample
fsai::glottis::BernoulliGlottis::evaluate(const RigidMotion& m,
                                          const std::array<double, 2>& qdot,
                                          std::array<double, 2>& Q) const
{
  const auto flow = bernoulli_flow(_profile, m, _par.p_sub, _par.p_sup,
                                   _par.rho, _par.separation_ratio);
  const auto c = hertz_contact(_contact, _profile.edge_centres(),
                               _profile.geometry().medial_radius, m, qdot);
  Q = {flow.generalised[0] + c.generalised[0],
       flow.generalised[1] + c.generalised[1]};
  Sample s;
  s.gap = flow.min_gap;
  s.Q = flow.Q;
  s.Q_inlet = flow.Q; // quasi-steady: no displaced volume
  s.h = m.h;
  s.phi = m.phi;
  s.drag = flow.force[0];
  s.lift = flow.force[1];
  s.moment = flow.generalised[1];
  s.contact_force = c.force;
  s.penetration = c.penetration;
  return s;
}

fsai::glottis::Sample fsai::glottis::BernoulliGlottis::step()
{
  const double dt = _par.dt;
  // Predictor: the load of the accepted state (evaluated when it was
  // accepted)
  std::array<double, 2> Q = _Q;
  Sample s;
  int it = 0;
  for (;; ++it)
  {
    const auto q_old = _fold.q();
    _fold.step(dt, Q);
    s = evaluate(_fold.motion(), _fold.qdot(), Q);
    const double dq
        = std::hypot(_fold.q()[0] - q_old[0], 1e-3 * (_fold.q()[1] - q_old[1]));
    const double scale = std::hypot(_fold.q()[0], 1e-3 * _fold.q()[1]) + 1e-6;
    if (it > 0 and dq <= _par.tol * scale)
      break;
    if (it + 1 >= _par.max_iterations)
    {
      throw std::runtime_error(fmt::format(
          "bernoulli glottis: no fixed point at t = {:.6g} s after {} "
          "iterations (|dq| = {:.3e}); reduce --dt",
          _t + dt, it + 1, dq));
    }
  }
  // The last iterate is the new state; Q, its load, predicts the next step
  _fold.accept();
  _Q = Q;
  _t += dt;
  s.t = _t;
  s.iterations = it + 1;
  require_finite(s, "bernoulli glottis");
  return s;
}

fsai::glottis::StabilityResult
fsai::glottis::linear_stability(const FoldProfile& profile,
                                const TwoDofParameters& vf,
                                const BernoulliGlottisParameters& p)
{
  TwoDofParameters v0 = vf;
  v0.h0 = 0;
  const TwoDofFold fold(profile, v0);
  const auto& K = fold.stiffness();
  const auto& M = fold.mass();
  const auto& D = fold.damping();
  auto load = [&](const Vec2& q)
  {
    const RigidMotion m(q[0], q[1], fold.axis());
    return bernoulli_flow(profile, m, p.p_sub, p.p_sup, p.rho,
                          p.separation_ratio);
  };
  StabilityResult r;
  // Static equilibrium K q = Q(q) by damped fixed-point iteration
  Vec2 q = {0, 0};
  for (int it = 0; it < 500; ++it)
  {
    const auto f = load(q);
    if (f.min_gap <= 0)
    {
      r.closed = true;
      return r;
    }
    const Vec2 qn = solve2(K, f.generalised);
    const double d = std::hypot(qn[0] - q[0], 1e-3 * (qn[1] - q[1]));
    q = {0.5 * (q[0] + qn[0]), 0.5 * (q[1] + qn[1])};
    if (d < 1e-14)
      break;
  }
  r.q_static = q;
  r.gap_static = load(q).min_gap;
  // Aerodynamic stiffness ∂Q/∂q by central differences
  const Vec2 step = {1e-8, 1e-5};
  Eigen::Matrix2d Ja;
  for (int j = 0; j < 2; ++j)
  {
    Vec2 qp = q, qm = q;
    qp[j] += step[j];
    qm[j] -= step[j];
    const auto fp = load(qp), fm = load(qm);
    for (int i = 0; i < 2; ++i)
      Ja(i, j) = (fp.generalised[i] - fm.generalised[i]) / (2 * step[j]);
  }
  Eigen::Matrix2d Me, Ke, De;
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j)
    {
      Me(i, j) = M[i][j];
      Ke(i, j) = K[i][j];
      De(i, j) = D[i][j];
    }
  const Eigen::Matrix2d Mi = Me.inverse();
  Eigen::Matrix4d A = Eigen::Matrix4d::Zero();
  A.block<2, 2>(0, 2) = Eigen::Matrix2d::Identity();
  A.block<2, 2>(2, 0) = Mi * (Ja - Ke);
  A.block<2, 2>(2, 2) = -Mi * De;
  const Eigen::EigenSolver<Eigen::Matrix4d> es(A);
  std::vector<std::complex<double>> ev(es.eigenvalues().begin(),
                                       es.eigenvalues().end());
  std::sort(ev.begin(), ev.end(),
            [](auto& a, auto& b) { return a.real() > b.real(); });
  for (auto& l : ev)
  {
    if (l.imag() < 0)
      continue; // one of each conjugate pair
    r.growth_rate.push_back(l.real());
    r.frequency_hz.push_back(l.imag() / (2 * M_PI));
  }
  return r;
}
