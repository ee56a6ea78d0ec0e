// Copyright (C) 2026 fsai developers
#include "TimeSeriesWriter.h"
#include "../common/timer.h"
#include "output_dir.h"
#include <stdexcept>

//-----------------------------------------------------------------------------
fsai::io::TimeSeriesWriter::TimeSeriesWriter(const std::string& path,
                                             std::vector<Field> fields)
    : _fields(std::move(fields))
{
  if (_fields.empty())
    throw std::runtime_error("TimeSeriesWriter '" + path + "': no fields");
  auto mesh = _fields.front()->function_space()->mesh();
  for (const Field& f : _fields)
  {
    if (f->function_space()->mesh() != mesh)
      throw std::runtime_error("TimeSeriesWriter '" + path
                               + "': fields live on different meshes");
  }
  ensure_parent_dir(path);
  _file = std::make_unique<dolfinx::io::XDMFFile>(mesh->comm(), path, "w");
  _file->write_mesh(*mesh);
}
//-----------------------------------------------------------------------------
void fsai::io::TimeSeriesWriter::write(double t)
{
  common::ScopedTimer timer("io: xdmf");
  for (const Field& f : _fields)
    _file->write_function(*f, t);
  ++_steps;
}
//-----------------------------------------------------------------------------
