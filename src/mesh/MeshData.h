// Copyright (C) 2026 fsai developers
#pragma once

#include <dolfinx/mesh/Mesh.h>
#include <dolfinx/mesh/MeshTags.h>
#include <functional>
#include <map>
#include <memory>
#include <string>

namespace fsai::mesh
{
/// A distributed mesh with the cell and facet tags of its gmsh physical
/// groups and the names of those groups
struct MeshData
{
  std::shared_ptr<dolfinx::mesh::Mesh> mesh;
  std::shared_ptr<dolfinx::mesh::MeshTags<std::int32_t>> cell_tags;
  std::shared_ptr<dolfinx::mesh::MeshTags<std::int32_t>> facet_tags;
  /// Physical group name -> tag, separately for cells and facets
  std::map<std::string, int> cell_names, facet_names;

  /// Tag of the facet group `name`; throws naming the available groups
  int facet_tag(const std::string& name) const;
  /// Tag of the cell group `name`
  int cell_tag(const std::string& name) const;
  /// Local facets of the group `name` whose midpoint (x, y, z) satisfies
  /// `keep`
  std::vector<std::int32_t>
  facets_where(const std::string& name,
               const std::function<bool(const double*)>& keep) const;
};
} // namespace fsai::mesh
