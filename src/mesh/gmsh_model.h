// Copyright (C) 2026 fsai developers
// In-process gmsh (C++ API, libgmsh-dev) -> distributed DOLFINx mesh.
#pragma once

#include "MeshData.h"
#include <array>
#include <functional>
#include <mpi.h>
#include <set>
#include <string>
#include <vector>

namespace fsai::mesh
{
/// gmsh::initialize/finalize on the root rank, quiet unless `verbose`.
/// Other ranks do nothing: the model is built on the root and the mesh
/// distributed by model_to_mesh.
class GmshSession
{
public:
  explicit GmshSession(MPI_Comm comm, int root = 0, bool verbose = false);
  ~GmshSession();
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;
  /// True on the rank that owns the gmsh model
  bool active() const { return _active; }

private:
  bool _active;
};

/// Create a distributed mesh from the current gmsh model on `root`, which
/// must be meshed. Cells are the elements of the physical groups of the
/// highest dimension present (at least one required); facet tags come from
/// the physical groups of one dimension lower. Affine (first-order) cells
/// only: triangles or tetrahedra.
/// @param[in] comm Communicator of the mesh (collective)
/// @param[in] root Rank holding the gmsh model
/// @param[in] gdim Geometric dimension (2 or 3)
/// @param[in] cell_groups If not empty, only the cells of these physical
///   groups (one part of a multi-region model, e.g. "fluid"), and the
///   tagged facets whose nodes all belong to them
MeshData model_to_mesh(MPI_Comm comm, int root, int gdim,
                       const std::vector<std::string>& cell_groups = {});

/// Run `build` (gmsh API calls that create and mesh a model) on rank 0
/// inside a GmshSession, then distribute the mesh with model_to_mesh. An
/// exception in `build` is re-thrown on every rank (no rank is left
/// waiting).
MeshData build_with_gmsh(MPI_Comm comm, int gdim,
                         const std::function<void()>& build);

/// As build_with_gmsh, for a model of several parts meshed together (so
/// they share the nodes of their interfaces): one distributed mesh per
/// named cell group, in the order of `parts`
std::vector<MeshData>
build_parts_with_gmsh(MPI_Comm comm, int gdim,
                      const std::function<void()>& build,
                      const std::vector<std::string>& parts);

/// Inside a build function (rank 0), for a 3D model fragmented into one
/// fluid and one solid volume: the physical groups "fluid" (1) and "solid"
/// (2), and face groups — the faces both share "interface", the solid's
/// other faces "clamped", each of the fluid's other faces the group that
/// `name_of(centre of mass)` gives. Returns the fluid's faces
std::set<int> tag_fluid_solid_3d(
    int fluid, int solid,
    const std::function<std::string(const std::array<double, 3>&)>& name_of);

/// Inside a build function (rank 0): a background size field of the
/// current model — size h_min on `curves`, growing linearly with the
/// distance to h_max at `dist_max` (distance sampled at `points_per_curve`
/// points per curve) — with the sizes from points, boundary extension and
/// curvature switched off so that the field alone decides.
/// `band` (optional): the fine size holds only within band.width of the
/// curves band.curves; beyond it the size grows in the same way with the
/// distance from that band (the larger of the two sizes is taken)
struct SizeBand
{
  std::vector<int> curves; ///< empty: no band, `curves` are fine everywhere
  double width = 0;
};
/// `box` (optional, size > 0): size at most box.size inside the
/// axis-aligned box, growing to h_max over box.transition outside it;
/// `coarse` (optional, size > 0): size at least coarse.size inside its
/// box, falling to the other fields' size over coarse.transition outside
struct SizeBox
{
  double size = 0;                         ///< 0: no box
  std::array<double, 4> xy = {0, 0, 0, 0}; ///< x_min, x_max, y_min, y_max
  double transition = 0;
};
void size_near_curves(const std::vector<int>& curves, double h_min,
                      double h_max, double dist_max, int points_per_curve = 200,
                      const SizeBand& band = {}, const SizeBox& box = {},
                      const SizeBox& coarse = {});

/// Build a mesh from a gmsh `.geo` file: the file is opened and meshed in
/// dimension `gdim` on rank 0 and distributed.
/// @param[in] h Characteristic length passed as the gmsh option
///   Mesh.MeshSizeMax (ignored if <= 0); a `.geo` file may also read the
///   ONELAB parameter "fsai/h"
MeshData from_geo_file(MPI_Comm comm, const std::string& path, int gdim,
                       double h = -1.0);
} // namespace fsai::mesh
