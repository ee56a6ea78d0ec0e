// Copyright (C) 2026 fsai developers
#include "area_function.h"
#include "../common/errors.h"
#include <cmath>
#include <fmt/format.h>
#include <fstream>
#include <sstream>

namespace
{
std::string trim(const std::string& s)
{
  const auto b = s.find_first_not_of(" \t\r");
  const auto e = s.find_last_not_of(" \t\r");
  return b == std::string::npos ? "" : s.substr(b, e - b + 1);
}

/// Parse a whole field as a finite number, or fail
bool to_number(const std::string& field, double& value)
{
  const std::string f = trim(field);
  if (f.empty())
    return false;
  std::size_t pos = 0;
  try
  {
    value = std::stod(f, &pos);
  }
  catch (const std::exception&)
  {
    return false;
  }
  return pos == f.size() and std::isfinite(value);
}
} // namespace

//-----------------------------------------------------------------------------
fsai::mesh::AreaFunction fsai::mesh::read_area_function(const std::string& path)
{
  std::ifstream in(path);
  if (!in)
    throw fsai::InputError("area function: cannot open '" + path + "'");
  AreaFunction af;
  af.source = path;
  std::string line;
  int lineno = 0;
  bool header = false;
  auto fail = [&](const std::string& what)
  {
    throw fsai::InputError(
        fmt::format("area function {}:{}: {}", path, lineno, what));
  };
  while (std::getline(in, line))
  {
    ++lineno;
    line = trim(line);
    if (line.empty() or line[0] == '#')
      continue;
    std::vector<std::string> fields;
    std::stringstream ss(line);
    for (std::string f; std::getline(ss, f, ',');)
      fields.push_back(trim(f));
    if (!header)
    {
      if (fields.size() != 2 or fields[0] != "x_cm" or fields[1] != "area_cm2")
        fail("expected the header 'x_cm,area_cm2', got '" + line + "'");
      header = true;
      continue;
    }
    double x, a;
    if (fields.size() != 2)
      fail(fmt::format("expected 2 columns, got {}", fields.size()));
    if (!to_number(fields[0], x) or !to_number(fields[1], a))
      fail("not a number in '" + line + "'");
    if (a <= 0.0)
      fail(fmt::format("area must be > 0 (got {} cm^2)", a));
    const double prev = af.x_end.empty() ? 0.0 : af.x_end.back() * 100.0;
    if (!(x > prev))
    {
      fail(fmt::format("x must increase from section to section and be > 0 "
                       "(got {} cm after {} cm)",
                       x, prev));
    }
    af.x_end.push_back(x * 1e-2);
    af.area.push_back(a * 1e-4);
  }
  if (!header)
    throw fsai::InputError("area function " + path
                           + ": no header 'x_cm,area_cm2'");
  if (af.area.empty())
    throw fsai::InputError("area function " + path + ": no sections");
  return af;
}
//-----------------------------------------------------------------------------
fsai::mesh::AreaFunction fsai::mesh::uniform_tube(double L, double A)
{
  fsai::require_positive("tube length", L);
  fsai::require_positive("tube area", A);
  return AreaFunction{
      {L}, {A}, fmt::format("uniform tube L = {} m, A = {} m^2", L, A)};
}
//-----------------------------------------------------------------------------
std::string fsai::mesh::vowel_file(const std::string& vowel)
{
  if (vowel != "u" and vowel != "a" and vowel != "i")
  {
    throw fsai::InputError(
        "unknown vowel '" + vowel
        + "' (shipped: u, a, i; or give --area-function FILE.csv)");
  }
  return std::string(FSAI_DATA_DIR) + "/vowel_" + vowel + ".csv";
}
//-----------------------------------------------------------------------------
double fsai::mesh::AreaFunction::area_at(double x, bool smooth) const
{
  const std::size_t n = size();
  if (!smooth)
  {
    for (std::size_t k = 0; k < n; ++k)
      if (x <= x_end[k])
        return area[k];
    return area.back();
  }
  if (x <= x_centre(0))
    return area.front();
  for (std::size_t k = 0; k + 1 < n; ++k)
  {
    const double x0 = x_centre(k), x1 = x_centre(k + 1);
    if (x <= x1)
      return area[k] + (area[k + 1] - area[k]) * (x - x0) / (x1 - x0);
  }
  return area.back();
}
//-----------------------------------------------------------------------------
fsai::mesh::AreaFunction fsai::mesh::resample(const AreaFunction& af,
                                              bool smooth, double dx)
{
  fsai::require_positive("resample: dx", dx);
  AreaFunction out;
  out.source = af.source + (smooth ? " (smooth)" : " (stepped)");
  for (std::size_t k = 0; k < af.size(); ++k)
  {
    const double x0 = af.x_start(k), l = af.x_end[k] - x0;
    const int m = std::max(1, int(std::ceil(l / dx)));
    for (int i = 0; i < m; ++i)
    {
      out.x_end.push_back(x0 + l * (i + 1) / m);
      out.area.push_back(af.area_at(x0 + l * (i + 0.5) / m, smooth));
    }
  }
  return out;
}
//-----------------------------------------------------------------------------
