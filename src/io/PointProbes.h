// Copyright (C) 2026 fsai developers
#pragma once

#include <array>
#include <dolfinx/fem/Function.h>
#include <memory>
#include <vector>

namespace fsai::io
{
/// Values of scalar or vector fields at fixed points (microphones, pressure
/// taps, point A of a benchmark), on any number of ranks. Each point is
/// located once (bounding-box tree + exact collision) and owned by the
/// lowest rank whose cells contain it; values() evaluates there and shares
/// the result, so every rank gets the same numbers.
class PointProbes
{
public:
  /// @param[in] mesh The mesh of the fields to be probed
  /// @param[in] points Points (x, y, z); z is ignored in 2D
  /// @throws InputError naming the first point outside the mesh
  PointProbes(std::shared_ptr<const dolfinx::mesh::Mesh> mesh,
              std::vector<std::array<double, 3>> points);

  /// Values of `u` at the points (collective): value_size numbers per
  /// point, point after point
  std::vector<double> values(const dolfinx::fem::Function<double>& u) const;

  /// Number of points
  std::size_t size() const { return _points.size(); }

private:
  std::shared_ptr<const dolfinx::mesh::Mesh> _mesh;
  std::vector<std::array<double, 3>> _points;
  // Points owned by this rank: index into _points and the local cell
  std::vector<std::size_t> _owned;
  std::vector<std::int32_t> _cells;
};
} // namespace fsai::io
