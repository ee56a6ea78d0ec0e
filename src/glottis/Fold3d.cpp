// Copyright (C) 2026 fsai developers
#include "Fold3d.h"
#include "waveform.h"
#include <common/Parameters.h>
#include <common/errors.h>
#include <common/log.h>
#include <coupling/InterfaceMap.h>
#include <coupling/PartitionedFsi.h>
#include <dolfinx/fem/utils.h>
#include <io/PointProbes.h>
#include <io/RunSummary.h>
#include <io/run_state.h>
#include <structure/ModalProjection.h>

#include <cmath>
#include <limits>

//-----------------------------------------------------------------------------
void fsai::glottis::Fold3dParameters::bind(fsai::common::Parameters& p)
{
  p.add("output", output, "output folder");
  p.add("p-sub", p_sub, "subglottal pressure [Pa]");
  p.add("ramp", ramp, "time over which p_sub ramps up [s]");
  p.add("dt", dt, "time step [s]");
  p.add("duration", duration, "simulated time [s]");
  p.add("stats_from", stats_from,
        "cycle statistics from this time [s] (< 0: the second half)");
  p.add("write_every", write_every, "steps between XDMF outputs (0: none)");
  p.add("zeta", zeta, "fold damping ratio (stiffness-proportional)");
  p.add("f_zeta", f_zeta, "frequency at which the damping ratio is zeta [Hz]");
  p.add("layers", layers, "1 (homogeneous fold) or 2 (body and cover)");
  p.add("modes", modes,
        "in-vacuo modes the fold's motion is projected on (0: none)");
  p.add("cover.E", cover.E, "Young's modulus of the cover [Pa]");
  p.add("cover.nu", cover.nu, "Poisson's ratio of the cover");
  p.add("cover.rho", cover.rho, "density of the cover [kg/m^3]");
  p.add("quick", quick, "a short, coarse look (not a result)");
  run.bind(p);
}
//-----------------------------------------------------------------------------
void fsai::glottis::Fold3dParameters::validate() const
{
  fsai::require_positive("--p-sub", p_sub);
  fsai::require(ramp >= 0, "--ramp", ">= 0", ramp);
  fsai::require_positive("--dt", dt);
  fsai::require(duration >= dt, "--duration", ">= --dt", duration);
  fsai::require(std::lround(duration / dt) <= 10'000'000, "--duration",
                "at most 1e7 steps of --dt", duration);
  fsai::require(stats_from < duration, "--stats_from", "< --duration",
                stats_from);
  fsai::require(write_every >= 0, "--write_every", ">= 0", write_every);
  fsai::require(zeta >= 0 and zeta < 1, "--zeta", "in [0, 1)", zeta);
  fsai::require_positive("--f_zeta", f_zeta);
  fsai::require(layers == 1 or layers == 2, "--layers", "1 or 2", layers);
  fsai::require(modes >= 0 and modes <= 50, "--modes", "in [0, 50]", modes);
  cover.validate("--cover");
  run.validate();
}
//-----------------------------------------------------------------------------
fsai::glottis::Fold3dSetup::Fold3dSetup()
{
  // The fold of fsai_modal (E 8 kPa, ν 0.4, ρ 1000 kg/m³; f1 100 Hz), P2
  // SVK (E4–E7): P2 tetrahedra do not lock at ν 0.4 (the modal study's
  // f1 converges to 0.2 %, bench/modal_convergence.py)
  solid.model = "svk";
  solid.degree = 2;
  solid.material = {8e3, 0.4, 1000.0};
  // Its tangent changes little within a step: modified Newton keeps the
  // factorisation while it contracts
  solid.newton_reuse = true;
  fluid.inlet_eps = 1e3; // E11a with ε large: a total-pressure inlet
  // MUMPS, its factorisation refined by a step's later coupling iterates
  // (E20a): on 2 ranks 1.44x faster per step than the iterative path at
  // the default 56k flow unknowns and 1.23x at 150k; the two would cross
  // near 260k (docs/fold3d.md). --fluid.solver iterative takes FGMRES
  // with the Schur fieldsplit and the PCD approximation, which holds in
  // the glottal jet (E20b)
  fluid.solver = "direct";
  fluid.schur = "pcd";
  fluid.quadrature_degree = 2;
  // Inexact flow solves stall IQN-ILS: with the iterative path at 1e-8 the
  // coupling residual stagnated near 1e-6 relative and a step at 4.15 ms
  // (800 Pa) failed after 50 iterations (4.9 per step before it); at 1e-10
  // the same start-up takes 2.5 per step (docs/fold3d.md)
  fluid.ksp_rtol = 1e-10;
  // The size-stiffened pseudo-elastic extension keeps the small gap cells
  // rigid while the fold moves
  ale.method = "elastic";
  ale.stiffening = "size";
  coupling.accelerator.method = "iqn-ils";
  coupling.tol = 1e-6;
  coupling.atol = 1e-11; // [m]: while the fold barely moves (the ramp)
}
//-----------------------------------------------------------------------------
void fsai::glottis::Fold3dSetup::bind(fsai::common::Parameters& p)
{
  scene.bind(p);
  fold.bind(p);
  channel.bind(p);
  fluid.bind(p);
  solid.bind(p);
  ale.bind(p);
  coupling.bind(p);
}
//-----------------------------------------------------------------------------
void fsai::glottis::Fold3dSetup::configure(const fsai::common::Parameters& p)
{
  if (scene.quick)
  {
    // A few coarse steps: the fold 2 mm, the gap cells 0.6 mm, 2 ms
    p.set_unless_given("fold.h", fold.h, 2e-3);
    p.set_unless_given("channel.half_gap", channel.half_gap, 0.4e-3);
    p.set_unless_given("channel.h_gap", channel.h_gap, 0.6e-3);
    p.set_unless_given("channel.h_far", channel.h_far, 2.5e-3);
    p.set_unless_given("channel.supraglottal", channel.supraglottal, 6e-3);
    p.set_unless_given("channel.subglottal", channel.subglottal, 3e-3);
    p.set_unless_given("dt", scene.dt, 5e-5);
    p.set_unless_given("duration", scene.duration, 2e-3);
    p.set_unless_given("ramp", scene.ramp, 1e-3);
    p.set_unless_given("write_every", scene.write_every, 10);
  }
  if (!scene.run.restart.empty())
    scene.output = scene.run.restart; // continue in the run's own folder
  scene.validate();
  fold.validate();
  channel.validate();
  fluid.validate();
  solid.validate();
  ale.validate();
  coupling.validate();
  fsai::require(fluid.inlet_eps > 0, "--fluid.inlet_eps",
                "> 0 (the inlet is driven by p_sub)", fluid.inlet_eps);
  fsai::require(fold.h >= channel.h_gap, "--fold.h",
                ">= --channel.h_gap (the interface is meshed at h_gap)",
                fold.h);
  solid.set_damping_ratio(scene.zeta, 0.0, scene.f_zeta);
}
//-----------------------------------------------------------------------------
fsai::glottis::Fold3dPhonation::Fold3dPhonation(MPI_Comm comm,
                                                const Fold3dSetup& setup,
                                                std::size_t rows_kept)
    : _comm(comm), _setup(setup)
{
  const auto& s = _setup;
  _meshes = mesh::glottal_channel_3d(comm, s.fold, s.channel);
  const auto& fm = _meshes.fluid;
  const auto& sm = _meshes.solid;
  auto find = [](const mesh::MeshData& m, const char* name)
  { return m.facet_tags->find(m.facet_tag(name)); };
  _interface = find(fm, "interface");
  _outlet = find(fm, "outlet");

  // Flow: the fold's surface is a wall that moves with the mesh
  fluid::FluidBoundaries fb;
  fb.inlet_penalty = find(fm, "inlet");
  fb.outlet = _outlet;
  fb.walls = find(fm, "walls");
  fb.walls.insert(fb.walls.end(), _interface.begin(), _interface.end());
  fb.symmetry = find(fm, "midplane");
  fb.symmetry_component = 0; // v_x = 0 on the mid-sagittal plane
  auto fp = s.fluid;
  fp.p_in = 0; // step() ramps it
  _flow = std::make_unique<fluid::FluidSolver>(fm.mesh, fb, fp, s.scene.dt);

  // Fold: held at its lateral, anterior and posterior faces
  _solid = std::make_unique<structure::ElasticSolver>(
      sm.mesh, find(sm, "clamped"), find(sm, "interface"), s.solid, s.scene.dt);
  if (s.scene.layers == 2)
    _solid->set_material(mesh::cover_cells(*sm.mesh, s.fold), s.scene.cover);
  if (s.scene.modes > 0)
    _modes
        = std::make_unique<structure::ModalProjection>(*_solid, s.scene.modes);

  // Mesh motion: the fold's surface moves the air; the ends and walls
  // stay; the symmetry plane slides in itself
  ale::MeshMotionBoundaries mb;
  mb.fixed = fb.inlet_penalty;
  for (auto* f : {&fb.outlet, &fb.walls})
    mb.fixed.insert(mb.fixed.end(), f->begin(), f->end());
  mb.slip = {{0, fb.symmetry}};
  mb.interface = _interface; // listed last: it wins where it meets a wall
  _motion = std::make_unique<ale::MeshMotion>(fm.mesh, _flow->velocity_space(),
                                              mb, s.ale);
  _map = std::make_unique<coupling::InterfaceMap>(*_flow->velocity_space(),
                                                  _interface, *_solid->space(),
                                                  find(sm, "interface"));
  _fsi = std::make_unique<coupling::PartitionedFsi>(
      *_flow, *_solid, *_motion, *_map, _interface, s.coupling,
      s.scene.output + "/coupling.csv", rows_kept);

  // The glottis's half-gap is measured in the middle fifth of its length
  // (the fold is held at z = 0 and z = length, where the gap stays at
  // rest)
  const auto X = _flow->velocity_space()->tabulate_dof_coordinates(false);
  const double zc = 0.5 * s.fold.length, band = 0.1 * s.fold.length;
  for (auto d : _map->fluid_dofs())
  {
    if (std::abs(X[3 * d + 2] - zc) <= band)
    {
      _gap_dofs.push_back(d);
      _gap_X.push_back(X[3 * d]);
    }
  }
  // The centre of the medial surface (x = depth, mid-height of its
  // vertical part, mid-length)
  const auto& g = s.fold;
  _medial = std::make_unique<io::PointProbes>(
      sm.mesh,
      std::vector<std::array<double, 3>>{
          {g.depth, g.height - g.b - 0.5 * g.t_medial, 0.5 * g.length}});
  fsai::log::info("3D fold: flow {} dofs, fold {} dofs, interface {} fluid "
                  "vertices on this rank",
                  _flow->dofs(), solid_dofs(), _map->fluid_dofs().size());
}
//-----------------------------------------------------------------------------
fsai::glottis::Fold3dPhonation::~Fold3dPhonation() = default;
//-----------------------------------------------------------------------------
double fsai::glottis::Fold3dPhonation::smallest_gap() const
{
  const double xm = _setup.channel.midplane(_setup.fold);
  auto d = _motion->displacement()->x()->array();
  const int bs = 3;
  double g = std::numeric_limits<double>::max();
  const auto& dofs = _gap_dofs;
  for (std::size_t i = 0; i < dofs.size(); ++i)
    g = std::min(g, xm - _gap_X[i] - d[bs * dofs[i]]);
  MPI_Allreduce(MPI_IN_PLACE, &g, 1, MPI_DOUBLE, MPI_MIN, _comm);
  return g;
}
//-----------------------------------------------------------------------------
fsai::glottis::Fold3dSample fsai::glottis::Fold3dPhonation::step()
{
  const auto& sp = _setup.scene;
  _t += sp.dt;
  _flow->set_inlet_pressure(pressure_ramp(_t, sp.ramp) * sp.p_sub);
  const auto rep = _fsi->step(_t);
  Fold3dSample out;
  out.t = _t;
  out.iterations = rep.iterations;
  out.converged = rep.converged;
  // Both halves of the channel: twice the half-channel's outflow
  out.Q = 2 * _flow->flow_rate(_outlet);
  out.gap = smallest_gap();
  const auto u = _medial->values(*_solid->displacement());
  out.ux = u[0];
  out.uy = u[1];
  if (_modes)
    out.modal = _modes->coordinates(*_solid->displacement());
  return out;
}
//-----------------------------------------------------------------------------
void fsai::glottis::Fold3dPhonation::checkpoint(
    nlohmann::json& scalars, std::optional<io::RankState>& fields)
{
  scalars["fold3d_t"] = _t;
  _fsi->clear_history(); // as the restarted run's (PartitionedFsi::load)
  io::RankState state;
  _flow->save(state, "flow.");
  _motion->save(state, "ale.");
  _solid->save(state, "fold.");
  _fsi->save(state, "fsi.");
  fields = std::move(state);
}
//-----------------------------------------------------------------------------
void fsai::glottis::Fold3dPhonation::restore(
    const nlohmann::json& scalars, const std::vector<io::RankState>& ranks)
{
  io::on_every_rank(_comm,
                    [&]
                    {
                      if (!scalars.contains("fold3d_t"))
                        throw InputError("restart: the checkpoint is not "
                                         "fsai_fold3d's");
                      _t = scalars["fold3d_t"].get<double>();
                      _flow->load(ranks, "flow.");
                      _motion->load(ranks, "ale.");
                      _solid->load(ranks, "fold.");
                      _fsi->load(ranks, "fsi.");
                    });
}
//-----------------------------------------------------------------------------
void fsai::glottis::Fold3dPhonation::describe(io::RunSummary& summary) const
{
  summary.set("flow_dofs", _flow->dofs());
  summary.set("solid_dofs", solid_dofs());
  summary.set("rest_half_gap_m", _setup.channel.half_gap);
  if (_modes)
    summary.set("mode_hz", _modes->frequencies_hz());
}
//-----------------------------------------------------------------------------
std::int64_t fsai::glottis::Fold3dPhonation::solid_dofs() const
{
  const auto& im = *_solid->space()->dofmap()->index_map;
  return im.size_global() * _solid->space()->dofmap()->index_map_bs();
}
//-----------------------------------------------------------------------------
double fsai::glottis::Fold3dPhonation::krylov_iterations_mean() const
{
  return _flow->krylov_iterations_mean();
}
//-----------------------------------------------------------------------------
std::vector<std::shared_ptr<const dolfinx::fem::Function<double>>>
fsai::glottis::Fold3dPhonation::flow_fields() const
{
  return {_flow->velocity(), _flow->pressure(), _motion->displacement()};
}
//-----------------------------------------------------------------------------
std::vector<std::shared_ptr<const dolfinx::fem::Function<double>>>
fsai::glottis::Fold3dPhonation::fold_fields() const
{
  return {_solid->displacement(), _solid->velocity()};
}
