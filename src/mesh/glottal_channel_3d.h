// Copyright (C) 2026 fsai developers
#pragma once

#include "benchmarks.h"
#include "vocal_fold.h"
#include <mpi.h>

namespace fsai::common
{
class Parameters;
}

namespace fsai::mesh
{
/// The 3D glottal channel of the fold3d scene ([channel] section): one
/// vocal fold (VocalFoldGeometry: x lateral → medial, y inferior →
/// superior, z anterior → posterior) in the half-channel
///   [0, depth + half_gap] × [−subglottal, height + supraglottal] × [0, length]
/// whose face x = depth + half_gap is the mid-sagittal symmetry plane.
/// The fold's lateral face lies on the channel wall x = 0, its anterior
/// and posterior faces on the walls z = 0 and z = length (where it is
/// held). The anterior–posterior mid-plane is not used as a symmetry
/// plane: the fold's modes that are odd in z are kept.
struct GlottalChannel3dGeometry
{
  double half_gap = 0.3e-3;    ///< rest half-gap, medial surface to plane
  double subglottal = 5e-3;    ///< channel below the fold [m]
  double supraglottal = 10e-3; ///< channel above the fold [m]
  double h_gap = 0.3e-3;       ///< cell size at the medial surface [m]
  double h_far = 1.5e-3;       ///< cell size far from it [m]
  double transition = 3e-3;    ///< distance over which h_gap grows [m]

  void bind(fsai::common::Parameters& p);
  void validate() const;
  /// x of the symmetry plane for `fold`
  double midplane(const VocalFoldGeometry& fold) const
  {
    return fold.depth + half_gap;
  }
};

/// Fluid and fold meshed as one gmsh model (tetrahedra sharing the
/// interface nodes). fluid: facet groups "inlet" (y = −subglottal),
/// "outlet" (y = height + supraglottal), "walls" (x = 0, z = 0, z =
/// length), "midplane" (the symmetry plane), "interface"; cell group
/// "fluid". solid: facet groups "clamped" (lateral, anterior, posterior
/// faces) and "interface"; cell group "solid". Size h_gap in the box
/// around the medial surface and the glottis, growing to h_far.
FluidSolidMeshes glottal_channel_3d(MPI_Comm comm,
                                    const VocalFoldGeometry& fold,
                                    const GlottalChannel3dGeometry& channel);
} // namespace fsai::mesh
