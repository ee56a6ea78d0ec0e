// Copyright (C) 2026 fsai developers
#include "csv_columns.h"
#include <common/errors.h>
#include <fstream>
#include <sstream>

std::vector<std::vector<double>>
fsai::io::read_csv_columns(const std::string& path,
                           const std::vector<std::string>& names)
{
  std::ifstream in(path);
  std::string line;
  if (!in or !std::getline(in, line))
    throw InputError("cannot read the CSV file '" + path + "'");
  std::vector<std::string> header;
  {
    std::stringstream ss(line);
    for (std::string f; std::getline(ss, f, ',');)
      header.push_back(f);
  }
  std::vector<std::size_t> col;
  for (const auto& n : names)
  {
    std::size_t k = 0;
    while (k < header.size() and header[k] != n)
      ++k;
    if (k == header.size())
      throw InputError("'" + path + "' has no column '" + n + "'");
    col.push_back(k);
  }
  std::vector<std::vector<double>> out(names.size());
  for (std::size_t row = 2; std::getline(in, line); ++row)
  {
    if (line.empty())
      continue;
    std::vector<std::string> f;
    std::stringstream ss(line);
    for (std::string v; std::getline(ss, v, ',');)
      f.push_back(v);
    for (std::size_t i = 0; i < col.size(); ++i)
    {
      std::size_t used = 0;
      double v = 0;
      try
      {
        v = col[i] < f.size() ? std::stod(f[col[i]], &used) : 0.0;
      }
      catch (const std::exception&)
      {
        used = 0;
      }
      if (col[i] >= f.size() or used != f[col[i]].size())
        throw InputError("'" + path + "' line " + std::to_string(row)
                         + ": column '" + names[i] + "' is not a number");
      out[i].push_back(v);
    }
  }
  return out;
}
