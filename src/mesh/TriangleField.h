// Copyright (C) 2026 fsai developers
//
// P1 fields of a 2D triangulation, evaluated at any point: the transfer of
// a flow state from one mesh to another (remeshing, docs/model.md
// E13a). The triangles of all ranks are gathered on every rank (a
// 2D flow mesh of 10⁴–10⁵ cells is a few MB), so each rank evaluates its
// own points with no further communication, whatever the partitions of
// the two meshes.
#pragma once
#include <array>
#include <dolfinx/fem/FunctionSpace.h>
#include <memory>
#include <mpi.h>
#include <span>
#include <vector>

namespace fsai::mesh
{
class TriangleField
{
public:
  /// @param[in] xy 6 coordinates per triangle (its 3 vertices)
  /// @param[in] values `ncomp` values per vertex, 3 vertices per triangle
  TriangleField(std::vector<double> xy, std::vector<double> values, int ncomp);

  /// The owned cells of a P1 space on a triangle mesh in its current
  /// geometry, gathered from all ranks (collective), with the values of the
  /// given fields (each a local array in V's layout, V's block size bs
  /// entries per dof block): bs · fields.size() components, field by field
  static TriangleField
  gather(MPI_Comm comm, const dolfinx::fem::FunctionSpace& V,
         const std::vector<std::span<const double>>& fields);

  int components() const { return _ncomp; }
  /// The fields at x, linear in the triangle that contains it; a point in
  /// no triangle (the two meshes' discrete boundaries of a curved wall
  /// differ by their chords) takes the value at the nearest point of the
  /// nearest triangle
  std::vector<double> operator()(const std::array<double, 2>& x) const;
  /// Distance of x from the triangulation (0 inside)
  double distance(const std::array<double, 2>& x) const;

private:
  /// Triangle t's barycentric coordinates of x, clamped to the triangle,
  /// and the distance of x from it
  std::pair<std::array<double, 3>, double>
  nearest(std::size_t t, const std::array<double, 2>& x) const;
  /// The nearest triangle to x and its clamped barycentric coordinates
  std::pair<std::size_t, std::array<double, 3>>
  locate(const std::array<double, 2>& x) const;
  std::vector<double> _xy, _values;
  int _ncomp;
  // Bucket grid over the bounding box: triangles by the buckets their
  // bounding boxes overlap
  double _x0, _y0, _hx, _hy;
  int _nx, _ny;
  std::vector<std::int32_t> _offsets, _triangles;
};
} // namespace fsai::mesh
