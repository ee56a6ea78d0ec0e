// Copyright (C) 2026 fsai developers
#pragma once
#include "MeshData.h"
#include "benchmarks.h"
#include <array>
#include <mpi.h>
#include <vector>

namespace fsai::glottis
{
class FoldProfile;
}

namespace fsai::mesh
{
/// Mesh sizes of the glottis channel [m]
struct ChannelSizes
{
  double h_far = 0.5e-3;  ///< away from the fold
  double h_gap = 0.05e-3; ///< on the fold
  /// > 0: h_gap only up to fine_height from the axis; above, the size
  /// grows with the distance from that band in the same way, so that the
  /// fold's upper flanks, where the air is nearly at rest, are not meshed
  /// at the glottis's size
  double fine_height = 0;
  double grading = 3e-3; ///< the size grows from h_gap to h_far over this
  /// > 0: at most h_jet in the jet region, y ≤ jet_height from the fold's
  /// inferior attachment (x = 0) to the outlet (growing to h_far over
  /// `grading` outside it)
  double h_jet = 0;
  double jet_height = 4e-3;
  /// > 0: at least h_inlet in the subglottal channel up to 2·grading
  /// before the fold's inferior attachment (x ≤ −2 grading), falling to
  /// the other sizes over `grading` downstream of it
  double h_inlet = 0;
};

/// The flow domain of the glottis scene (docs/model.md "Glottis
/// closure"): the symmetric half-channel 0 ≤ y ≤ H from x = −inlet_length
/// to x = fold_length + outlet_length, less the fold (its surface a spline
/// through the profile points). Facet groups "inlet", "outlet", "axis"
/// (y = 0), "wall" (y = H) and "fold"; cell group "fluid". Size h_gap on
/// the fold, growing linearly to h_far at `grading` from it; see
/// ChannelSizes for the finer and coarser regions.
MeshData glottis_channel(MPI_Comm comm, const glottis::FoldProfile& profile,
                         const ChannelSizes& sizes);

/// The same channel with the fold surface the polyline through `curve`, the
/// moved fold's surface points from the inferior to the superior
/// attachment (without them; they stay at (0, H) and (T, H)): the mesh of a
/// remeshed fold (docs/model.md E13a)
MeshData glottis_channel(MPI_Comm comm, const glottis::FoldProfile& profile,
                         const ChannelSizes& sizes,
                         const std::vector<std::array<double, 2>>& curve);

/// Points (in the current gmsh geo model) of the fold curve, superior to
/// inferior: its superior attachment (T, H) first, every 2nd profile point,
/// its inferior attachment (0, H) last. The one definition of the fold
/// curve of every mesh of the glottis scenes (flow, fold, acoustic
/// domain), which must have the same nodes on it
std::vector<int> add_fold_points(const glottis::FoldProfile& profile);

/// The same channel (no fine band, no jet box) and the fold itself as one
/// gmsh model, so that the two meshes have the same nodes on the fold
/// curve: `fluid` as above, `solid` the fold (cell group "fold") between
/// the curve "fold" and its lateral attachment "attachment" (y = H, from
/// the inferior to the superior attachment point), meshed with the same
/// size field (h_gap at the surface; of `sizes` only h_far, h_gap and
/// grading: the finer and coarser regions must be off)
FluidSolidMeshes glottis_channel_and_fold(MPI_Comm comm,
                                          const glottis::FoldProfile& profile,
                                          const ChannelSizes& sizes);
} // namespace fsai::mesh
