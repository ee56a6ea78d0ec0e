// Copyright (C) 2026 fsai developers
//
// The flow fields of a glottis model over a run, in XDMF: flow.xdmf, and
// after each remeshing (docs/model.md E13a) a new file flow_remeshedN.xdmf
// on the new mesh, opened at its first write. Shared by fsai_glottis and
// fsai_demo.
#pragma once
#include "GlottisModel.h"
#include <io/TimeSeriesWriter.h>
#include <memory>
#include <string>

namespace fsai::glottis
{
class FlowOutput
{
public:
  /// @param[in] dir Output folder
  /// @param[in] model Its flow_fields() (none: nothing is written)
  /// @param[in] continue_after Restart time (TimeSeriesWriter)
  FlowOutput(std::string dir, const GlottisModel& model, double continue_after);
  /// Append the flow at time t (on the model's current mesh)
  void write(double t);

private:
  std::string _dir;
  const GlottisModel& _model;
  double _continue_after;
  int _meshes;
  std::unique_ptr<io::TimeSeriesWriter> _xdmf;
};
} // namespace fsai::glottis
