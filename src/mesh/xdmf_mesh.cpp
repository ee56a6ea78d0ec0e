// Copyright (C) 2026 fsai developers
#include "xdmf_mesh.h"
#include "../common/errors.h"
#include <dolfinx/fem/CoordinateElement.h>
#include <dolfinx/io/XDMFFile.h>
#include <filesystem>
#include <sstream>

using namespace dolfinx;

namespace
{
/// "kind name tag;..." for the group names
std::string encode(const fsai::mesh::MeshData& d)
{
  std::ostringstream s;
  for (auto& [n, t] : d.cell_names)
    s << "cell " << n << " " << t << ";";
  for (auto& [n, t] : d.facet_names)
    s << "facet " << n << " " << t << ";";
  return s.str();
}

void decode(const std::string& text, fsai::mesh::MeshData& d)
{
  std::istringstream s(text);
  std::string item;
  while (std::getline(s, item, ';'))
  {
    std::istringstream f(item);
    std::string kind, name;
    int tag;
    if (f >> kind >> name >> tag)
      (kind == "cell" ? d.cell_names : d.facet_names)[name] = tag;
  }
}
} // namespace

//-----------------------------------------------------------------------------
void fsai::mesh::write_xdmf(const std::string& path, const MeshData& data)
{
  io::XDMFFile file(data.mesh->comm(), path, "w");
  file.write_mesh(*data.mesh);
  const std::string geometry
      = "/Xdmf/Domain/Grid[@Name='" + data.mesh->name + "']/Geometry";
  if (data.cell_tags)
    file.write_meshtags(*data.cell_tags, geometry);
  if (data.facet_tags)
    file.write_meshtags(*data.facet_tags, geometry);
  file.write_information("fsai_groups", encode(data), "/Xdmf/Domain");
}
//-----------------------------------------------------------------------------
fsai::mesh::MeshData fsai::mesh::read_xdmf(MPI_Comm comm,
                                           const std::string& path,
                                           const std::string& mesh_name)
{
  if (!std::filesystem::is_regular_file(path))
    throw InputError("mesh file '" + path + "' not found");
  io::XDMFFile file(comm, path, "r");
  auto [cell_type, degree] = file.read_cell_type(mesh_name);
  if (degree != 1
      or (cell_type != dolfinx::mesh::CellType::triangle
          and cell_type != dolfinx::mesh::CellType::tetrahedron))
  {
    throw InputError("mesh file '" + path
                     + "': only affine triangles or tetrahedra are supported");
  }
  MeshData out;
  out.mesh = std::make_shared<dolfinx::mesh::Mesh>(
      file.read_mesh(fem::CoordinateElement(cell_type, 1),
                     dolfinx::mesh::GhostMode::shared_facet, mesh_name));
  const int tdim = out.mesh->topology().dim();
  out.mesh->topology_mutable().create_entities(tdim - 1);
  out.mesh->topology_mutable().create_connectivity(tdim - 1, tdim);
  out.mesh->topology_mutable().create_connectivity(tdim, 0);

  // Tags and names are optional; read_meshtags throws if absent
  for (auto [name, target] : {std::pair{"cell_tags", &out.cell_tags},
                              std::pair{"facet_tags", &out.facet_tags}})
  {
    try
    {
      *target = std::make_shared<dolfinx::mesh::MeshTags<std::int32_t>>(
          file.read_meshtags(out.mesh, name));
    }
    catch (const std::runtime_error&)
    {
      *target = nullptr;
    }
  }
  try
  {
    decode(file.read_information("fsai_groups", "/Xdmf/Domain"), out);
  }
  catch (const std::runtime_error&)
  {
  }
  return out;
}
//-----------------------------------------------------------------------------
