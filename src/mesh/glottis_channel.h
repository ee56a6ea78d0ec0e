// Copyright (C) 2026 fsai developers
#pragma once
#include "MeshData.h"
#include <mpi.h>

namespace fsai::glottis
{
class FoldProfile;
}

namespace fsai::mesh
{
/// The flow domain of the glottis scene (shared/DESIGN.md §2 "Glottis
/// closure"): the symmetric half-channel 0 ≤ y ≤ H from x = −inlet_length
/// to x = fold_length + outlet_length, less the fold (its surface a spline
/// through the profile points). Facet groups "inlet", "outlet", "axis"
/// (y = 0), "wall" (y = H) and "fold"; cell group "fluid". Size h_gap on
/// the fold, growing linearly to h_far at 3 mm from it.
MeshData glottis_channel(MPI_Comm comm, const glottis::FoldProfile& profile,
                         double h_far, double h_gap);
} // namespace fsai::mesh
