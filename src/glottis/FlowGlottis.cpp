// Copyright (C) 2026 fsai developers
#include "FlowGlottis.h"
#include "BernoulliFlow.h"
#include "waveform.h"
#include <algorithm>
#include <cmath>
#include <common/Parameters.h>
#include <common/errors.h>
#include <common/mpi_gather.h>
#include <common/timer.h>
#include <cstdio>
#include <cstdlib>
#include <dolfinx/fem/utils.h>
#include <dolfinx/mesh/utils.h>
#include <io/TimeSeriesWriter.h>
#include <mesh/glottis_channel.h>

namespace
{
constexpr double lever = 1e-3; // ℓ: coupling variable (h, ℓφ) [m]

} // namespace

void fsai::glottis::FlowGlottisParameters::bind(fsai::common::Parameters& p)
{
  p.add("fe.ramp", ramp, "time over which p_sub ramps up [s]");
  p.add("fe.h_far", sizes.h_far, "mesh size away from the fold [m]");
  p.add("fe.h_gap", sizes.h_gap, "mesh size on the fold [m]");
  p.add("fe.fine_height", sizes.fine_height,
        "> 0: mesh size h_gap only within this distance of the axis, the "
        "size growing beyond it as away from the fold (0: on all of the "
        "fold) [m]");
  p.add("fe.grading", sizes.grading,
        "distance from the fold over which the mesh size grows from h_gap "
        "to h_far [m]");
  p.add("fe.h_jet", sizes.h_jet,
        "> 0: mesh size in the jet region (within fe.jet_height of the "
        "axis, downstream of the fold's inferior attachment), h_far "
        "elsewhere [m]");
  p.add("fe.jet_height", sizes.jet_height, "height of the jet region [m]");
  p.add("fe.h_inlet", sizes.h_inlet,
        "> 0: mesh size in the subglottal channel from the inlet to "
        "2 fe.grading before the fold, coarser than h_far [m]");
  p.add("closure.g_min", g_min,
        "closest approach of the fluid boundary to the axis [m]");
  p.add("closure.porous_ramp", porous_ramp,
        "width over which a cell's porous indicator rises from 0 to 1 with "
        "the depth of its midpoint inside the fold (0: a switch) [m]");
  p.add("closure.porous_floor_dt", porous_floor_dt,
        "porous ramp: the Δt of its floor 0.01 rho/(sigma_p dt) (0: the "
        "run's --dt) [s]");
  p.add_choice("closure.gap_motion", gap_motion, {"algebraic", "elastic"},
               "mesh motion between the medial surface and the axis");
  p.add("closure.gap_columns", gap_columns,
        "algebraic gap motion: the columns under the fold boundary up to "
        "g0 + this times the edge radius from the axis");
  p.add("fe.remesh_quality", remesh_quality,
        "elastic fold: mesh the channel again when a cell's scaled Jacobian "
        "falls below this (0: never)");
  p.add("fe.step_cuts", step_cuts,
        "elastic fold: a failed step (coupling not converged, a cell "
        "inverted) is taken as two halves, up to this many times in a row");
  p.add_choice("fe.cut_history", cut_history, {"clear", "keep"},
               "elastic fold, step cuts: the halves of a discarded attempt "
               "start the coupling's IQN-ILS afresh (clear) or reuse the "
               "columns of it and the steps before (keep)");
  p.add_choice("closure.lift", lift, {"uniform", "local"},
               "elastic fold: the fluid boundary lifted above g_min as a whole "
               "(uniform) or around the points below 2 g_min (local)");
  p.add("closure.wedge_angle", wedge_angle,
        "elastic fold: the fluid boundary kept out of the wedge narrower "
        "than this at each attachment of the fold to the wall (0: not "
        "kept) [deg]");
  p.add("fe.superpose_motion", superpose_motion,
        "move the mesh by superposing three precomputed extensions of the "
        "fold motion (exact for the linear extension) instead of solving "
        "at every move");
  p.add_choice("coupling.predictor", predictor, {"load", "displacement"},
               "first guess of the fold state each step");
}

void fsai::glottis::FlowGlottisParameters::validate() const
{
  fsai::require_positive("--p-sub", p_sub);
  fsai::require(ramp >= 0, "--fe.ramp", ">= 0", ramp);
  fsai::require_positive("--dt", dt);
  fsai::require_positive("--fe.h_far", sizes.h_far);
  fsai::require_positive("--fe.h_gap", sizes.h_gap);
  fsai::require(sizes.fine_height >= 0, "--fe.fine_height", ">= 0",
                sizes.fine_height);
  fsai::require_positive("--fe.grading", sizes.grading);
  fsai::require(sizes.h_jet >= 0, "--fe.h_jet", ">= 0", sizes.h_jet);
  fsai::require_positive("--fe.jet_height", sizes.jet_height);
  fsai::require(sizes.h_inlet >= 0, "--fe.h_inlet", ">= 0", sizes.h_inlet);
  fsai::require_positive("--closure.g_min", g_min);
  fsai::require(porous_ramp >= 0, "--closure.porous_ramp", ">= 0", porous_ramp);
  fsai::require(porous_floor_dt >= 0, "--closure.porous_floor_dt", ">= 0",
                porous_floor_dt);
  fsai::require(gap_columns >= 0, "--closure.gap_columns", ">= 0", gap_columns);
  fsai::require(wedge_angle >= 0 and wedge_angle < 90, "--closure.wedge_angle",
                "in [0, 90)", wedge_angle);
  fsai::require(remesh_quality >= 0 and remesh_quality < 1,
                "--fe.remesh_quality", "in [0, 1)", remesh_quality);
  fsai::require(step_cuts >= 0 and step_cuts <= 8, "--fe.step_cuts",
                "in [0, 8]", step_cuts);
}

fsai::glottis::FlowGlottisSetup::FlowGlottisSetup()
{
  fold.h0 = 0.05e-3;     // a small perturbation from rest
  fluid.sigma_p = 1e7;   // porous closure: see FlowGlottis.h
  fluid.inlet_eps = 1e3; // E11a with ε large: total-pressure inlet
  // Plain pseudo-elastic extension: survives the closing gap (fluid
  // boundary at g_min = 10 % of the rest gap) and costs one solve per
  // move; Jacobian stiffening (6 solves) is 60x dearer per move and
  // size stiffening inverted a gap cell at t = 24.2 ms (g = 0.066 mm)
  ale.stiffening = "none";
  // MUMPS: the fieldsplit iterative solver (26 ms vs 34 ms per solve)
  // stalls (KSP_DIVERGED_ITS) once the porous term σ_P χ ≫ ρ/Δt
  // switches on in the closing gap
  fluid.solver = "direct";
  coupling.atol = 1e-11; // [m] on (h, 1 mm·φ)
  // The porous region switches cell-wise between coupling iterations,
  // so near closure the interface map is discontinuous and a step can
  // stall (relative residual 5.7e-4 after 50 iterations at t = 38.6 ms
  // in one 2-rank run): such steps are logged, counted in the summary
  // and the run goes on
  coupling.on_failure = "warn";
}
//-----------------------------------------------------------------------------
void fsai::glottis::FlowGlottisSetup::bind(fsai::common::Parameters& p)
{
  geometry.bind(p);
  fold.bind(p);
  contact.bind(p);
  fe.bind(p);
  fluid.bind(p);
  ale.bind(p);
  coupling.bind(p);
}
//-----------------------------------------------------------------------------
void fsai::glottis::FlowGlottisSetup::validate(double p_sub, double dt)
{
  geometry.validate();
  fold.validate();
  contact.validate();
  fe.p_sub = p_sub;
  fe.dt = dt;
  fe.validate();
  fluid.validate();
  ale.validate();
  coupling.validate();
}
//-----------------------------------------------------------------------------
fsai::glottis::FlowGlottis::FlowGlottis(
    MPI_Comm comm, const FoldProfile& profile, const TwoDofParameters& vf,
    const ContactParameters& contact, const FlowGlottisParameters& p,
    fluid::FluidParameters fp, const ale::MeshMotionParameters& ap,
    const coupling::CouplingParameters& cp, const std::string& coupling_csv,
    std::size_t coupling_rows_kept)
    : _comm(comm), _profile(profile), _contact(contact), _par(p),
      _fold(profile, vf), _channel(comm, profile, p, fp, ap)
{
  _loop = std::make_unique<coupling::FixedPointCoupling>(comm, cp, coupling_csv,
                                                         coupling_rows_kept);
  if (p.superpose_motion and _channel.linear_motion())
  {
    const auto axis = _fold.axis();
    for (int k = 0; k < 3; ++k)
    {
      _channel.set_interface(
          [&](const std::array<double, 2>& X) -> std::array<double, 2>
          {
            const double w = _profile.weight(X);
            const double rx = X[0] - axis[0], ry = X[1] - axis[1];
            if (k == 0)
              return {w * rx, w * ry};
            if (k == 1)
              return {-w * ry, w * rx};
            return {0.0, w};
          });
      _extension_basis[k] = _channel.extension();
    }
    _d_move.resize(_extension_basis[0].size());
  }
  _q_n = _q_nn = _fold.q();
  std::array<double, 2> Q{0, 0};
  _fold.initialise(Q);
}

std::array<double, 2> fsai::glottis::FlowGlottis::boundary_displacement(
    const RigidMotion& m, const std::array<double, 2>& X, double lift) const
{
  // The fluid boundary is the fold surface moved rigidly (tapered towards
  // the wall attachment) and lifted by `lift` as a whole
  const double w = _profile.weight(X);
  const auto u = m.displacement(X);
  return {w * u[0], w * (u[1] + lift)};
}

double fsai::glottis::FlowGlottis::boundary_lift(const RigidMotion& m) const
{
  // By the fold's half-gap g, the lowest point of the rigidly moved surface
  return glottis::boundary_lift(lowest_point(moved_surface(_profile, m)),
                                _par.g_min);
}

void fsai::glottis::FlowGlottis::set_boundary(const RigidMotion& m)
{
  const double lift = boundary_lift(m);
  _channel.set_interface([&](const std::array<double, 2>& X)
                         { return boundary_displacement(m, X, lift); });
}

fsai::ale::MeshQuality
fsai::glottis::FlowGlottis::move_mesh(double t, const std::array<double, 2>& q)
{
  const RigidMotion m(q[0], q[1], _fold.axis());
  if (_extension_basis[0].empty())
  {
    set_boundary(m);
    return _channel.move(t);
  }
  // boundary_displacement(m, X, lift) = w(X) [(c − 1) r + s r⊥ + (lift − h)
  // e_y] (RigidMotion::displacement), r = X − X_EA, r⊥ = (−r_y, r_x)
  const double alpha[3]
      = {std::cos(q[1]) - 1, std::sin(q[1]), boundary_lift(m) - q[0]};
  for (std::size_t i = 0; i < _d_move.size(); ++i)
    _d_move[i] = alpha[0] * _extension_basis[0][i]
                 + alpha[1] * _extension_basis[1][i]
                 + alpha[2] * _extension_basis[2][i];
  return _channel.move_to(_d_move, t);
}

std::array<double, 2>
fsai::glottis::FlowGlottis::evaluate(double t, const std::array<double, 2>& q,
                                     Sample& s)
{
  const RigidMotion m(q[0], q[1], _fold.axis());
  // 1. fold boundary and mesh (the same move --replay makes); the fold
  // wall moves with the mesh
  move_mesh(t, q);
  _channel.set_wall_velocity();
  // 2. porous region: the cells inside the moved fold; flow
  _channel.mark_porous(_profile.points(), [&](const std::array<double, 2>& x)
                       { return m.reference_of(x); });
  _channel.solve_flow();
  // 3. generalised forces of the fluid's nodal forces by the tapered
  //    virtual displacements
  std::array<double, 4> loc{0, 0, 0, 0}; // Q_h, Q_φ, F_x, F_y
  for (const auto& [X, f] : _channel.fold_forces())
  {
    const double w = _profile.weight(X);
    const auto du = m.derivatives(X);
    loc[0] += w * (f[0] * du[0][0] + f[1] * du[0][1]);
    loc[1] += w * (f[0] * du[1][0] + f[1] * du[1][1]);
    loc[2] += f[0];
    loc[3] += f[1];
  }
  std::array<double, 4> glob;
  MPI_Allreduce(loc.data(), glob.data(), 4, MPI_DOUBLE, MPI_SUM, _comm);
  // 4. contact and the fold step
  const auto c
      = hertz_contact(_contact, _profile.edge_centres(),
                      _profile.geometry().medial_radius, m, _fold.qdot());
  _fold.step(_par.dt, {glob[0] + c.generalised[0], glob[1] + c.generalised[1]});
  _load = {glob[0], glob[1]};
  s.drag = glob[2];
  s.lift = glob[3];
  s.moment = glob[1];
  s.contact_force = c.force;
  s.penetration = c.penetration;
  return _fold.q();
}

fsai::glottis::Sample fsai::glottis::FlowGlottis::step()
{
  common::ScopedTimer timer("glottis: fe step");
  const double t = _t + _par.dt;
  _channel.flow().set_inlet_pressure(pressure_ramp(t, _par.ramp) * _par.p_sub);
  _channel.flow().save_state();
  // The coupling variable (h, ℓφ) lives on rank 0; the map broadcasts it
  int rank;
  MPI_Comm_rank(_comm, &rank);
  std::vector<double> x;
  const auto q0 = predict();
  if (rank == 0)
    x = {q0[0], lever * q0[1]};
  Sample s;
  auto rep = _loop->step(t, x,
                         [&](std::span<const double> xi, std::span<double> Hx)
                         {
                           std::array<double, 2> q{0, 0};
                           if (rank == 0)
                             q = {xi[0], xi[1] / lever};
                           MPI_Bcast(q.data(), 2, MPI_DOUBLE, 0, _comm);
                           const auto qn = evaluate(t, q, s);
                           if (rank == 0)
                           {
                             Hx[0] = qn[0];
                             Hx[1] = lever * qn[1];
                           }
                         });
  _fold.accept();
  _channel.advance();
  _q_nn = _q_n;
  _q_n = _fold.q();
  _load_nn = _load_n;
  _load_n = _load;
  ++_steps;
  _t = t;
  s.t = t;
  s.h = _fold.q()[0];
  s.phi = _fold.q()[1];
  s.iterations = rep.iterations;
  s.converged = rep.converged;
  // Glottal flow through the section x = medial_x (both folds, depth L_g)
  const auto Q = _channel.flow_rates();
  s.Q_inlet = Q[0];
  s.Q = Q[1];
  s.gap = lowest_point(moved_surface(_profile, _fold.motion()));
  require_finite(s, "FE glottis");
  return s;
}
//-----------------------------------------------------------------------------
std::array<double, 2> fsai::glottis::FlowGlottis::predict()
{
  // Linear extrapolation from the last two accepted steps (constant after
  // the first)
  auto extrapolate
      = [this](const std::array<double, 2>& n, const std::array<double, 2>& nn)
  {
    return _steps >= 2
               ? std::array<double, 2>{2 * n[0] - nn[0], 2 * n[1] - nn[1]}
               : n;
  };
  const auto q = extrapolate(_q_n, _q_nn);
  if (_par.predictor == "displacement" or _steps == 0)
    return q;
  // The fold's own Newmark step under the extrapolated fluid load; the
  // Hertz force (stiff, switching) at the extrapolated state. The trial
  // step is repeated by the first evaluation (TwoDofFold::step starts
  // from the accepted state every time)
  const auto Q = extrapolate(_load_n, _load_nn);
  const RigidMotion m(q[0], q[1], _fold.axis());
  const auto c
      = hertz_contact(_contact, _profile.edge_centres(),
                      _profile.geometry().medial_radius, m, _fold.qdot());
  _fold.step(_par.dt, {Q[0] + c.generalised[0], Q[1] + c.generalised[1]});
  return _fold.q();
}
//-----------------------------------------------------------------------------
fsai::io::RankState fsai::glottis::FlowGlottis::save() const
{
  io::RankState state;
  _channel.save(state);
  _loop->save(state, "coupling.");
  const auto f = _fold.state();
  state["fold.state"] = {f[0][0], f[0][1], f[1][0], f[1][1], f[2][0], f[2][1]};
  state["glottis.q_history"] = {_q_n[0], _q_n[1], _q_nn[0], _q_nn[1]};
  state["glottis.load_history"]
      = {_load_n[0], _load_n[1], _load_nn[0], _load_nn[1]};
  state["glottis.t_steps"] = {_t, double(_steps)};
  return state;
}
//-----------------------------------------------------------------------------
void fsai::glottis::FlowGlottis::load(const std::vector<io::RankState>& ranks)
{
  // A mismatch on one rank must not leave the others waiting
  io::on_every_rank(
      _comm,
      [&]
      {
        _channel.load(ranks);
        // The coupling unknowns (h, ℓφ) live on rank 0: its columns come from
        // the checkpoint's rank 0; the other ranks keep empty columns
        int rank = 0;
        MPI_Comm_rank(_comm, &rank);
        const auto& r0 = ranks.at(0);
        io::RankState iqn;
        for (const auto& [name, v] : r0)
          if (name.rfind("coupling.", 0) == 0)
            iqn[name] = name.ends_with("counts") or rank == 0
                            ? v
                            : std::vector<double>();
        _loop->load(iqn, "coupling.");
        const auto& f = io::state_entry(r0, "fold.state", 6);
        _fold.set_state({{{f[0], f[1]}, {f[2], f[3]}, {f[4], f[5]}}});
        const auto& q = io::state_entry(r0, "glottis.q_history", 4);
        _q_n = {q[0], q[1]};
        _q_nn = {q[2], q[3]};
        const auto& l = io::state_entry(r0, "glottis.load_history", 4);
        _load_n = {l[0], l[1]};
        _load_nn = {l[2], l[3]};
        const auto& ts = io::state_entry(r0, "glottis.t_steps", 2);
        _t = ts[0];
        _steps = int(ts[1]);
      });
}
//-----------------------------------------------------------------------------
std::optional<double>
fsai::glottis::FlowGlottis::write_last_good(const std::string& path)
{
  _channel.rewind();
  _fold.set_state(_fold.state());
  io::TimeSeriesWriter xdmf(path, _channel.fields());
  xdmf.write(_t);
  return _t;
}
