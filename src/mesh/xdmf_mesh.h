// Copyright (C) 2026 fsai developers
// Meshes with tags to and from XDMF/HDF5 (for meshes too costly to rebuild
// with gmsh every run, or made elsewhere).
#pragma once

#include "MeshData.h"
#include <mpi.h>
#include <string>

namespace fsai::mesh
{
/// Write mesh, cell tags ("cell_tags") and facet tags ("facet_tags").
/// Group names go to the XDMF's Information element "fsai_groups".
void write_xdmf(const std::string& path, const MeshData& data);

/// Read a mesh named `mesh_name` (affine triangles or tetrahedra) and, if
/// present, tags named "cell_tags" and "facet_tags" and the group names
/// written by write_xdmf
MeshData read_xdmf(MPI_Comm comm, const std::string& path,
                   const std::string& mesh_name = "mesh");
} // namespace fsai::mesh
