// Copyright (C) 2026 fsai developers
#pragma once

#include <fstream>
#include <mpi.h>
#include <string>
#include <vector>

namespace fsai::io
{
/// CSV time series (probes, forces, convergence tables) written by rank 0.
/// Every row is flushed, so a run stopped at any point leaves a readable
/// file. Values are written with 17 significant digits (round-trip exact).
class CsvWriter
{
public:
  /// @param[in] comm Only rank 0 of `comm` writes; row() may be called on
  ///   all ranks (values from rank 0 are used)
  /// @param[in] path File name
  /// @param[in] columns Header names (with units, e.g. "t_s")
  CsvWriter(MPI_Comm comm, const std::string& path,
            std::vector<std::string> columns);

  /// Continue the series `path` of an interrupted run: its header must
  /// equal `columns` and it must hold at least `keep_rows` rows; the rows
  /// after those (written after the checkpoint) are dropped and new rows
  /// follow, so the series has no gap and no duplicate. The kept rows are
  /// available on every rank from kept_rows(). Throws InputError (on every
  /// rank) if the file does not fit.
  CsvWriter(MPI_Comm comm, const std::string& path,
            std::vector<std::string> columns, std::size_t keep_rows);
  const std::vector<std::vector<double>>& kept_rows() const { return _kept; }

  /// Append one row; its size must match the header
  void row(const std::vector<double>& values);

private:
  std::vector<std::string> _columns;
  std::ofstream _out;
  bool _writer;
  std::vector<std::vector<double>> _kept;
};
} // namespace fsai::io
