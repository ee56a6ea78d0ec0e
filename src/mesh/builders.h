// Copyright (C) 2026 fsai developers
// Parametric meshes built in-process with gmsh, with named physical groups.
#pragma once

#include "MeshData.h"
#include <array>
#include <mpi.h>

namespace fsai::mesh
{
/// Rectangle [x0, x1] x [y0, y1] (a channel when x is the stream direction),
/// unstructured triangles of size h.
/// Facet groups: "left" (1), "right" (2), "bottom" (3), "top" (4);
/// cell group "domain" (1).
MeshData rectangle(MPI_Comm comm, std::array<double, 2> p0,
                   std::array<double, 2> p1, double h);

/// Box [p0, p1], unstructured tetrahedra of size h.
/// Facet groups: "xmin" (1), "xmax" (2), "ymin" (3), "ymax" (4),
/// "zmin" (5), "zmax" (6); cell group "domain" (1).
MeshData box(MPI_Comm comm, std::array<double, 3> p0, std::array<double, 3> p1,
             double h);
} // namespace fsai::mesh
