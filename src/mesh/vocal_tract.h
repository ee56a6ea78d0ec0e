// Copyright (C) 2026 fsai developers
#pragma once

#include "MeshData.h"
#include "area_function.h"
#include <mpi.h>
#include <string>

namespace fsai::common
{
class Parameters;
}

namespace fsai::mesh
{
/// Geometry of a vocal tract built from an area function ([tract] section)
struct VocalTractGeometry
{
  /// "planar": channel of width A(x)/depth (keeps the plane-wave, Webster,
  /// resonances of the tract); "axisym": tube of radius sqrt(A/π) in the
  /// (x, r) half-plane
  std::string model = "planar";
  bool half = false; ///< planar: symmetric half y >= 0 only
  bool smooth
      = true; ///< wall through the section centres (AreaFunction::area_at)
  double depth = 0.018; ///< L_g, depth of the planar model [m]
  bool open = true;     ///< radiation region beyond the lips (else the lips
                        ///< are a boundary "lips")
  double radius = 0.08; ///< radius of the radiation region around the lips [m]
  bool baffle = false;  ///< wall x = L around the mouth (flanged end)
  double wall = 0.005;  ///< wall thickness of the tract outside (unflanged) [m]
  double layer = 0.0;   ///< absorbing-layer thickness beyond `radius` [m]
  double h = 0.005;     ///< mesh size [m]
  double cells_across = 2.0; ///< minimum cells across a section's half-width

  void bind(fsai::common::Parameters& p);
  void validate() const;
};

/// Mesh of a vocal tract: x from the glottis (x = 0) to the lips (x = L),
/// y the (half-)width or radius. Cell groups "tract", "air" (radiation
/// region), "layer"; facet groups "glottis", "wall", "axis" (y = 0 of a
/// half or axisymmetric model), "lips" (closed model) and "radiation"
/// (outer circle). Built on rank 0 with gmsh (OpenCASCADE), distributed.
MeshData vocal_tract(MPI_Comm comm, const AreaFunction& af,
                     const VocalTractGeometry& g);

/// Half-width (planar) or radius (axisymmetric) of a section of area A
double tract_half_width(const VocalTractGeometry& g, double A);
} // namespace fsai::mesh
