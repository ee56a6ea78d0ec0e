// Copyright (C) 2026 fsai developers
#include "gmsh_model.h"
#include "../common/errors.h"
#include "../common/timer.h"
#include <algorithm>
#include <dolfinx/common/MPI.h>
#include <dolfinx/fem/CoordinateElement.h>
#include <dolfinx/graph/AdjacencyList.h>
#include <dolfinx/io/cells.h>
#include <dolfinx/io/xdmf_utils.h>
#include <dolfinx/mesh/cell_types.h>
#include <dolfinx/mesh/utils.h>
#include <filesystem>
#include <gmsh.h>
#include <map>
#include <set>
#include <unordered_map>

using namespace dolfinx;

namespace
{
/// Elements of all physical groups of dimension `dim`, as gmsh node tags
/// (row-major, `nodes_per_entity` per row) with their group tags
struct TaggedEntities
{
  std::vector<std::size_t> nodes;
  std::vector<std::int32_t> tags;
  int element_type = -1;
  int nodes_per_entity = 0;
  std::map<std::string, int> names;
};

TaggedEntities tagged_entities(int dim)
{
  TaggedEntities out;
  gmsh::vectorpair groups;
  gmsh::model::getPhysicalGroups(groups, dim);
  for (auto [d, tag] : groups)
  {
    std::string name;
    gmsh::model::getPhysicalName(d, tag, name);
    out.names[name.empty() ? std::to_string(tag) : name] = tag;
    std::vector<int> entities;
    gmsh::model::getEntitiesForPhysicalGroup(d, tag, entities);
    for (int e : entities)
    {
      std::vector<int> types;
      std::vector<std::vector<std::size_t>> elem_tags, node_tags;
      gmsh::model::mesh::getElements(types, elem_tags, node_tags, d, e);
      for (std::size_t k = 0; k < types.size(); ++k)
      {
        if (out.element_type < 0)
        {
          out.element_type = types[k];
          std::string ename;
          int edim, order, nn, nprim;
          std::vector<double> coords;
          gmsh::model::mesh::getElementProperties(types[k], ename, edim, order,
                                                  nn, coords, nprim);
          out.nodes_per_entity = nn;
        }
        else if (out.element_type != types[k])
        {
          throw std::runtime_error(
              "gmsh model mixes element types in dimension "
              + std::to_string(dim) + " (only one type is supported)");
        }
        out.nodes.insert(out.nodes.end(), node_tags[k].begin(),
                         node_tags[k].end());
        out.tags.insert(out.tags.end(), elem_tags[k].size(), tag);
      }
    }
  }
  return out;
}

/// Flatten a name->tag map for broadcasting: "name\0tag\0..."
std::string pack_names(const std::map<std::string, int>& names)
{
  std::string s;
  for (auto& [n, t] : names)
    s += n + '\0' + std::to_string(t) + '\0';
  return s;
}

std::map<std::string, int> unpack_names(const std::string& s)
{
  std::map<std::string, int> names;
  std::size_t pos = 0;
  while (pos < s.size())
  {
    std::size_t a = s.find('\0', pos);
    std::size_t b = s.find('\0', a + 1);
    names[s.substr(pos, a - pos)] = std::stoi(s.substr(a + 1, b - a - 1));
    pos = b + 1;
  }
  return names;
}

/// Tag of group `name` in `names`; the error lists the known groups
int lookup(const std::map<std::string, int>& names, const std::string& kind,
           const std::string& name)
{
  auto it = names.find(name);
  if (it != names.end())
    return it->second;
  std::string known;
  for (auto& [n, t] : names)
    known += " " + n;
  throw std::runtime_error("no " + kind + " group '" + name
                           + "'; groups:" + known);
}

void broadcast(MPI_Comm comm, int root, std::string& s)
{
  std::uint64_t n = s.size();
  MPI_Bcast(&n, 1, MPI_UINT64_T, root, comm);
  s.resize(n);
  MPI_Bcast(s.data(), static_cast<int>(n), MPI_CHAR, root, comm);
}

/// Run `fn` on `root` only; an exception there is re-thrown on every rank
/// (message prefixed by `prefix`), so no rank waits in a later collective
void run_on_root(MPI_Comm comm, int root, const std::function<void()>& fn,
                 const std::string& prefix)
{
  std::string error;
  if (dolfinx::MPI::rank(comm) == root)
  {
    try
    {
      fn();
    }
    catch (const std::exception& e)
    {
      error = e.what();
    }
    catch (const std::string& e)
    {
      // gmsh 4.8 throws its error messages as std::string
      error = e.empty()                 ? std::string("gmsh: unknown error")
              : e.rfind("gmsh", 0) == 0 ? e
                                        : "gmsh: " + e;
    }
    catch (...)
    {
      error = "gmsh: unknown error";
    }
  }
  broadcast(comm, root, error);
  if (!error.empty())
    throw std::runtime_error(prefix + error);
}

/// Gmsh node tags -> 0-based rows of the node array, permuted from gmsh's to
/// DOLFINx's local node order
std::vector<std::int64_t>
to_dolfinx(const TaggedEntities& e, dolfinx::mesh::CellType type,
           const std::unordered_map<std::size_t, std::int64_t>& index)
{
  const std::vector<std::uint8_t> perm
      = io::cells::perm_gmsh(type, e.nodes_per_entity);
  const std::size_t n = e.nodes_per_entity;
  std::vector<std::int64_t> out(e.nodes.size());
  for (std::size_t c = 0; c < e.nodes.size() / n; ++c)
    for (std::size_t i = 0; i < n; ++i)
      out[c * n + i] = index.at(e.nodes[c * n + perm[i]]);
  return out;
}

/// MeshTags from entities given by global input node indices (collective)
std::shared_ptr<dolfinx::mesh::MeshTags<std::int32_t>>
make_tags(const std::shared_ptr<dolfinx::mesh::Mesh>& m, int dim,
          const std::vector<std::int64_t>& entities,
          const std::vector<std::int32_t>& values, int nodes_per_entity,
          const std::string& name)
{
  auto [local_entities, local_values]
      = io::xdmf_utils::distribute_entity_data(*m, dim, entities, values);
  auto adj = graph::regular_adjacency_list(std::move(local_entities),
                                           nodes_per_entity);
  auto tags = std::make_shared<dolfinx::mesh::MeshTags<std::int32_t>>(
      dolfinx::mesh::create_meshtags(
          std::shared_ptr<const dolfinx::mesh::Mesh>(m), dim, adj,
          std::span<const std::int32_t>(local_values)));
  tags->name = name;
  return tags;
}
} // namespace

//-----------------------------------------------------------------------------
fsai::mesh::GmshSession::GmshSession(MPI_Comm comm, int root, bool verbose)
    : _active(dolfinx::MPI::rank(comm) == root)
{
  if (_active)
  {
    gmsh::initialize(0, nullptr, false);
    gmsh::option::setNumber("General.Terminal", verbose ? 1 : 0);
    gmsh::option::setNumber("General.Verbosity", verbose ? 5 : 2);
  }
}
//-----------------------------------------------------------------------------
fsai::mesh::GmshSession::~GmshSession()
{
  if (_active)
    gmsh::finalize();
}
//-----------------------------------------------------------------------------
fsai::mesh::MeshData
fsai::mesh::model_to_mesh(MPI_Comm comm, int root, int gdim,
                          const std::vector<std::string>& cell_groups)
{
  if (gdim != 2 and gdim != 3)
    throw std::runtime_error("model_to_mesh: gdim must be 2 or 3");
  common::ScopedTimer timer("mesh: distribute");
  const int tdim = gdim;
  const dolfinx::mesh::CellType cell_type
      = tdim == 2 ? dolfinx::mesh::CellType::triangle
                  : dolfinx::mesh::CellType::tetrahedron;
  const int nv_cell = tdim + 1, nv_facet = tdim;

  std::vector<double> x;
  std::vector<std::int64_t> cells, facets;
  std::vector<std::int32_t> cell_values, facet_values;
  std::string cell_names, facet_names;
  run_on_root(
      comm, root,
      [&]()
      {
        // Nodes: gmsh tags need not be contiguous; rows in tag order
        std::vector<std::size_t> node_tags;
        std::vector<double> coords, param;
        gmsh::model::mesh::getNodes(node_tags, coords, param, -1, -1);
        std::unordered_map<std::size_t, std::int64_t> index;
        x.resize(node_tags.size() * gdim);
        for (std::size_t i = 0; i < node_tags.size(); ++i)
        {
          index[node_tags[i]] = i;
          for (int j = 0; j < gdim; ++j)
            x[i * gdim + j] = coords[3 * i + j];
        }

        TaggedEntities c = tagged_entities(tdim);
        if (c.tags.empty())
        {
          throw std::runtime_error("gmsh model has no meshed physical group of "
                                   "dimension "
                                   + std::to_string(tdim));
        }
        if (c.nodes_per_entity != nv_cell)
          throw std::runtime_error("gmsh model: only affine (order 1) "
                                   "triangles/tetrahedra are supported");
        cells = to_dolfinx(c, cell_type, index);
        cell_values = c.tags;
        if (!cell_groups.empty())
        {
          // Only the cells of the named groups (one part of a model whose
          // parts share nodes on their interfaces)
          std::set<std::int32_t> keep;
          for (auto& name : cell_groups)
            keep.insert(lookup(c.names, "cell", name));
          std::vector<std::int64_t> kc;
          std::vector<std::int32_t> kv;
          for (std::size_t i = 0; i < cell_values.size(); ++i)
          {
            if (keep.count(cell_values[i]))
            {
              kc.insert(kc.end(), cells.begin() + i * nv_cell,
                        cells.begin() + (i + 1) * nv_cell);
              kv.push_back(cell_values[i]);
            }
          }
          cells = std::move(kc);
          cell_values = std::move(kv);
          std::map<std::string, int> kept_names;
          for (auto& [n, t] : c.names)
            if (keep.count(t))
              kept_names[n] = t;
          c.names = kept_names;
        }
        cell_names = pack_names(c.names);

        TaggedEntities f = tagged_entities(tdim - 1);
        if (!f.tags.empty())
        {
          facets = to_dolfinx(
              f, dolfinx::mesh::cell_entity_type(cell_type, tdim - 1, 0),
              index);
          facet_values = f.tags;
          facet_names = pack_names(f.names);
        }

        // Keep only the nodes of cells: gmsh also meshes construction
        // points (spline control points, unused .geo points), and DOLFINx
        // 0.5.2 crashes in distribute_entity_data on unreferenced nodes
        std::vector<std::int64_t> renum(x.size() / gdim, -1);
        std::int64_t used = 0;
        for (std::int64_t& n : cells)
        {
          if (renum[n] < 0)
            renum[n] = used++;
          n = renum[n];
        }
        // Tagged facets: those of another part (a node outside this part's
        // cells) are dropped; without parts that is a broken model
        std::vector<std::int64_t> kf;
        std::vector<std::int32_t> kfv;
        for (std::size_t f = 0; f < facet_values.size(); ++f)
        {
          bool inside = true;
          for (int i = 0; i < nv_facet; ++i)
            inside = inside and renum[facets[f * nv_facet + i]] >= 0;
          if (!inside and cell_groups.empty())
          {
            throw std::runtime_error("gmsh model: a tagged facet has a node "
                                     "that belongs to no cell");
          }
          if (inside)
          {
            for (int i = 0; i < nv_facet; ++i)
              kf.push_back(renum[facets[f * nv_facet + i]]);
            kfv.push_back(facet_values[f]);
          }
        }
        facets = std::move(kf);
        facet_values = std::move(kfv);
        std::vector<double> xc(used * gdim);
        for (std::size_t i = 0; i < renum.size(); ++i)
          if (renum[i] >= 0)
            std::copy_n(x.begin() + i * gdim, gdim,
                        xc.begin() + renum[i] * gdim);
        x = std::move(xc);
      },
      "");
  broadcast(comm, root, cell_names);
  broadcast(comm, root, facet_names);

  // Distribute (cells are partitioned from the root's data)
  fem::CoordinateElement element(cell_type, 1);
  graph::AdjacencyList<std::int64_t> cell_adj = graph::regular_adjacency_list(
      std::vector<std::int64_t>(cells), nv_cell);
  const std::size_t num_nodes = x.size() / gdim;
  auto m = std::make_shared<dolfinx::mesh::Mesh>(dolfinx::mesh::create_mesh(
      comm, cell_adj, element, x, {num_nodes, static_cast<std::size_t>(gdim)},
      dolfinx::mesh::GhostMode::shared_facet));

  MeshData out;
  out.mesh = m;
  m->topology_mutable().create_entities(tdim - 1);
  m->topology_mutable().create_connectivity(tdim - 1, tdim);
  m->topology_mutable().create_connectivity(tdim, 0);
  out.cell_tags = make_tags(m, tdim, cells, cell_values, nv_cell, "cell_tags");
  out.facet_tags
      = make_tags(m, tdim - 1, facets, facet_values, nv_facet, "facet_tags");
  out.cell_names = unpack_names(cell_names);
  out.facet_names = unpack_names(facet_names);
  return out;
}
//-----------------------------------------------------------------------------
fsai::mesh::MeshData
fsai::mesh::build_with_gmsh(MPI_Comm comm, int gdim,
                            const std::function<void()>& build)
{
  common::ScopedTimer timer("mesh: gmsh");
  GmshSession session(comm); // Active on rank 0, the root below
  run_on_root(comm, 0, build, "gmsh: ");
  timer.stop();
  return model_to_mesh(comm, 0, gdim);
}
//-----------------------------------------------------------------------------
std::vector<fsai::mesh::MeshData>
fsai::mesh::build_parts_with_gmsh(MPI_Comm comm, int gdim,
                                  const std::function<void()>& build,
                                  const std::vector<std::string>& parts)
{
  common::ScopedTimer timer("mesh: gmsh");
  GmshSession session(comm);
  run_on_root(comm, 0, build, "gmsh: ");
  timer.stop();
  std::vector<MeshData> out;
  for (auto& part : parts)
    out.push_back(model_to_mesh(comm, 0, gdim, {part}));
  return out;
}
//-----------------------------------------------------------------------------
void fsai::mesh::size_near_curves(const std::vector<int>& curves, double h_min,
                                  double h_max, double dist_max,
                                  int points_per_curve, const SizeBand& band,
                                  const SizeBox& box, const SizeBox& coarse)
{
  namespace field = gmsh::model::mesh::field;
  // h_min up to `dist_min` from `on`, h_max from dist_min + dist_max on
  auto graded = [&](const std::vector<int>& on, double dist_min)
  {
    const int fd = field::add("Distance");
    field::setNumbers(fd, "CurvesList",
                      std::vector<double>(on.begin(), on.end()));
    field::setNumber(fd, "NumPointsPerCurve", points_per_curve);
    const int ft = field::add("Threshold");
    field::setNumber(ft, "InField", fd);
    field::setNumber(ft, "SizeMin", h_min);
    field::setNumber(ft, "SizeMax", h_max);
    field::setNumber(ft, "DistMin", dist_min);
    field::setNumber(ft, "DistMax", dist_min + dist_max);
    return ft;
  };
  // box.size inside the box, `outside` beyond its transition layer
  auto box_field = [](const SizeBox& box, double outside)
  {
    const int fb = field::add("Box");
    field::setNumber(fb, "VIn", box.size);
    field::setNumber(fb, "VOut", outside);
    field::setNumber(fb, "XMin", box.xy[0]);
    field::setNumber(fb, "XMax", box.xy[1]);
    field::setNumber(fb, "YMin", box.xy[2]);
    field::setNumber(fb, "YMax", box.xy[3]);
    field::setNumber(fb, "Thickness", box.transition);
    return fb;
  };
  int f = graded(curves, 0.0);
  if (!band.curves.empty())
  {
    const int fb = graded(band.curves, band.width);
    const int fmax = field::add("Max");
    field::setNumbers(fmax, "FieldsList", {double(f), double(fb)});
    f = fmax;
  }
  if (box.size > 0)
  {
    const int fmin = field::add("Min");
    field::setNumbers(fmin, "FieldsList",
                      {double(f), double(box_field(box, h_max))});
    f = fmin;
  }
  if (coarse.size > 0)
  {
    // Outside the box (and its transition) the Max takes the other fields
    const int fmax = field::add("Max");
    field::setNumbers(fmax, "FieldsList",
                      {double(f), double(box_field(coarse, h_min))});
    f = fmax;
  }
  field::setAsBackgroundMesh(f);
  gmsh::option::setNumber("Mesh.MeshSizeExtendFromBoundary", 0);
  gmsh::option::setNumber("Mesh.MeshSizeFromPoints", 0);
  gmsh::option::setNumber("Mesh.MeshSizeFromCurvature", 0);
}
//-----------------------------------------------------------------------------
fsai::mesh::MeshData fsai::mesh::from_geo_file(MPI_Comm comm,
                                               const std::string& path,
                                               int gdim, double h)
{
  if (!std::filesystem::is_regular_file(path))
    throw InputError("mesh file '" + path + "' not found");
  return build_with_gmsh(comm, gdim,
                         [&]()
                         {
                           if (h > 0)
                           {
                             gmsh::onelab::setNumber("fsai/h", {h});
                             gmsh::option::setNumber("Mesh.MeshSizeMax", h);
                           }
                           gmsh::open(path);
                           gmsh::model::mesh::generate(gdim);
                         });
}
//-----------------------------------------------------------------------------
std::vector<std::int32_t> fsai::mesh::MeshData::facets_where(
    const std::string& name,
    const std::function<bool(const double*)>& keep) const
{
  const std::vector<std::int32_t> all = facet_tags->find(facet_tag(name));
  const std::vector<double> mid = dolfinx::mesh::compute_midpoints(
      *mesh, mesh->topology().dim() - 1, all);
  std::vector<std::int32_t> out;
  for (std::size_t i = 0; i < all.size(); ++i)
    if (keep(mid.data() + 3 * i))
      out.push_back(all[i]);
  return out;
}
//-----------------------------------------------------------------------------
int fsai::mesh::MeshData::facet_tag(const std::string& name) const
{
  return lookup(facet_names, "facet", name);
}
//-----------------------------------------------------------------------------
int fsai::mesh::MeshData::cell_tag(const std::string& name) const
{
  return lookup(cell_names, "cell", name);
}
//-----------------------------------------------------------------------------
//-----------------------------------------------------------------------------
std::set<int> fsai::mesh::tag_fluid_solid_3d(
    int fluid, int solid,
    const std::function<std::string(const std::array<double, 3>&)>& name_of)
{
  auto faces = [](int volume)
  {
    gmsh::vectorpair b;
    gmsh::model::getBoundary({{3, volume}}, b, false, false, false);
    std::set<int> f;
    for (auto [d, t] : b)
      f.insert(std::abs(t));
    return f;
  };
  const std::set<int> ff = faces(fluid), fs = faces(solid);
  std::map<std::string, std::vector<int>> groups;
  for (int f : ff)
  {
    std::array<double, 3> c;
    gmsh::model::occ::getCenterOfMass(2, f, c[0], c[1], c[2]);
    groups[fs.count(f) ? "interface" : name_of(c)].push_back(f);
  }
  for (int f : fs)
    if (!ff.count(f))
      groups["clamped"].push_back(f);
  int id = 1;
  for (auto& [name, g] : groups)
  {
    gmsh::model::addPhysicalGroup(2, g, id);
    gmsh::model::setPhysicalName(2, id++, name);
  }
  gmsh::model::addPhysicalGroup(3, {fluid}, 1);
  gmsh::model::setPhysicalName(3, 1, "fluid");
  gmsh::model::addPhysicalGroup(3, {solid}, 2);
  gmsh::model::setPhysicalName(3, 2, "solid");
  return ff;
}
