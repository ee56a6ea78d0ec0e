// Copyright (C) 2026 fsai developers
#include "CsvWriter.h"
#include "../common/errors.h"
#include "output_dir.h"
#include <cstdio>
#include <sstream>
#include <stdexcept>

//-----------------------------------------------------------------------------
fsai::io::CsvWriter::CsvWriter(MPI_Comm comm, const std::string& path,
                               std::vector<std::string> columns)
    : _columns(std::move(columns))
{
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  _writer = rank == 0;
  if (_writer)
  {
    ensure_parent_dir(path);
    _out.open(path);
    if (!_out)
      throw std::runtime_error("cannot write '" + path + "'");
    for (std::size_t i = 0; i < _columns.size(); ++i)
      _out << (i ? "," : "") << _columns[i];
    _out << '\n' << std::flush;
    if (!_out)
      throw std::runtime_error("cannot write '" + path + "' (disk full?)");
  }
}
//-----------------------------------------------------------------------------
void fsai::io::CsvWriter::row(const std::vector<double>& values)
{
  if (values.size() != _columns.size())
  {
    throw std::logic_error("CsvWriter: row has " + std::to_string(values.size())
                           + " values, header has "
                           + std::to_string(_columns.size()));
  }
  if (!_writer)
    return;
  char buf[32];
  for (std::size_t i = 0; i < values.size(); ++i)
  {
    std::snprintf(buf, sizeof(buf), "%.17g", values[i]);
    _out << (i ? "," : "") << buf;
  }
  _out << '\n' << std::flush;
  if (!_out)
    throw std::runtime_error("CsvWriter: write failed (disk full?)");
}
//-----------------------------------------------------------------------------
fsai::io::CsvWriter::CsvWriter(MPI_Comm comm, const std::string& path,
                               std::vector<std::string> columns,
                               std::size_t keep_rows)
    : _columns(std::move(columns))
{
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  _writer = rank == 0;
  // Rank 0 reads and checks; the verdict and the kept rows go to all ranks
  std::string error;
  std::vector<double> flat;
  if (_writer)
  {
    std::ifstream in(path);
    std::string header, line;
    std::string expected;
    for (std::size_t i = 0; i < _columns.size(); ++i)
      expected += (i ? "," : "") + _columns[i];
    if (!in or !std::getline(in, header))
      error = "cannot read '" + path + "' to continue it";
    else if (header != expected)
      error = "'" + path + "' has other columns than this run writes";
    while (error.empty() and flat.size() < keep_rows * _columns.size()
           and std::getline(in, line))
    {
      std::stringstream ss(line);
      std::string v;
      std::size_t n = 0;
      for (; std::getline(ss, v, ','); ++n)
      {
        try
        {
          flat.push_back(std::stod(v));
        }
        catch (const std::exception&)
        {
          error = "'" + path + "': non-numeric value '" + v + "'";
          break;
        }
      }
      if (error.empty() and n != _columns.size())
        error = "'" + path + "': a row with " + std::to_string(n) + " values";
    }
    if (error.empty() and flat.size() < keep_rows * _columns.size())
    {
      error = "'" + path + "' holds "
              + std::to_string(flat.size() / _columns.size())
              + " rows, the checkpoint needs " + std::to_string(keep_rows);
    }
  }
  int failed = error.empty() ? 0 : 1;
  MPI_Bcast(&failed, 1, MPI_INT, 0, comm);
  if (failed)
  {
    int n = int(error.size());
    MPI_Bcast(&n, 1, MPI_INT, 0, comm);
    error.resize(n);
    MPI_Bcast(error.data(), n, MPI_CHAR, 0, comm);
    throw InputError("restart: " + error);
  }
  flat.resize(keep_rows * _columns.size());
  MPI_Bcast(flat.data(), int(flat.size()), MPI_DOUBLE, 0, comm);
  for (std::size_t r = 0; r < keep_rows; ++r)
  {
    _kept.emplace_back(flat.begin() + r * _columns.size(),
                       flat.begin() + (r + 1) * _columns.size());
  }
  if (_writer)
  {
    // Rewrite header and kept rows (exactly as row() formats them), then
    // append
    _out.open(path, std::ios::trunc);
    if (!_out)
      throw std::runtime_error("cannot write '" + path + "'");
    for (std::size_t i = 0; i < _columns.size(); ++i)
      _out << (i ? "," : "") << _columns[i];
    _out << '\n';
  }
  for (const auto& r : _kept)
    row(r);
}
//-----------------------------------------------------------------------------
