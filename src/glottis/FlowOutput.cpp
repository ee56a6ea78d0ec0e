// Copyright (C) 2026 fsai developers
#include "FlowOutput.h"
#include <fmt/format.h>

fsai::glottis::FlowOutput::FlowOutput(std::string dir,
                                      const GlottisModel& model,
                                      double continue_after)
    : _dir(std::move(dir)), _model(model), _continue_after(continue_after),
      _meshes(model.remeshes())
{
}

void fsai::glottis::FlowOutput::write(double t)
{
  if (_model.flow_fields().empty())
    return;
  if (!_xdmf or _model.remeshes() != _meshes)
  {
    _meshes = _model.remeshes();
    const std::string name = _meshes == 0
                                 ? std::string("flow.xdmf")
                                 : fmt::format("flow_remeshed{}.xdmf", _meshes);
    _xdmf = std::make_unique<io::TimeSeriesWriter>(
        _dir + "/" + name, _model.flow_fields(), _continue_after);
  }
  _xdmf->write(t);
}
