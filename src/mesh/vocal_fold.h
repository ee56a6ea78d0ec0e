// Copyright (C) 2026 fsai developers
#pragma once

#include "MeshData.h"
#include <array>
#include <mpi.h>
#include <vector>

namespace fsai::common
{
class Parameters;
}

namespace fsai::mesh
{
/// Parametric 3D vocal fold ([fold] section): a coronal profile in the
/// (x, y) plane — x from the lateral (thyroid) wall x = 0 towards the
/// glottal midline, y from inferior to superior — extruded along z
/// (anterior → posterior) over the fold length.
///
/// The profile follows the shape of the M5 family of Scherer et al. (2001)
/// in simplified, explicit form: a horizontal superior surface, a rounded
/// superior-medial corner (semi-axes a, b), a vertical medial (contact)
/// surface of height t_medial, a rounded inferior-medial corner (radius
/// r_inf), and a straight inferior surface running down to the lateral wall.
/// Defaults: depth 5 mm, height 10 mm, length 16 mm. The length is an adult
/// male membranous fold (15–18 mm, Hirano 1981). The depth is the
/// vibrating tissue only (cover, ligament and the medial part of the
/// thyroarytenoid, ≈ 5 mm in Hirano's coronal sections); the face x = 0 is
/// the attachment to the stiffer lateral muscle. With the homogeneous
/// E = 8 kPa of the source paper this puts f1 in the male range (100 Hz;
/// the paper's own geometry: 101.8 Hz). The M5-sized depth 8.4 mm with
/// length 17 mm gives f1 = 61 Hz at 8 kPa — below the range: a fold that
/// deep needs a stiffer body (see `--layers 2`).
struct VocalFoldGeometry
{
  double depth = 5e-3;    ///< lateral → medial extent [m]
  double height = 10e-3;  ///< at the lateral wall [m]
  double length = 16e-3;  ///< anterior → posterior [m]
  double a = 2e-3;        ///< superior-medial corner, horizontal semi-axis
  double b = 2e-3;        ///< superior-medial corner, vertical semi-axis
  double t_medial = 1e-3; ///< vertical medial surface
  double r_inf = 1e-3;    ///< inferior-medial corner radius
  double cover = 1e-3;    ///< cover thickness for two-layer folds [m]
  double h = 1e-3;        ///< mesh size [m]

  void bind(fsai::common::Parameters& p);
  void validate() const;

  /// The free (air-facing) boundary of the profile, superior-lateral end
  /// to inferior-lateral end, as a polyline in (x, y)
  std::vector<std::array<double, 2>> free_profile() const;
};

/// Inside a gmsh build function (rank 0): the fold as an OpenCASCADE
/// entity of the current model, not yet synchronised — the profile's
/// plane surface (dim 2, in z = 0) or its extrusion over the length
/// (dim 3); returns its tag
int add_fold_body(const VocalFoldGeometry& g, int dim);

/// Tetrahedral mesh of the fold (dim 3), or triangle mesh of its coronal
/// section (dim 2, the profile in z = 0). Facet groups "lateral" (x = 0, 1),
/// "anterior" (z = 0, 2) and "posterior" (z = length, 3) in 3D only,
/// "surface" (the free surface, 4); cell group "fold" (1).
MeshData vocal_fold(MPI_Comm comm, const VocalFoldGeometry& g, int dim = 3);

/// Local facets where the fold of vocal_fold() is held: "lateral", and in
/// 3D also "anterior" and "posterior" (a section has no such faces)
std::vector<std::int32_t> attached_facets(const MeshData& m);

/// Local cells (owned and ghosts) whose midpoint lies within `distance` of
/// the open polyline `curve` in the x–y plane (the cover of a body–cover
/// fold: `curve` its free surface)
std::vector<std::int32_t>
cells_near_curve(const dolfinx::mesh::Mesh& mesh,
                 const std::vector<std::array<double, 2>>& curve,
                 double distance);

/// Local cells whose midpoint lies within g.cover of the free surface
/// (the cover of a body–cover fold)
std::vector<std::int32_t> cover_cells(const dolfinx::mesh::Mesh& mesh,
                                      const VocalFoldGeometry& g);
} // namespace fsai::mesh
