// Copyright (C) 2026 fsai developers
//
// The elastic fold's surface motion as a time series, for the analysis of
// its shapes (bench/glottis_pod.py: POD energy shares, DMD frequencies and
// growth rates, the shapes against the in-vacuo modes; docs/glottis.md "Do
// two or three shapes carry the motion?"). Two files in the run's folder:
//   - modes_surface.csv: the fold's ordered surface points (inferior →
//     superior) with their reference position and the first in-vacuo modes'
//     displacement there (each mode scaled to max |u| = 1 over the fold),
//     one row per point: s_m, X_m, Y_m, f<k>_ux, f<k>_uy per mode;
//   - fold_surface.csv: every N steps, t_s and the displacement of every
//     ordered point (ux0, uy0, ux1, …).
// After a restart the series is cut back to the checkpoint's step, as
// series.csv is.
#pragma once
#include "ElasticFold.h"
#include <io/CsvWriter.h>
#include <memory>
#include <string>

namespace fsai::glottis
{
class FoldSurfaceRecord
{
public:
  /// @param[in] every Record every `every` steps (steps k = every, 2 every…)
  /// @param[in] modes In-vacuo modes written to modes_surface.csv
  /// @param[in] first_step The step the run starts after (a restart's)
  FoldSurfaceRecord(ElasticFold& fold, const std::string& folder, int every,
                    int modes, long first_step);
  /// After step k at time t (collective)
  void step(long k, double t);

private:
  ElasticFold& _fold;
  int _every;
  std::unique_ptr<io::CsvWriter> _csv;
};
} // namespace fsai::glottis
