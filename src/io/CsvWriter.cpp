// Copyright (C) 2026 fsai developers
#include "CsvWriter.h"
#include "output_dir.h"
#include <cstdio>
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
