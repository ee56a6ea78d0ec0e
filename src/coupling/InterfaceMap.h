// Copyright (C) 2026 fsai developers
//
// Data exchange across a fluid–structure interface whose two sides come
// from one gmsh model (mesh::build_parts_with_gmsh), so the fluid's
// interface vertices are vertices of the solid mesh too. Each side may be
// partitioned differently: the owned interface values are gathered on all
// ranks (the interface is a curve in 2D, a surface in 3D: small), and
// every rank fills its local dofs by coordinate matching set up once.
//   solid → fluid: the solid field (P1 or P2) at the fluid's P1 interface
//     vertices (exact: they are solid vertices);
//   fluid → solid: the fluid P1 field at the solid's interface dofs:
//     vertices exactly, P2 edge midpoints as the mean of the edge's two
//     vertices (the P1 trace, exact on straight edges).
// Non-matching meshes (a documented path, not implemented): replace the
// coordinate matching by point evaluation on the other side's boundary
// (io::PointProbes does it for cells) with a consistent (mortar-like) load
// transfer.
#pragma once

#include <dolfinx/fem/Function.h>
#include <memory>
#include <span>
#include <vector>

namespace fsai::coupling
{
class InterfaceMap
{
public:
  /// @param[in] Vf Fluid vector P1 space; `fluid_facets` its interface
  /// @param[in] Vs Solid vector space (P1 or P2); `solid_facets` its
  ///   interface (local facet indices of each mesh; collective)
  /// @param[in] tol Coordinate matching tolerance [m]
  /// @throws std::runtime_error naming a point without a partner
  InterfaceMap(const dolfinx::fem::FunctionSpace& Vf,
               std::span<const std::int32_t> fluid_facets,
               const dolfinx::fem::FunctionSpace& Vs,
               std::span<const std::int32_t> solid_facets, double tol = 1e-9);

  /// Set uf at the fluid interface dofs from us (other dofs untouched)
  void solid_to_fluid(const dolfinx::fem::Function<double>& us,
                      dolfinx::fem::Function<double>& uf) const;
  /// Set us at the solid interface dofs from uf (other dofs untouched)
  void fluid_to_solid(const dolfinx::fem::Function<double>& uf,
                      dolfinx::fem::Function<double>& us) const;

  /// Local interface dofs (blocks) of each side
  const std::vector<std::int32_t>& fluid_dofs() const { return _fdofs; }
  const std::vector<std::int32_t>& solid_dofs() const { return _sdofs; }

private:
  MPI_Comm _comm;
  int _bs;
  std::vector<std::int32_t> _fdofs, _sdofs;   // local interface dof blocks
  std::vector<std::int32_t> _fowned, _sowned; // owned subsets, gather order
  // fluid dof i <- gathered solid value _f_from[i]
  std::vector<std::int64_t> _f_from;
  // solid dof j <- mean of gathered fluid values _s_from[j] (a, b; a = b
  // for a vertex)
  std::vector<std::array<std::int64_t, 2>> _s_from;

  std::vector<double> gather(const dolfinx::fem::Function<double>& u,
                             const std::vector<std::int32_t>& owned) const;
};
} // namespace fsai::coupling
