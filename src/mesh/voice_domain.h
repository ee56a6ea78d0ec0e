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
namespace fsai::glottis
{
class FoldProfile;
}

namespace fsai::mesh
{
/// Geometry of the acoustic domain of the voice scene ([voice] section,
/// docs/model.md §4): the fixed flow domain
/// Ω^f_0 of the glottis scene (subglottal duct, the fold at rest, the
/// supraglottal channel) continued by the vocal tract of a vowel to the
/// lips and a half-disc radiation region beyond them, all as the symmetric
/// half y ≥ 0 of a planar model of depth L_g.
struct VoiceDomainGeometry
{
  /// A half-disc radiation region beyond the lips; false: the domain ends
  /// at the lips (set by the scene for the piston load, A11)
  bool radiation_region = true;
  double radius = 0.05;      ///< radiation region around the lips [m]
  double layer = 0.0;        ///< absorbing layer beyond `radius` [m] (0: none)
  double h = 0.004;          ///< acoustic mesh size away from walls [m]
  double h_fold = 0.1e-3;    ///< size on the fold surface [m]
  double growth = 0.3;       ///< size growth with the distance to the fold
  double cells_across = 2.0; ///< minimum cells across a tract half-width
  /// Length of the tract's first part that is the flow domain's channel
  /// (half-height H; set by the scene) [m]: 0 when the tract is the
  /// vowel's from the glottis on
  double channel = 0.0;
  void bind(fsai::common::Parameters& p);
  void validate() const;
};

/// The vocal tract the acoustic domain contains, as one area function from
/// the fold's superior attachment x = T (tract coordinate 0) to the lips:
/// the flow domain's supraglottal channel (half-width H, area 2 H L_g) over
/// its length, then the vowel's area function from that distance on (its
/// first part is replaced by the channel). This is the tract whose 1D
/// transfer-function formants the sound is compared with.
AreaFunction voice_tract(const AreaFunction& vowel,
                         const glottis::FoldProfile& profile);

/// The acoustic domain upstream of the tract, as an area function for the
/// 1D model: the subglottal duct (area 2 H L_g) from the flow inlet, then
/// the glottis at rest, area 2 y(x) L_g with y the fold surface's lowest
/// point at x (sections of 0.05 mm), up to the fold's superior attachment
/// x = T where the tract of voice_tract begins. The acoustic domain is
/// fixed, so its glottis stays open at the rest gap.
AreaFunction voice_subglottal(const glottis::FoldProfile& profile);

/// Mesh of the acoustic domain (tract from voice_tract). x as in
/// glottis_channel (fold from 0 to T, inlet at −inlet_length), lips at
/// x = T + tract length. Facet groups "inlet" (subglottal end), "axis",
/// "wall" (channel and tract walls, the step between them and the baffle at
/// the lips plane), "fold", "radiation" (outer arc) or, without the
/// radiation region, "lips" (the opening); cell groups "air" and "layer". Size
/// h_fold on the fold growing with the distance, at most h, and at most
/// half-width / cells_across inside the tract.
MeshData voice_domain(MPI_Comm comm, const glottis::FoldProfile& profile,
                      const AreaFunction& tract, const VoiceDomainGeometry& g);
} // namespace fsai::mesh
