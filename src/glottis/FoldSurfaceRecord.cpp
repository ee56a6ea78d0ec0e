// Copyright (C) 2026 fsai developers
#include "FoldSurfaceRecord.h"
#include <fmt/format.h>
#include <structure/modal.h>

fsai::glottis::FoldSurfaceRecord::FoldSurfaceRecord(ElasticFold& fold,
                                                    const std::string& folder,
                                                    int every, int modes,
                                                    long first_step)
    : _fold(fold), _every(every)
{
  const auto& X = fold.surface_reference();
  const auto md = structure::modal_analysis(fold.solver(), modes);
  std::vector<std::string> columns = {"s_m", "X_m", "Y_m"};
  std::vector<std::vector<std::array<double, 2>>> shapes;
  for (const auto& m : md)
  {
    columns.push_back(fmt::format("f{:.2f}Hz_ux", m.frequency_hz));
    columns.push_back(fmt::format("f{:.2f}Hz_uy", m.frequency_hz));
    shapes.push_back(fold.surface_values(*m.shape));
  }
  {
    io::CsvWriter points(fold.comm(), folder + "/modes_surface.csv", columns);
    for (std::size_t k = 0; k < X.size(); ++k)
    {
      std::vector<double> row
          = {fold.profile().arc_length(X[k]), X[k][0], X[k][1]};
      for (const auto& u : shapes)
        row.insert(row.end(), {u[k][0], u[k][1]});
      points.row(row);
    }
  }
  columns = {"t_s"};
  for (std::size_t k = 0; k < X.size(); ++k)
  {
    columns.push_back(fmt::format("ux{}", k));
    columns.push_back(fmt::format("uy{}", k));
  }
  const std::string path = folder + "/fold_surface.csv";
  _csv = first_step > 0
             ? std::make_unique<io::CsvWriter>(fold.comm(), path, columns,
                                               std::size_t(first_step / every))
             : std::make_unique<io::CsvWriter>(fold.comm(), path, columns);
}
//-----------------------------------------------------------------------------
void fsai::glottis::FoldSurfaceRecord::step(long k, double t)
{
  if (k % _every != 0)
    return;
  const auto u = _fold.surface_values(*_fold.solver().displacement());
  std::vector<double> row = {t};
  row.reserve(1 + 2 * u.size());
  for (const auto& v : u)
    row.insert(row.end(), {v[0], v[1]});
  _csv->row(row);
}
