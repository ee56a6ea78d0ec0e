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

// Midpoint of triangle c in the mesh's current coordinates
std::array<double, 2> cell_midpoint(const dolfinx::mesh::Mesh& mesh,
                                    std::int32_t c)
{
  const auto x = mesh.geometry().x();
  std::array<double, 2> mid{0, 0};
  for (auto n : mesh.geometry().dofmap().links(c))
  {
    mid[0] += x[3 * n] / 3;
    mid[1] += x[3 * n + 1] / 3;
  }
  return mid;
}
} // namespace

void fsai::glottis::FlowGlottisParameters::bind(fsai::common::Parameters& p)
{
  p.add("fe.ramp", ramp, "time over which p_sub ramps up [s]");
  p.add("fe.h_far", h_far, "mesh size away from the fold [m]");
  p.add("fe.h_gap", h_gap, "mesh size on the fold [m]");
  p.add("fe.fine_height", fine_height,
        "> 0: mesh size h_gap only within this distance of the axis, the "
        "size growing beyond it as away from the fold (0: on all of the "
        "fold) [m]");
  p.add("fe.grading", grading,
        "distance from the fold over which the mesh size grows from h_gap "
        "to h_far [m]");
  p.add("fe.h_jet", h_jet,
        "> 0: mesh size in the jet region (within fe.jet_height of the "
        "axis, downstream of the fold's inferior attachment), h_far "
        "elsewhere [m]");
  p.add("fe.jet_height", jet_height, "height of the jet region [m]");
  p.add("closure.g_min", g_min,
        "closest approach of the fluid boundary to the axis [m]");
  p.add_choice("closure.gap_motion", gap_motion, {"algebraic", "elastic"},
               "mesh motion between the medial surface and the axis");
  p.add("closure.gap_columns", gap_columns,
        "algebraic gap motion: the columns under the fold boundary up to "
        "g0 + this times the edge radius from the axis");
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
  fsai::require_positive("--fe.h_far", h_far);
  fsai::require_positive("--fe.h_gap", h_gap);
  fsai::require(fine_height >= 0, "--fe.fine_height", ">= 0", fine_height);
  fsai::require_positive("--fe.grading", grading);
  fsai::require(h_jet >= 0, "--fe.h_jet", ">= 0", h_jet);
  fsai::require_positive("--fe.jet_height", jet_height);
  fsai::require_positive("--closure.g_min", g_min);
  fsai::require(gap_columns >= 0, "--closure.gap_columns", ">= 0", gap_columns);
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
      _fold(profile, vf)
{
  p.validate();
  const auto& g = profile.geometry();
  fsai::require(p.g_min < g.rest_gap, "--closure.g_min", "< the rest gap",
                p.g_min);
  _mesh = mesh::glottis_channel(comm, profile, p.h_far, p.h_gap, p.fine_height,
                                p.grading, p.h_jet, p.jet_height);
  auto find = [&](const char* name)
  { return _mesh.facet_tags->find(_mesh.facet_tag(name)); };
  _fold_facets = find("fold");
  _inlet_facets = find("inlet");
  fluid::FluidBoundaries fb;
  fb.inlet_penalty = _inlet_facets;
  fb.outlet = find("outlet");
  fb.walls = find("wall");
  fb.walls.insert(fb.walls.end(), _fold_facets.begin(), _fold_facets.end());
  fb.symmetry = find("axis");
  fp.p_in = 0; // set_inlet_pressure() ramps it
  _flow = std::make_unique<fluid::FluidSolver>(_mesh.mesh, fb, fp, p.dt);
  ale::MeshMotionBoundaries mb;
  mb.interface = _fold_facets;
  mb.fixed = _inlet_facets;
  for (const char* name : {"outlet", "wall"})
  {
    auto f = find(name);
    mb.fixed.insert(mb.fixed.end(), f.begin(), f.end());
  }
  const auto V = _flow->velocity_space();
  _F = std::make_shared<dolfinx::fem::Function<double>>(V);
  _fold_dofs = dolfinx::fem::locate_dofs_topological(*V, 1, _fold_facets);
  const std::vector<double> X = V->tabulate_dof_coordinates(false);
  _X_ref = X;
  for (auto d : _fold_dofs)
    _fold_X.push_back({X[3 * d], X[3 * d + 1]});
  mb.slip = {{1, fb.symmetry}};
  if (p.gap_motion == "algebraic")
  {
    // The lower envelope of the fold boundary near the axis as the mesh
    // has it: every fold node (all ranks) whose reference height is
    // within rest gap + R of the axis, by x. Each node below that envelope
    // hangs from the boundary segment above it (column top = linear
    // interpolation of the two boundary nodes, exactly the discrete
    // boundary, so no node can pass it); every rank tests its owned and
    // ghost dofs by the same geometric rule
    const double y_lim = g.rest_gap + p.gap_columns * g.medial_radius;
    std::vector<double> loc;
    for (auto& X : _fold_X)
      if (X[1] <= 1.5 * y_lim)
        loc.insert(loc.end(), {X[0], X[1]});
    const std::vector<double> all = common::allgather(comm, loc);
    std::vector<std::array<double, 2>> env;
    for (std::size_t k = 0; k + 1 < all.size(); k += 2)
      env.push_back({all[k], all[k + 1]});
    std::sort(env.begin(), env.end());
    env.erase(std::unique(env.begin(), env.end()), env.end());
    const std::int32_t nblocks = V->dofmap()->index_map->size_local()
                                 + V->dofmap()->index_map->num_ghosts();
    for (std::int32_t d = 0; d < nblocks and env.size() >= 2; ++d)
    {
      const double x = _X_ref[3 * d], y = _X_ref[3 * d + 1];
      auto it = std::upper_bound(env.begin(), env.end(),
                                 std::array<double, 2>{x, 1e300});
      if (it == env.begin() or it == env.end())
        continue;
      const auto& A = *(it - 1);
      const auto& B = *it;
      const double t = B[0] > A[0] ? (x - A[0]) / (B[0] - A[0]) : 0.0;
      const double yc = (1 - t) * A[1] + t * B[1];
      if (yc <= y_lim and y < yc - 1e-3 * g.rest_gap)
      {
        _gap_dofs.push_back(d);
        _gap_nodes.push_back({A, B});
        _gap_t.push_back(t);
        _gap_fraction.push_back(y / yc);
      }
    }
    mb.prescribed = _gap_dofs;
  }
  _motion = std::make_unique<ale::MeshMotion>(_mesh.mesh,
                                              _flow->velocity_space(), mb, ap);
  _loop = std::make_unique<coupling::FixedPointCoupling>(comm, cp, coupling_csv,
                                                         coupling_rows_kept);
  // Cells that can become porous: reference midpoint within the fold's
  // x-extent, below the attachment band
  const auto& mesh = *_mesh.mesh;
  const std::int32_t ncells = mesh.topology().index_map(2)->size_local()
                              + mesh.topology().index_map(2)->num_ghosts();
  for (std::int32_t c = 0; c < ncells; ++c)
  {
    const auto [cx, cy] = cell_midpoint(mesh, c);
    if (cx > 0 and cx < g.fold_length and cy < g.half_height - g.taper)
      _candidates.push_back(c);
  }
  // Upstream fold facets: midpoint (reference configuration) x < medial_x
  {
    auto xg = dolfinx::mesh::entities_to_geometry(mesh, 1, _fold_facets, false);
    const auto x = mesh.geometry().x();
    for (std::size_t i = 0; i < _fold_facets.size(); ++i)
      if (0.5 * (x[3 * xg[2 * i]] + x[3 * xg[2 * i + 1]]) < g.medial_x)
        _upstream_fold_facets.push_back(_fold_facets[i]);
  }
  if (p.superpose_motion and _motion->linear())
  {
    const auto axis = _fold.axis();
    for (int k = 0; k < 3; ++k)
    {
      set_interface(
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
      _extension_basis[k] = _motion->extension();
    }
    _d_move.resize(_extension_basis[0].size());
  }
  _q_n = _q_nn = _fold.q();
  std::array<double, 2> Q{0, 0};
  _fold.initialise(Q);
}

std::int64_t fsai::glottis::FlowGlottis::cells() const
{
  return _mesh.mesh->topology().index_map(2)->size_global();
}

std::array<std::int64_t, 2> fsai::glottis::FlowGlottis::cells_per_rank() const
{
  const std::int64_t n = _mesh.mesh->topology().index_map(2)->size_local();
  std::array<std::int64_t, 2> r{-n, n};
  MPI_Allreduce(MPI_IN_PLACE, r.data(), 2, MPI_INT64_T, MPI_MAX, _comm);
  return {-r[0], r[1]};
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
  // The fold's half-gap g (lowest point of the rigidly moved surface). The
  // fluid boundary stops at g_min: below g_min + b it is lifted as a whole
  // by g_b − g with g_b = g_min + b exp((g − g_min − b)/b) (C¹, b = g_min),
  // so its lowest point stays above g_min however far the fold crosses the
  // axis. Lifting the whole surface keeps its shape: an earlier per-point
  // clamp flattened the superior edge round onto the axis, and the cells
  // under it, compressed 10× at one column and 20× at the next, inverted
  // at p_sub = 1200 Pa. The part of the gap the fold occupies is porous.
  double g = 1e300;
  for (const auto& p : moved_surface(_profile, m))
    g = std::min(g, p[1]);
  const double b = _par.g_min;
  if (g >= _par.g_min + b)
    return 0.0;
  return _par.g_min + b * std::exp((g - _par.g_min - b) / b) - g;
}

void fsai::glottis::FlowGlottis::set_boundary(const RigidMotion& m)
{
  const double lift = boundary_lift(m);
  set_interface([&](const std::array<double, 2>& X)
                { return boundary_displacement(m, X, lift); });
}

void fsai::glottis::FlowGlottis::set_interface(
    const std::function<std::array<double, 2>(const std::array<double, 2>&)>& u)
{
  auto a = _motion->interface_displacement().x()->mutable_array();
  for (std::size_t i = 0; i < _fold_dofs.size(); ++i)
  {
    const auto ui = u(_fold_X[i]);
    a[2 * _fold_dofs[i]] = ui[0];
    a[2 * _fold_dofs[i] + 1] = ui[1];
  }
  // Algebraic gap motion: the column of nodes under the boundary point
  // above (between boundary nodes A and B) moves with it horizontally (the axis
  // nodes slide along the axis) and is compressed vertically, a node at height
  // fraction s = y/y_s keeping s. The map (x, s) → (x + U_x(x), s Y(x)), Y the
  // new surface height, has Jacobian (1 + U_x') Y > 0: no node passes the
  // boundary above it however close the fold comes. (Shifting x by s U_x
  // instead shears the columns: with the fold rotated by φ they tilt to a slope
  // Y/U_x below the surface's φ and the cells under the superior edge invert.)
  for (std::size_t i = 0; i < _gap_dofs.size(); ++i)
  {
    const auto ua = u(_gap_nodes[i][0]);
    const auto ub = u(_gap_nodes[i][1]);
    const double t = _gap_t[i];
    a[2 * _gap_dofs[i]] = (1 - t) * ua[0] + t * ub[0];
    a[2 * _gap_dofs[i] + 1] = _gap_fraction[i] * ((1 - t) * ua[1] + t * ub[1]);
  }
}

void fsai::glottis::FlowGlottis::mark_porous(const RigidMotion& m)
{
  // χ = 1 in the cells whose (current) midpoint lies inside the moved fold
  auto& chi = _flow->porous_indicator();
  auto c_arr = chi.x()->mutable_array();
  const auto dofmap = chi.function_space()->dofmap();
  for (auto c : _candidates)
  {
    const auto mid = cell_midpoint(*_mesh.mesh, c);
    c_arr[dofmap->cell_dofs(c)[0]]
        = _profile.contains(m.reference_of(mid)) ? 1.0 : 0.0;
  }
}

fsai::ale::MeshQuality
fsai::glottis::FlowGlottis::move_mesh(double t, const std::array<double, 2>& q)
{
  const RigidMotion m(q[0], q[1], _fold.axis());
  if (_extension_basis[0].empty())
  {
    set_boundary(m);
    return _motion->move(t);
  }
  // boundary_displacement(m, X, lift) = w(X) [(c − 1) r + s r⊥ + (lift − h)
  // e_y] (RigidMotion::displacement), r = X − X_EA, r⊥ = (−r_y, r_x)
  const double alpha[3]
      = {std::cos(q[1]) - 1, std::sin(q[1]), boundary_lift(m) - q[0]};
  for (std::size_t i = 0; i < _d_move.size(); ++i)
    _d_move[i] = alpha[0] * _extension_basis[0][i]
                 + alpha[1] * _extension_basis[1][i]
                 + alpha[2] * _extension_basis[2][i];
  return _motion->move_to(_d_move, t);
}

std::array<double, 2>
fsai::glottis::FlowGlottis::evaluate(double t, const std::array<double, 2>& q,
                                     Sample& s)
{
  const RigidMotion m(q[0], q[1], _fold.axis());
  // 1. fold boundary and mesh (the same move --replay makes); the fold
  // wall moves with the mesh
  move_mesh(t, q);
  _motion->velocity(_flow->mesh_velocity(), _par.dt);
  {
    auto w = _flow->mesh_velocity().x()->array();
    auto gw = _flow->wall_velocity().x()->mutable_array();
    for (auto d : _fold_dofs)
      for (int k = 0; k < 2; ++k)
        gw[2 * d + k] = w[2 * d + k];
  }
  // 2. porous region, flow
  mark_porous(m);
  _flow->restore_state();
  _flow->step();
  // 3. generalised forces of the fluid's nodal forces (per unit depth, so
  //    times L_g) by the tapered virtual displacements
  _flow->nodal_forces(_fold_facets, *_F);
  const double Lg = _profile.geometry().depth;
  const auto F = _F->x()->array();
  const std::int32_t owned
      = _flow->velocity_space()->dofmap()->index_map->size_local();
  std::array<double, 4> loc{0, 0, 0, 0}; // Q_h, Q_φ, F_x, F_y
  for (std::size_t i = 0; i < _fold_dofs.size(); ++i)
  {
    const auto d = _fold_dofs[i];
    if (d >= owned)
      continue;
    const double f[2] = {Lg * F[2 * d], Lg * F[2 * d + 1]};
    const double w = _profile.weight(_fold_X[i]);
    const auto du = m.derivatives(_fold_X[i]);
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
  _flow->set_inlet_pressure(pressure_ramp(t, _par.ramp) * _par.p_sub);
  _flow->save_state();
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
  _motion->advance();
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
  // Glottal flow through the section x = medial_x (both folds, depth L_g).
  // The inlet flux also carries the air that the moving inferior surface
  // displaces (spikes at the closing instants, a false "leakage"). With
  // div v = 0, the flux through the section is the inlet flux minus the
  // flux through the upstream fold wall, where v equals the mesh velocity of
  // the actual fluid boundary (held at g_min near the axis, which a rigid-
  // surface correction gets wrong). The section moves with the mesh there;
  // the axis is a slip line, so this differs from a fixed section only by
  // the mesh's horizontal motion near the axis.
  const double depth2 = 2 * _profile.geometry().depth;
  s.Q_inlet = -depth2 * _flow->flow_rate(_inlet_facets);
  s.Q = s.Q_inlet - depth2 * _flow->flow_rate(_upstream_fold_facets);
  const auto surf = moved_surface(_profile, _fold.motion());
  s.gap = 1e300;
  for (auto& p : surf)
    s.gap = std::min(s.gap, p[1]);
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
  _flow->save(state, "flow.");
  _motion->save(state, "ale.");
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
  std::string error;
  try
  {
    _flow->load(ranks, "flow.");
    _motion->load(ranks, "ale.");
    // The coupling unknowns (h, ℓφ) live on rank 0: its columns come from
    // the checkpoint's rank 0; the other ranks keep empty columns
    int rank = 0;
    MPI_Comm_rank(_comm, &rank);
    const auto& r0 = ranks.at(0);
    io::RankState iqn;
    for (const auto& [name, v] : r0)
      if (name.rfind("coupling.", 0) == 0)
        iqn[name]
            = name.ends_with("counts") or rank == 0 ? v : std::vector<double>();
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
  }
  catch (const std::exception& e)
  {
    error = e.what();
  }
  io::throw_if_any_rank(_comm, error);
}
//-----------------------------------------------------------------------------
void fsai::glottis::FlowGlottis::write_last_good(const std::string& path)
{
  _flow->restore_state();
  _motion->rewind();
  _fold.set_state(_fold.state());
  io::TimeSeriesWriter xdmf(path,
                            {_flow->velocity(), _flow->pressure(),
                             _flow->porous_field(), _motion->displacement()});
  xdmf.write(_t);
}
