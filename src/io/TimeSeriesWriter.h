// Copyright (C) 2026 fsai developers
#pragma once

#include <dolfinx/fem/Function.h>
#include <limits>
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
/// The files are closed after every write(), so a run killed at any moment
/// leaves a readable series (the HDF5 file is only consistent on disk when
/// closed). A restarted run continues the series of the killed one: the
/// steps written after the checkpoint are removed first, so the series has
/// no duplicate time.
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
  /// @param[in] continue_after Restart: keep the existing series' steps up
  ///   to this time and append after them (NaN, or no file at `path`: a
  ///   new series)
  TimeSeriesWriter(const std::string& path, std::vector<Field> fields,
                   double continue_after
                   = std::numeric_limits<double>::quiet_NaN());

  /// Append all fields at time t
  void write(double t);

  /// Number of steps written by this writer
  int steps() const { return _steps; }

private:
  std::string _path;
  std::vector<Field> _fields;
  int _steps = 0;
};

/// Remove the steps after time `t` from the XDMF series `path` (its XML
/// entries and their HDF5 datasets); rank 0 does the work. Returns the
/// number of steps removed (on every rank); InputError if the file cannot
/// be read.
int truncate_time_series(MPI_Comm comm, const std::string& path, double t);
} // namespace fsai::io
