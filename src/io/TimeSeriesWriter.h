// Copyright (C) 2026 fsai developers
#pragma once

#include <dolfinx/fem/Function.h>
#include <dolfinx/io/XDMFFile.h>
#include <memory>
#include <string>
#include <vector>

namespace fsai::io
{
/// XDMF/HDF5 time series of one group of fields on one mesh, for ParaView.
/// The mesh is written once (reference configuration); each write() adds
/// the fields at time t. Fields are evaluated at the mesh vertices (P2 is
/// written at vertices; DG0 as cell data).
///
/// NOTE(DOLFINx 0.5.2): XDMFFile writes the geometry once, so a moving (ALE)
/// mesh is shown by also writing its displacement field and applying
/// ParaView's "Warp By Vector" to it.
class TimeSeriesWriter
{
public:
  using Field = std::shared_ptr<const dolfinx::fem::Function<double>>;

  /// @param[in] path File name (.xdmf; the .h5 goes beside it)
  /// @param[in] fields Fields written at every step, named by their `name`
  TimeSeriesWriter(const std::string& path, std::vector<Field> fields);

  /// Append all fields at time t
  void write(double t);

  /// Number of steps written
  int steps() const { return _steps; }

private:
  std::vector<Field> _fields;
  std::unique_ptr<dolfinx::io::XDMFFile> _file;
  int _steps = 0;
};
} // namespace fsai::io
