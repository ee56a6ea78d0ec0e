// Copyright (C) 2026 fsai developers
#include "field_state.h"
#include "../common/errors.h"
#include <dolfinx/common/IndexMap.h>
#include <dolfinx/fem/DofMap.h>
#include <dolfinx/mesh/Topology.h>
#include <dolfinx/mesh/cell_types.h>
#include <unordered_map>

std::vector<std::int64_t>
fsai::io::node_keys(const dolfinx::fem::FunctionSpace& V)
{
  const auto& mesh = *V.mesh();
  const int tdim = mesh.topology().dim();
  const auto& dofmap = *V.dofmap();
  const std::int32_t nblocks
      = dofmap.index_map->size_local() + dofmap.index_map->num_ghosts();
  const auto& input = mesh.geometry().input_global_indices();
  const auto& xdofs = mesh.geometry().dofmap();
  auto cmap = mesh.topology().index_map(tdim);
  const std::int32_t ncells = cmap->size_local() + cmap->num_ghosts();
  const auto& layout = dofmap.element_dof_layout();
  const auto edges
      = dolfinx::mesh::get_entity_vertices(mesh.topology().cell_type(), 1);
  const int nv = dolfinx::mesh::num_cell_vertices(mesh.topology().cell_type());
  // P1: one block per vertex; P2: also one per edge (keyed by its two
  // vertices, as negative numbers below -1)
  const bool p2 = layout.num_dofs() == nv + edges.num_nodes();
  if (layout.num_entity_dofs(0) != 1
      or (layout.num_dofs() != nv and !(p2 and layout.num_entity_dofs(1) == 1)))
  {
    throw std::runtime_error("checkpoint: node keys need a P1 or P2 space");
  }
  std::vector<std::int64_t> keys(nblocks, -1);
  for (std::int32_t c = 0; c < ncells; ++c)
  {
    auto cd = dofmap.cell_dofs(c);
    auto xd = xdofs.links(c);
    if (int(xd.size()) != nv)
      throw std::runtime_error("checkpoint: node keys need a P1 mesh");
    for (int i = 0; i < nv; ++i)
      keys[cd[layout.entity_dofs(0, i)[0]]] = input[xd[i]];
    if (!p2)
      continue;
    for (std::int32_t e = 0; e < edges.num_nodes(); ++e)
    {
      std::int64_t a = input[xd[edges.links(e)[0]]],
                   b = input[xd[edges.links(e)[1]]];
      if (a > b)
        std::swap(a, b);
      keys[cd[layout.entity_dofs(1, e)[0]]] = -2 - (b * (b + 1) / 2 + a);
    }
  }
  return keys;
}

std::vector<std::int64_t> fsai::io::cell_keys(const dolfinx::mesh::Mesh& mesh)
{
  const auto& idx = mesh.topology().original_cell_index;
  auto cmap = mesh.topology().index_map(mesh.topology().dim());
  const std::size_t ncells = cmap->size_local() + cmap->num_ghosts();
  if (idx.size() < ncells)
    throw std::runtime_error("checkpoint: the mesh has no input index for "
                             "its ghost cells");
  return std::vector<std::int64_t>(idx.begin(), idx.begin() + ncells);
}

void fsai::io::put_blocks(RankState& state, const std::string& name,
                          std::span<const double> values, int bs,
                          std::span<const std::int64_t> keys,
                          std::int32_t owned)
{
  state[name].assign(values.begin(), values.begin() + std::size_t(bs) * owned);
  // Keys as doubles: exact up to 2^53
  state[name + "#keys"].assign(keys.begin(), keys.begin() + owned);
}

void fsai::io::get_blocks(const std::vector<RankState>& ranks,
                          const std::string& name, std::span<double> values,
                          int bs, std::span<const std::int64_t> keys)
{
  std::unordered_map<std::int64_t, std::size_t> local;
  local.reserve(keys.size());
  for (std::size_t i = 0; i < keys.size(); ++i)
    local.emplace(keys[i], i);
  std::vector<char> found(keys.size(), 0);
  for (const auto& s : ranks)
  {
    const auto& v = state_entry(s, name);
    const auto& k = state_entry(s, name + "#keys");
    if (v.size() != k.size() * std::size_t(bs))
      throw InputError("restart: checkpoint entry '" + name
                       + "' does not match its keys");
    for (std::size_t j = 0; j < k.size(); ++j)
    {
      auto it = local.find(std::int64_t(k[j]));
      if (it == local.end())
        continue;
      std::copy_n(v.begin() + j * bs, bs, values.begin() + it->second * bs);
      found[it->second] = 1;
    }
  }
  for (std::size_t i = 0; i < keys.size(); ++i)
  {
    if (!found[i])
    {
      throw InputError("restart: checkpoint entry '" + name
                       + "' has no value for mesh entity "
                       + std::to_string(keys[i])
                       + " (the checkpoint is of another mesh)");
    }
  }
}

std::vector<fsai::io::RankState>
fsai::io::read_all_rank_states(MPI_Comm comm, const std::string& stem,
                               int nranks)
{
  std::vector<RankState> all;
  for (int r = 0; r < nranks; ++r)
    all.push_back(
        read_rank_state_file(comm, stem + ".r" + std::to_string(r) + ".bin"));
  return all;
}
