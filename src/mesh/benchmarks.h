// Copyright (C) 2026 fsai developers
// Geometries of the published benchmarks (references/).
#pragma once

#include "MeshData.h"
#include <mpi.h>

namespace fsai::mesh
{
/// The elastic beam of Turek & Hron (2006) (turek_hron_setup.csv): the
/// rectangle [0.2, 0.6] x [0.19, 0.21] m outside the cylinder of radius
/// 0.05 m centred at (0.2, 0.2), which clamps it. Triangles of size h.
/// Facet groups "clamped" (on the cylinder, 1) and "free" (2); cell group
/// "beam" (1). Point A = (0.6, 0.2) is a mesh vertex.
MeshData turek_hron_beam(MPI_Comm comm, double h);
} // namespace fsai::mesh

namespace fsai::mesh
{
/// The channel of the DFG "flow around a cylinder" benchmark (Schäfer &
/// Turek 1996, dfg_cylinder.csv): [0, 2.2] x [0, 0.41] m without the
/// cylinder of radius 0.05 m centred at (0.2, 0.2). Triangles of size
/// h_cyl on the cylinder growing to h in the far field (gmsh distance
/// field). Facet groups "inlet" (1), "outlet" (2), "walls" (3),
/// "cylinder" (4); cell group "fluid" (1).
MeshData dfg_channel(MPI_Comm comm, double h, double h_cyl);
} // namespace fsai::mesh

namespace fsai::mesh
{
/// The Turek & Hron (2006) FSI geometry (turek_hron_setup.csv) meshed as
/// one gmsh model with two parts that share the interface nodes: the
/// channel [0, 2.5] x [0, 0.41] m without the cylinder (r = 0.05 m at
/// (0.2, 0.2)) and the beam [0.2, 0.6] x [0.19, 0.21] m outside it. Size
/// h_i on the cylinder, the beam and its interface, growing to h at 0.3 m.
/// fluid: facet groups "inlet", "outlet", "walls", "cylinder", "interface";
/// cell group "fluid". solid: facet groups "clamped", "interface"; cell
/// group "solid". Point A = (0.6, 0.2) is a vertex of both.
struct FluidSolidMeshes
{
  MeshData fluid, solid;
};
FluidSolidMeshes turek_hron_fsi(MPI_Comm comm, double h, double h_i);
} // namespace fsai::mesh

namespace fsai::mesh
{
/// A small 3D FSI scene: the channel [0, 1] x [0, 0.4] x [0, 0.4] m (x the
/// stream direction, y up) with an elastic flap [0.4, 0.45] x [0, 0.25] x
/// [0.1, 0.3] m standing on its floor, meshed as one model with two parts
/// (tetrahedra of size h). fluid: "inlet" (x = 0), "outlet" (x = 1),
/// "walls", "interface"; solid: "clamped" (the flap's base), "interface".
FluidSolidMeshes channel_flap_3d(MPI_Comm comm, double h);
} // namespace fsai::mesh
