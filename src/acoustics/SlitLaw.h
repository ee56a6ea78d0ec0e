// Copyright (C) 2026 fsai developers
//
// A slit in a fixed acoustic domain (docs/model.md A5): in its cells the
// air obeys the momentum law of a slit narrower than the mesh's,
//   ρ' ∂v/∂t + r' v = −∇p'    (ρ' = ρ0 × inertia, r' = resistance),
// while continuity is unchanged. In the weak form the slit cells'
// stiffness is scaled by κ = 1 / (ρ'/ρ0 + r'Δt/ρ0) and loaded by κ r' v_n
// (forms/acoustics.py: k_section, L_section). ρ' = ρ0, r' = 0 is the plain
// wave equation; r' → ∞ closes the domain there. The law (inertia and
// resistance per cell) is the caller's: a WaveSolver is given the operator
// (WaveSolver::set_slit) and applies it every step.
#pragma once
#include <array>
#include <dolfinx/fem/Constant.h>
#include <dolfinx/fem/Form.h>
#include <dolfinx/fem/Function.h>
#include <dolfinx/la/petsc.h>
#include <io/run_state.h>
#include <map>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace fsai::acoustics
{
/// What a slit needs from the wave solver it is attached to
struct SlitContext
{
  std::shared_ptr<const dolfinx::fem::FunctionSpace> V; ///< p' (P1)
  int degree = 1;
  /// Lighthill's source scale (DG0): κ in the slit when the source acts
  /// there, 0 when it does not; 1 elsewhere
  std::shared_ptr<dolfinx::fem::Function<double>> source_scale;
  std::map<std::string, std::shared_ptr<const dolfinx::fem::Constant<double>>>
      constants;
  double rho0 = 1.2;
  double dt = 0;
  std::vector<PetscInt> fixed_rows; ///< global pressure-release rows
};

class SlitLaw
{
public:
  /// @param[in] cells Owned local cells of the slit (any rank may have
  ///   none; every rank must construct and attach it: assembly is
  ///   collective)
  /// @param[in] lighthill_in_slit Lighthill's force enters the slit's
  ///   momentum law, scaled by κ like ∇p' (true), or is left out there
  SlitLaw(std::vector<std::int32_t> cells, bool lighthill_in_slit);

  /// The slit's cells (sorted, no repeats)
  const std::vector<std::int32_t>& cells() const { return _cells; }
  /// The law from the next step on, one value per cells() entry: inertia
  /// ρ'/ρ0 > 0 and resistance r' ≥ 0 [kg/(m³ s)] (defaults 1 and 0)
  void set(std::span<const double> inertia, std::span<const double> resistance);
  /// Acoustic velocity v' [m/s] in each slit cell after the last step
  const std::vector<std::array<double, 2>>& velocity() const { return _v; }

  // The wave solver's side
  /// Build the forms and matrices on the solver's space (collective)
  void attach(const SlitContext& context);
  /// κ and the load for the step; A = A0 + βΔt² D_k(κ)
  void update_operator(Mat A0, Mat A, double beta);
  /// D_k(κ) of the step (for the right-hand side's K(κ) p~)
  Mat stiffness_change() const { return _D_k.mat(); }
  /// Add the slit's load to an assembly array
  void add_load(std::span<double> b) const;
  /// v_{n+1} = (ρ'/Δt v_n − ∇p_{n+1}) / (ρ'/Δt + r') in each cell
  void update_velocity(std::span<const double> p);
  /// The slit's velocity in a checkpoint (by cell key) and back
  void save(io::RankState& state, const std::string& prefix) const;
  void load(const std::vector<io::RankState>& ranks, const std::string& prefix);

private:
  std::vector<std::int64_t> keys() const;
  std::vector<std::int32_t> _cells;
  bool _lighthill;
  SlitContext _ctx;
  std::vector<double> _inertia, _resistance;
  std::vector<std::array<double, 2>> _v;
  std::shared_ptr<dolfinx::fem::Function<double>> _kappa, _flux;
  std::shared_ptr<dolfinx::mesh::MeshTags<std::int32_t>> _tags;
  std::shared_ptr<dolfinx::fem::Form<double>> _k_form, _L_form;
  dolfinx::la::petsc::Matrix _D_k{nullptr, false};
  /// DG0 blocks of each cell (scalar space, vector space), its P1 dofs and
  /// the gradients of their basis functions (∂φ_i/∂x, ∂φ_i/∂y)
  std::vector<std::pair<std::int32_t, std::int32_t>> _dg0;
  std::vector<std::array<std::int32_t, 3>> _dofs;
  std::vector<std::array<double, 6>> _grad;
};
} // namespace fsai::acoustics
