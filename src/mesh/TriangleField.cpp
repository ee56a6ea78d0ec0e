// Copyright (C) 2026 fsai developers
#include "TriangleField.h"
#include <algorithm>
#include <cmath>
#include <common/mpi_gather.h>
#include <dolfinx/common/IndexMap.h>
#include <dolfinx/fem/DofMap.h>
#include <dolfinx/mesh/Mesh.h>
#include <limits>
#include <stdexcept>

fsai::mesh::TriangleField::TriangleField(std::vector<double> xy,
                                         std::vector<double> values, int ncomp)
    : _xy(std::move(xy)), _values(std::move(values)), _ncomp(ncomp)
{
  const std::size_t n = _xy.size() / 6;
  if (n == 0 or _xy.size() != 6 * n or _values.size() != 3 * n * ncomp)
    throw std::invalid_argument("TriangleField: sizes of xy and values");
  double x1 = -1e300, y1 = -1e300;
  _x0 = _y0 = 1e300;
  for (std::size_t i = 0; i < _xy.size(); i += 2)
  {
    _x0 = std::min(_x0, _xy[i]), x1 = std::max(x1, _xy[i]);
    _y0 = std::min(_y0, _xy[i + 1]), y1 = std::max(y1, _xy[i + 1]);
  }
  // About 2 buckets per triangle, square in the mean
  const double w = std::max(x1 - _x0, 1e-300), h = std::max(y1 - _y0, 1e-300);
  const double side = std::sqrt(w * h / (2.0 * double(n)));
  _nx = std::clamp(int(std::ceil(w / side)), 1, 4096);
  _ny = std::clamp(int(std::ceil(h / side)), 1, 4096);
  _hx = w / _nx, _hy = h / _ny;
  auto range = [&](std::size_t t)
  {
    double a = 1e300, b = -1e300, c = 1e300, d = -1e300;
    for (int k = 0; k < 3; ++k)
    {
      a = std::min(a, _xy[6 * t + 2 * k]), b = std::max(b, _xy[6 * t + 2 * k]);
      c = std::min(c, _xy[6 * t + 2 * k + 1]);
      d = std::max(d, _xy[6 * t + 2 * k + 1]);
    }
    auto ix = [&](double x)
    { return std::clamp(int((x - _x0) / _hx), 0, _nx - 1); };
    auto iy = [&](double y)
    { return std::clamp(int((y - _y0) / _hy), 0, _ny - 1); };
    return std::array<int, 4>{ix(a), ix(b), iy(c), iy(d)};
  };
  std::vector<std::int32_t> count(std::size_t(_nx) * _ny + 1, 0);
  for (std::size_t t = 0; t < n; ++t)
  {
    const auto r = range(t);
    for (int j = r[2]; j <= r[3]; ++j)
      for (int i = r[0]; i <= r[1]; ++i)
        ++count[std::size_t(j) * _nx + i + 1];
  }
  _offsets.assign(count.size(), 0);
  for (std::size_t b = 1; b < count.size(); ++b)
    _offsets[b] = _offsets[b - 1] + count[b];
  _triangles.resize(_offsets.back());
  std::vector<std::int32_t> fill(_offsets.begin(), _offsets.end() - 1);
  for (std::size_t t = 0; t < n; ++t)
  {
    const auto r = range(t);
    for (int j = r[2]; j <= r[3]; ++j)
      for (int i = r[0]; i <= r[1]; ++i)
        _triangles[fill[std::size_t(j) * _nx + i]++] = std::int32_t(t);
  }
}
//-----------------------------------------------------------------------------
fsai::mesh::TriangleField fsai::mesh::TriangleField::gather(
    MPI_Comm comm, const dolfinx::fem::FunctionSpace& V,
    const std::vector<std::span<const double>>& fields)
{
  const auto& mesh = *V.mesh();
  if (mesh.topology().dim() != 2
      or mesh.topology().cell_type() != dolfinx::mesh::CellType::triangle)
    throw std::invalid_argument("TriangleField: a triangle mesh is needed");
  const auto dofmap = V.dofmap();
  const int bs = dofmap->index_map_bs();
  const std::vector<double> X = V.tabulate_dof_coordinates(false);
  const std::int32_t ncells = mesh.topology().index_map(2)->size_local();
  std::vector<double> xy, values;
  xy.reserve(6 * ncells);
  values.reserve(3 * ncells * bs * fields.size());
  for (std::int32_t c = 0; c < ncells; ++c)
  {
    const auto dofs = dofmap->cell_dofs(c);
    if (dofs.size() != 3)
      throw std::invalid_argument("TriangleField: a P1 space is needed");
    for (auto d : dofs)
    {
      xy.insert(xy.end(), {X[3 * d], X[3 * d + 1]});
      for (const auto& f : fields)
        for (int k = 0; k < bs; ++k)
          values.push_back(f[bs * d + k]);
    }
  }
  return TriangleField(common::allgather(comm, xy),
                       common::allgather(comm, values),
                       bs * int(fields.size()));
}
//-----------------------------------------------------------------------------
std::pair<std::array<double, 3>, double>
fsai::mesh::TriangleField::nearest(std::size_t t,
                                   const std::array<double, 2>& x) const
{
  const double* p = &_xy[6 * t];
  const double ax = p[0], ay = p[1];
  const double e1x = p[2] - ax, e1y = p[3] - ay, e2x = p[4] - ax,
               e2y = p[5] - ay;
  const double det = e1x * e2y - e1y * e2x;
  const double rx = x[0] - ax, ry = x[1] - ay;
  const double l1 = (rx * e2y - ry * e2x) / det,
               l2 = (e1x * ry - e1y * rx) / det;
  if (l1 >= 0 and l2 >= 0 and l1 + l2 <= 1)
    return {{1 - l1 - l2, l1, l2}, 0.0};
  // Outside: the nearest point on one of the three edges
  std::array<double, 3> best{};
  double dmin = std::numeric_limits<double>::infinity();
  for (int k = 0; k < 3; ++k)
  {
    const int k1 = (k + 1) % 3;
    const double px = p[2 * k], py = p[2 * k + 1];
    const double qx = p[2 * k1] - px, qy = p[2 * k1 + 1] - py;
    const double s = std::clamp(
        ((x[0] - px) * qx + (x[1] - py) * qy) / (qx * qx + qy * qy), 0.0, 1.0);
    const double d = std::hypot(x[0] - px - s * qx, x[1] - py - s * qy);
    if (d < dmin)
    {
      dmin = d;
      best = {0, 0, 0};
      best[k] = 1 - s;
      best[k1] = s;
    }
  }
  return {best, dmin};
}
//-----------------------------------------------------------------------------
std::pair<std::size_t, std::array<double, 3>>
fsai::mesh::TriangleField::locate(const std::array<double, 2>& x) const
{
  const int i0 = std::clamp(int(std::floor((x[0] - _x0) / _hx)), 0, _nx - 1);
  const int j0 = std::clamp(int(std::floor((x[1] - _y0) / _hy)), 0, _ny - 1);
  std::size_t best_t = 0;
  std::array<double, 3> best_l{};
  double best_d = std::numeric_limits<double>::infinity();
  // Rings of buckets around x's; once a triangle is found, one more ring
  // (a nearer triangle's box may start in the next ring)
  int last_ring = std::max(_nx, _ny);
  for (int r = 0; r <= last_ring; ++r)
  {
    for (int j = j0 - r; j <= j0 + r; ++j)
      for (int i = i0 - r; i <= i0 + r; ++i)
      {
        if (std::max(std::abs(i - i0), std::abs(j - j0)) != r or i < 0 or j < 0
            or i >= _nx or j >= _ny)
          continue;
        const std::size_t b = std::size_t(j) * _nx + i;
        for (auto k = _offsets[b]; k < _offsets[b + 1]; ++k)
        {
          const auto [l, d] = nearest(_triangles[k], x);
          if (d < best_d)
            best_d = d, best_t = _triangles[k], best_l = l;
          if (d == 0)
            return {best_t, best_l};
        }
      }
    if (best_d < std::numeric_limits<double>::infinity())
      last_ring = std::min(last_ring, r + 1);
  }
  return {best_t, best_l};
}
//-----------------------------------------------------------------------------
std::vector<double>
fsai::mesh::TriangleField::operator()(const std::array<double, 2>& x) const
{
  const auto [t, l] = locate(x);
  std::vector<double> out(_ncomp, 0.0);
  for (int v = 0; v < 3; ++v)
    for (int c = 0; c < _ncomp; ++c)
      out[c] += l[v] * _values[(3 * t + v) * _ncomp + c];
  return out;
}
//-----------------------------------------------------------------------------
double fsai::mesh::TriangleField::distance(const std::array<double, 2>& x) const
{
  const auto [t, l] = locate(x);
  double px = 0, py = 0;
  for (int v = 0; v < 3; ++v)
    px += l[v] * _xy[6 * t + 2 * v], py += l[v] * _xy[6 * t + 2 * v + 1];
  return std::hypot(x[0] - px, x[1] - py);
}
