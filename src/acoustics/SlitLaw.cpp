// Copyright (C) 2026 fsai developers
#include "SlitLaw.h"
#include "../common/errors.h"
#include "../common/timer.h"
#include <algorithm>
#include <cmath>
#include <dolfinx/fem/assembler.h>
#include <dolfinx/fem/petsc.h>
#include <dolfinx/fem/utils.h>
#include <fsai_forms/acoustics.h>
#include <io/field_state.h>

using namespace dolfinx;
namespace acoustic_forms = fsai::forms::acoustics;

//-----------------------------------------------------------------------------
fsai::acoustics::SlitLaw::SlitLaw(std::vector<std::int32_t> cells,
                                  bool lighthill_in_slit)
    : _cells(std::move(cells)), _lighthill(lighthill_in_slit)
{
  std::sort(_cells.begin(), _cells.end());
  _cells.erase(std::unique(_cells.begin(), _cells.end()), _cells.end());
  _inertia.assign(_cells.size(), 1.0);
  _resistance.assign(_cells.size(), 0.0);
  _v.assign(_cells.size(), {0.0, 0.0});
}
//-----------------------------------------------------------------------------
void fsai::acoustics::SlitLaw::set(std::span<const double> inertia,
                                   std::span<const double> resistance)
{
  if (inertia.size() != _cells.size() or resistance.size() != _cells.size())
  {
    throw std::runtime_error("acoustics: slit law for "
                             + std::to_string(inertia.size()) + " cells, "
                             + std::to_string(_cells.size()) + " expected");
  }
  for (std::size_t i = 0; i < inertia.size(); ++i)
  {
    if (!(inertia[i] > 0) or !(resistance[i] >= 0) or !std::isfinite(inertia[i])
        or !std::isfinite(resistance[i]))
    {
      throw std::runtime_error(
          "acoustics: slit law needs a finite inertia > 0 and resistance >= 0 "
          "(got "
          + std::to_string(inertia[i]) + ", " + std::to_string(resistance[i])
          + ")");
    }
  }
  std::copy(inertia.begin(), inertia.end(), _inertia.begin());
  std::copy(resistance.begin(), resistance.end(), _resistance.begin());
}
//-----------------------------------------------------------------------------
void fsai::acoustics::SlitLaw::attach(const SlitContext& context)
{
  _ctx = context;
  const auto& V = *_ctx.V;
  auto mesh = std::const_pointer_cast<mesh::Mesh>(V.mesh());
  const int tdim = mesh->topology().dim();
  const int degree = _ctx.degree;
  fsai::require(degree == 1, "acoustics: a slit", "P1 pressure", degree);
  fsai::require(tdim == 2, "acoustics: a slit", "a 2D mesh", tdim);
  const std::int32_t nc = mesh->topology().index_map(tdim)->size_local();
  for (auto c : _cells)
    fsai::require(c >= 0 and c < nc, "acoustics: slit cell",
                  "an owned cell of this rank", c);
  // Per cell: P1 dofs and ∇φ_i = J⁻ᵀ ∇̂φ_i (triangles, x-y plane)
  const auto X = V.tabulate_dof_coordinates(false);
  for (auto c : _cells)
  {
    const auto d = V.dofmap()->cell_dofs(c);
    const double j00 = X[3 * d[1]] - X[3 * d[0]],
                 j01 = X[3 * d[2]] - X[3 * d[0]],
                 j10 = X[3 * d[1] + 1] - X[3 * d[0] + 1],
                 j11 = X[3 * d[2] + 1] - X[3 * d[0] + 1];
    const double det = j00 * j11 - j01 * j10;
    // rows of J⁻¹: (j11, −j01)/det and (−j10, j00)/det; ∇φ1 = first row of
    // J⁻¹ (as a column), ∇φ2 = second, ∇φ0 = −∇φ1 − ∇φ2
    const double g1x = j11 / det, g1y = -j01 / det, g2x = -j10 / det,
                 g2y = j00 / det;
    _dofs.push_back({d[0], d[1], d[2]});
    _grad.push_back({-g1x - g2x, -g1y - g2y, g1x, g1y, g2x, g2y});
  }
  auto space = [&](auto factory, const char* name)
  {
    return std::make_shared<fem::FunctionSpace>(
        fem::create_functionspace(factory, name, mesh));
  };
  _kappa = std::make_shared<fem::Function<double>>(
      space(acoustic_forms::functionspace_k_section(tdim, degree), "kappa"));
  _kappa->x()->set(1.0);
  _flux = std::make_shared<fem::Function<double>>(space(
      acoustic_forms::functionspace_L_section(tdim, degree), "slit_flux"));
  // DG0 dofs are not numbered as the cells: the block of each slit cell in
  // the scalar and in the vector space (κ and the source scale: the same
  // element on the same mesh, hence the same numbering)
  for (auto c : _cells)
  {
    const auto d = _kappa->function_space()->dofmap()->cell_dofs(c)[0];
    if (_ctx.source_scale->function_space()->dofmap()->cell_dofs(c)[0] != d)
      throw std::runtime_error("acoustics: DG0 spaces numbered differently");
    _dg0.push_back({d, _flux->function_space()->dofmap()->cell_dofs(c)[0]});
  }
  std::vector<std::int32_t> cells = _cells, ones(_cells.size(), 1);
  _tags = std::make_shared<mesh::MeshTags<std::int32_t>>(
      mesh, tdim, std::move(cells), std::move(ones));
  const std::map<fem::IntegralType, const mesh::MeshTags<int>*> sd{
      {fem::IntegralType::cell, _tags.get()}};
  auto Vp = _ctx.V;
  _k_form = std::make_shared<fem::Form<double>>(fem::create_form<double>(
      acoustic_forms::k_section(tdim, degree), {Vp, Vp}, {{"kappa", _kappa}},
      _ctx.constants, sd, mesh));
  _L_form = std::make_shared<fem::Form<double>>(fem::create_form<double>(
      acoustic_forms::L_section(tdim, degree), {Vp}, {{"slit_flux", _flux}},
      _ctx.constants, sd, mesh));
  _D_k = la::petsc::Matrix(fem::petsc::create_matrix(*_k_form), false);
}
//-----------------------------------------------------------------------------
void fsai::acoustics::SlitLaw::update_operator(Mat A0, Mat A, double beta)
{
  common::ScopedTimer t("acoustics: slit update");
  // κ = 1 / (ρ'/ρ0 + r'Δt/ρ0) and the load κ r' v_n, cell by cell
  {
    auto kappa = _kappa->x()->mutable_array();
    auto source = _ctx.source_scale->x()->mutable_array();
    auto flux = _flux->x()->mutable_array();
    for (std::size_t i = 0; i < _cells.size(); ++i)
    {
      const double r = _resistance[i];
      const double k = 1.0 / (_inertia[i] + r * _ctx.dt / _ctx.rho0);
      const auto [dk, dv] = _dg0[i];
      kappa[dk] = k;
      source[dk] = _lighthill ? k : 0.0;
      flux[2 * dv] = k * r * _v[i][0];
      flux[2 * dv + 1] = k * r * _v[i][1];
    }
  }
  MatZeroEntries(_D_k.mat());
  fem::assemble_matrix(la::petsc::Matrix::set_block_fn(_D_k.mat(), ADD_VALUES),
                       *_k_form, {});
  MatAssemblyBegin(_D_k.mat(), MAT_FINAL_ASSEMBLY);
  MatAssemblyEnd(_D_k.mat(), MAT_FINAL_ASSEMBLY);
  // Pressure-release rows keep p̈ = 0: no change on them
  MatZeroRowsColumns(_D_k.mat(), PetscInt(_ctx.fixed_rows.size()),
                     _ctx.fixed_rows.data(), 0.0, nullptr, nullptr);
  MatCopy(A0, A, SAME_NONZERO_PATTERN);
  MatAXPY(A, beta * _ctx.dt * _ctx.dt, _D_k.mat(), SUBSET_NONZERO_PATTERN);
}
//-----------------------------------------------------------------------------
void fsai::acoustics::SlitLaw::add_load(std::span<double> b) const
{
  fem::assemble_vector(b, *_L_form);
}
//-----------------------------------------------------------------------------
void fsai::acoustics::SlitLaw::update_velocity(std::span<const double> p)
{
  for (std::size_t i = 0; i < _cells.size(); ++i)
  {
    const auto& d = _dofs[i];
    const auto& g = _grad[i];
    const double m = _inertia[i] * _ctx.rho0 / _ctx.dt;
    for (int k = 0; k < 2; ++k)
    {
      const double grad_p
          = g[k] * p[d[0]] + g[2 + k] * p[d[1]] + g[4 + k] * p[d[2]];
      _v[i][k] = (m * _v[i][k] - grad_p) / (m + _resistance[i]);
    }
  }
}
//-----------------------------------------------------------------------------
std::vector<std::int64_t> fsai::acoustics::SlitLaw::keys() const
{
  const auto all = io::cell_keys(*_ctx.V->mesh());
  std::vector<std::int64_t> k;
  for (auto c : _cells)
    k.push_back(all[c]);
  return k;
}
//-----------------------------------------------------------------------------
void fsai::acoustics::SlitLaw::save(io::RankState& state,
                                    const std::string& prefix) const
{
  // The slit's velocity by cell (input index)
  const auto k = keys();
  std::vector<double> v;
  for (const auto& vi : _v)
    v.insert(v.end(), vi.begin(), vi.end());
  io::put_blocks(state, prefix + "slit_v", v, 2, k, std::int32_t(k.size()));
}
//-----------------------------------------------------------------------------
void fsai::acoustics::SlitLaw::load(const std::vector<io::RankState>& ranks,
                                    const std::string& prefix)
{
  const auto k = keys();
  std::vector<double> v(2 * k.size());
  io::get_blocks(ranks, prefix + "slit_v", v, 2, k);
  for (std::size_t i = 0; i < _cells.size(); ++i)
    _v[i] = {v[2 * i], v[2 * i + 1]};
}
