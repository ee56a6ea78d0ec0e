// Copyright (C) 2026 fsai developers
//
// ALE mesh motion driven by the interface (docs/model.md §3,
// E13): the fluid-mesh displacement d is the harmonic or pseudo-elastic
// extension of the interface displacement (forms/ale.py), solved on the
// reference mesh with cell-size stiffening, and the mesh is moved to
// x = X + d (always from the reference X: no drift over many periods).
// The mesh velocity is the BDF derivative of d that the flow solver's time
// discretisation needs for geometric conservation (E19):
//   w^{n+1} = (3 d^{n+1} − 4 d^n + d^{n−1}) / (2Δt)   (BDF1 at the start)
// Every move checks the mesh quality (minimum scaled Jacobian) and throws
// MeshInvertedError, naming time, place and quality, when a cell inverts.
#pragma once

#include <array>
#include <dolfinx/fem/DirichletBC.h>
#include <dolfinx/fem/Form.h>
#include <dolfinx/fem/Function.h>
#include <dolfinx/la/petsc.h>
#include <io/run_state.h>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <vector>

namespace fsai::common
{
class Parameters;
}

namespace fsai::ale
{
/// Mesh-motion parameters ([ale] section)
struct MeshMotionParameters
{
  /// "harmonic" (vector Laplace) or "elastic" (pseudo-elastic medium)
  std::string method = "elastic";
  /// Cell stiffening k of the extension: "none"; "size", k = (V_max/V_K)^χ
  /// from the reference cell volumes (small cells move more rigidly);
  /// "jacobian", k = (V_max/V_K)^χ · J_K^(−χ) with J_K = det(I + ∇d) the
  /// cell's volume ratio in the current motion (cells being squeezed
  /// stiffen, so the compression spreads over the gap), found by fixed-point
  /// iterations from the previous move's d
  std::string stiffening = "none";
  double chi = 0.5;   ///< stiffening exponent χ
  int iterations = 6; ///< "jacobian": fixed-point iterations per move
  /// λ_m/μ_m of the pseudo-elastic medium (ν_m = λ/(2(λ+μ)) in 3D)
  double lambda = 1.0;
  /// Smallest scaled Jacobian accepted before a move is an error
  /// (equilateral = 1, degenerate = 0, inverted < 0)
  double min_quality = 0.0;

  void bind(fsai::common::Parameters& p);
  void validate() const;
};

/// Boundary facets (local indices) by role. Facets in none of the lists
/// are free (natural condition), which is rarely wanted: list them all.
struct MeshMotionBoundaries
{
  std::vector<std::int32_t> interface; ///< d = the interface displacement
  std::vector<std::int32_t> fixed;     ///< d = 0
  /// d_c = 0 for component c only (slip along a straight axis-aligned line
  /// or plane: the symmetry axis y = 0 is {1, facets})
  std::vector<std::pair<int, std::vector<std::int32_t>>> slip;
  /// Interior (or boundary) dof blocks whose displacement the caller
  /// prescribes through interface_displacement() as well (an algebraic
  /// motion of a region, e.g. a closing gap); local indices with ghosts,
  /// chosen consistently on every rank
  std::vector<std::int32_t> prescribed;
};

/// A cell inverted or fell below the accepted quality
class MeshInvertedError : public std::runtime_error
{
public:
  explicit MeshInvertedError(const std::string& what) : std::runtime_error(what)
  {
  }
};

/// Mesh quality of the current configuration
struct MeshQuality
{
  double min_scaled_jacobian;    ///< global minimum over cells
  std::array<double, 3> where{}; ///< midpoint of the worst cell
};

/// Minimum scaled Jacobian of a simplex mesh (collective): per cell the
/// smallest corner value det(e_1..e_d)/(|e_1|..|e_d|), normalised so that
/// the equilateral simplex gives 1; negative for an inverted cell, which is
/// detected by the sign of the Jacobian relative to the reference mesh
MeshQuality mesh_quality(const dolfinx::mesh::Mesh& mesh,
                         std::span<const double> reference_x);

class MeshMotion
{
public:
  /// @param[in] mesh The fluid mesh, moved in place; its coordinates at
  ///   construction are the reference X
  /// @param[in] V P1 vector space on `mesh` (the flow velocity space)
  MeshMotion(std::shared_ptr<dolfinx::mesh::Mesh> mesh,
             std::shared_ptr<const dolfinx::fem::FunctionSpace> V,
             const MeshMotionBoundaries& bnd, const MeshMotionParameters& p);

  /// Interface displacement: set its values at the interface dofs (values
  /// elsewhere are ignored) before move()
  dolfinx::fem::Function<double>& interface_displacement()
  {
    return *_d_interface;
  }

  /// Extend the interface displacement, move the mesh to X + d and check
  /// its quality (throws MeshInvertedError with `t` in the message). Can be
  /// called repeatedly within one time step (coupling iterations).
  MeshQuality move(double t);

  /// Whether the extension is a fixed linear map of the interface values
  /// (no Jacobian stiffening, which depends on the current motion)
  bool linear() const { return _par.stiffening != "jacobian"; }
  /// The extension of the current interface values (all local entries of
  /// a displacement, ghosts included), without moving the mesh. For a
  /// linear() motion a caller whose interface values are a combination of
  /// a few fixed fields can extend each once and move by their combination
  /// (move_to), which gives move()'s mesh to round-off without its solve
  std::vector<double> extension();
  /// Move the mesh to X + d for a given d (local entries, ghosts included)
  /// and check its quality as move() does
  MeshQuality move_to(std::span<const double> d, double t);

  /// Mesh velocity of the current d for the step of length dt after one of
  /// length dt_n (variable-step BDF2, the flow's weights; BDF1 for the
  /// first step after construction or reset)
  void velocity(dolfinx::fem::Function<double>& w, double dt,
                double dt_n) const;

  /// Accept the step: d becomes the history for the next velocity()
  void advance();
  /// Back to the last accepted d and its mesh (after a failed step)
  void rewind();

  /// The current mesh is the reference of a motion already under way
  /// (remeshing): d^n = 0 and d^{n−1} = x^{n−1} − x^n, the previous
  /// positions of the nodes relative to the current ones (local entries,
  /// ghosts included), so that the next velocity() is BDF2 as before
  void continue_from(std::span<const double> d_nn);
  /// The accepted d^n and d^{n−1} (local entries, ghosts included)
  std::array<std::span<const double>, 2> history() const
  {
    return {std::span<const double>(_d_n), std::span<const double>(_d_nn)};
  }

  /// The accepted motion (d, its history, the relaxed Jacobians) into a
  /// checkpoint (by mesh node and cell, io/field_state.h) and back from all
  /// the checkpoint's ranks; load() also moves the mesh to X + d
  void save(io::RankState& state, const std::string& prefix) const;
  void load(const std::vector<io::RankState>& ranks, const std::string& prefix);

  /// The mesh displacement d (for output: Warp By Vector in ParaView)
  std::shared_ptr<const dolfinx::fem::Function<double>> displacement() const
  {
    return _d;
  }

  /// Cell stiffening coefficient k (DG0), for output and tests
  std::shared_ptr<const dolfinx::fem::Function<double>> stiffening() const
  {
    return _k;
  }

private:
  /// d = the extension of the current interface values (the mesh is left
  /// at the reference X)
  void extend(dolfinx::fem::Function<double>& d);
  MeshQuality place_and_check(double t);
  std::shared_ptr<dolfinx::mesh::Mesh> _mesh;
  std::shared_ptr<const dolfinx::fem::FunctionSpace> _V;
  MeshMotionParameters _par;
  std::vector<double> _X;              // reference geometry coordinates
  std::vector<std::int32_t> _node_dof; // geometry node -> P1 dof (block)
  std::shared_ptr<dolfinx::fem::Function<double>> _d, _d_interface, _k;
  std::vector<double> _d_n, _d_nn;    // accepted history
  std::vector<double> _det0, _k_size; // reference cell Jacobians, size factor
  std::vector<double> _J; // relaxed cell volume ratios (jacobian stiffening)
  void assemble();   // k from the stiffening model, then A (reference mesh)
  void place_mesh(); // x = X + d
  int _history = 0;  // accepted steps available (0, 1, 2)
  std::shared_ptr<dolfinx::fem::Form<double>> _a;
  std::vector<std::shared_ptr<const dolfinx::fem::DirichletBC<double>>> _bcs;
  dolfinx::la::petsc::Matrix _A;
  dolfinx::la::petsc::KrylovSolver _solver;
};
} // namespace fsai::ale
