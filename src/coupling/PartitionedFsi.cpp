// Copyright (C) 2026 fsai developers
#include "PartitionedFsi.h"
#include "../common/timer.h"
#include "../io/field_state.h"
#include <dolfinx/fem/assembler.h>
#include <dolfinx/fem/utils.h>
#include <fsai_forms/ale.h>

using namespace dolfinx;

//-----------------------------------------------------------------------------
fsai::coupling::PartitionedFsi::PartitionedFsi(
    fluid::FluidSolver& flow, structure::ElasticSolver& solid,
    ale::MeshMotion& motion, const InterfaceMap& map,
    std::span<const std::int32_t> fluid_interface, const CouplingParameters& p,
    const std::string& csv_path, std::size_t csv_rows_kept)
    : _flow(flow), _solid(solid), _motion(motion), _map(map),
      _loop(flow.velocity_space()->mesh()->comm(), p, csv_path, csv_rows_kept)
{
  if (std::abs(flow.dt() - solid.dt()) > 1e-12 * flow.dt())
    throw std::runtime_error("FSI: the flow and structure time steps differ");
  auto V = flow.velocity_space();
  auto mesh = std::const_pointer_cast<mesh::Mesh>(V->mesh());
  const int tdim = mesh->topology().dim(), bs = V->dofmap()->index_map_bs();
  const std::int32_t owned = V->dofmap()->index_map->size_local();
  for (auto d : map.fluid_dofs())
    if (d < owned)
      _owned.push_back(d);
  _d = std::make_shared<fem::Function<double>>(
      std::const_pointer_cast<fem::FunctionSpace>(V));
  _F = std::make_shared<fem::Function<double>>(
      std::const_pointer_cast<fem::FunctionSpace>(V));

  // Lumped interface mass on the reference mesh (the mesh must not have
  // moved yet): nodal forces / mass = nominal traction
  std::vector<std::int32_t> f;
  const std::int32_t nf = mesh->topology().index_map(tdim - 1)->size_local();
  _facets.assign(fluid_interface.begin(), fluid_interface.end());
  for (auto i : fluid_interface)
    if (i < nf)
      f.push_back(i);
  std::sort(f.begin(), f.end());
  auto tags = std::make_shared<mesh::MeshTags<std::int32_t>>(
      mesh, tdim - 1, f, std::vector<std::int32_t>(f.size(), 1));
  auto form = fem::create_form<double>(
      forms::ale::lumped(tdim, 1),
      {std::const_pointer_cast<fem::FunctionSpace>(V)}, {},
      {{"e", std::make_shared<fem::Constant<double>>(
                 std::vector<double>(tdim, 1.0))}},
      {{fem::IntegralType::exterior_facet, tags.get()}});
  la::Vector<double> m(V->dofmap()->index_map, bs);
  m.set(0.0);
  fem::assemble_vector(m.mutable_array(), form);
  m.scatter_rev(std::plus<double>());
  for (auto d : _owned)
    for (int k = 0; k < bs; ++k)
      _inv_mass.push_back(1.0 / m.array()[bs * d + k]);
  _x_n.assign(_owned.size() * bs, 0.0);
  _x_nn = _x_n;
}
//-----------------------------------------------------------------------------
void fsai::coupling::PartitionedFsi::evaluate(double t,
                                              std::span<const double> x,
                                              std::span<double> Hx)
{
  const int bs = _flow.velocity_space()->dofmap()->index_map_bs();
  // 1. mesh
  {
    auto a = _motion.interface_displacement().x()->mutable_array();
    for (std::size_t i = 0; i < _owned.size(); ++i)
      for (int k = 0; k < bs; ++k)
        a[bs * _owned[i] + k] = x[bs * i + k];
  }
  _motion.move(t);
  _motion.velocity(_flow.mesh_velocity(), _flow.dt(), _flow.dt_previous());
  // 2. flow, the interface moving with the mesh
  {
    auto w = _flow.mesh_velocity().x()->array();
    auto g = _flow.wall_velocity().x()->mutable_array();
    for (auto d : _map.fluid_dofs())
      for (int k = 0; k < bs; ++k)
        g[bs * d + k] = w[bs * d + k];
  }
  _flow.restore_state();
  _flow.step();
  // 3. load: nominal traction at the fluid vertices -> the solid's trace
  _flow.nodal_forces(_facets, *_F);
  {
    auto F = _F->x()->mutable_array();
    for (std::size_t i = 0; i < _owned.size(); ++i)
      for (int k = 0; k < bs; ++k)
        F[bs * _owned[i] + k] *= _inv_mass[bs * i + k];
  }
  _map.fluid_to_solid(*_F, _solid.traction());
  // 4. structure
  _solid.restore_state();
  _solid.step();
  // 5. its interface displacement at the fluid vertices
  _map.solid_to_fluid(*_solid.displacement(), *_d);
  auto d = _d->x()->array();
  for (std::size_t i = 0; i < _owned.size(); ++i)
    for (int k = 0; k < bs; ++k)
      Hx[bs * i + k] = d[bs * _owned[i] + k];
}
//-----------------------------------------------------------------------------
fsai::coupling::StepReport fsai::coupling::PartitionedFsi::step(double t)
{
  common::ScopedTimer timer("fsi: step");
  _flow.save_state();
  _solid.save_state();
  std::vector<double> x(_x_n.size());
  for (std::size_t i = 0; i < x.size(); ++i)
    x[i] = _accepted >= 2 ? 2 * _x_n[i] - _x_nn[i] : _x_n[i];
  StepReport rep
      = _loop.step(t, x,
                   [&](std::span<const double> xi, std::span<double> Hx)
                   { evaluate(t, xi, Hx); });
  _motion.advance();
  _x_nn = _x_n;
  _x_n = x;
  ++_accepted;
  return rep;
}
//-----------------------------------------------------------------------------
std::vector<std::int64_t> fsai::coupling::PartitionedFsi::owned_keys() const
{
  // Partition-independent keys of the owned interface dof blocks: the
  // restart's partition (and rank count) may differ
  const auto all = io::node_keys(*_flow.velocity_space());
  std::vector<std::int64_t> keys;
  for (auto d : _owned)
    keys.push_back(all[d]);
  return keys;
}
//-----------------------------------------------------------------------------
void fsai::coupling::PartitionedFsi::save(io::RankState& state,
                                          const std::string& prefix) const
{
  const int bs = _flow.velocity_space()->dofmap()->index_map_bs();
  const auto keys = owned_keys();
  const auto n = std::int32_t(_owned.size());
  io::put_blocks(state, prefix + "x_n", _x_n, bs, keys, n);
  io::put_blocks(state, prefix + "x_nn", _x_nn, bs, keys, n);
  state[prefix + "accepted"] = {double(_accepted)};
}
//-----------------------------------------------------------------------------
void fsai::coupling::PartitionedFsi::load(
    const std::vector<io::RankState>& ranks, const std::string& prefix)
{
  const int bs = _flow.velocity_space()->dofmap()->index_map_bs();
  const auto keys = owned_keys();
  io::get_blocks(ranks, prefix + "x_n", _x_n, bs, keys);
  io::get_blocks(ranks, prefix + "x_nn", _x_nn, bs, keys);
  _accepted = int(io::state_entry(ranks.at(0), prefix + "accepted", 1)[0]);
  _loop.clear_history();
}
