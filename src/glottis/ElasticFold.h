// Copyright (C) 2026 fsai developers
//
// The elastic vocal fold of the glottis scene (`--fold elastic`;
// docs/model.md §1): the region between the fold profile's
// surface and its lateral attachment y = H (mesh::glottis_channel_and_fold,
// the same nodes on the fold curve as the flow mesh) as a plane-strain
// linear elastic body (E = 8 kPa, ν = 0.4 by default; ElasticSolver, Newmark,
// stiffness-proportional Rayleigh damping), fixed at the attachment and
// loaded by a pressure on its surface. The two folds meet on the symmetry
// axis y = 0: a penalty contact with that plane (forms/structure.py,
// implicit in each Newton solve) takes the place of the rigid profile's
// Hertz force, since the body's own elasticity now gives the deformation
// near the contact.
//
// The surface is handled as an ordered polyline of its displacement dofs
// (P2: vertices and facet midpoints), inferior → superior like
// FoldProfile::points(): every rank holds the whole polyline (a few hundred
// points), gathered each evaluation, so a 1D flow model sees the same
// surface on any number of ranks.
#pragma once
#include "FoldProfile.h"
#include "HertzContact.h"
#include "Sample.h"
#include <coupling/FixedPointCoupling.h>
#include <memory>
#include <mesh/MeshData.h>
#include <mpi.h>
#include <span>
#include <structure/ElasticSolver.h>
#include <vector>

namespace fsai::common
{
class Parameters;
}

namespace fsai::glottis
{
/// [elastic] section
struct ElasticFoldParameters
{
  int degree = 2;
  double h_surface = 0.2e-3; ///< mesh size on the fold surface [m]
  double h_far = 1e-3;       ///< mesh size away from it [m]
  structure::Material material{8e3, 0.4, 1000.0};
  /// 1: homogeneous; 2: body–cover, the cells whose midpoint lies within
  /// `cover` of the free surface (the profile) are of `cover_material`,
  /// the rest (the body) of `material` (as `fsai_modal --layers 2`)
  int layers = 1;
  double cover = 1e-3; ///< cover thickness [m]
  /// > 0: the fold within this distance of the wall (y ≥ H − band) is held
  /// fixed, the body attached to the thyroid cartilage, as the 2-DOF
  /// fold's attachment band (glottis.taper, G1) is. 0: the whole section
  /// vibrates, held only along the wall. A soft fold held only there
  /// shears so far downstream (0.4 mm at 1 mm from the wall at 800 Pa)
  /// that its superior surface rolls onto the wall at the superior
  /// attachment, and the fluid's corner there collapses (docs/glottis.md)
  double attachment_band = 0; ///< [m]
  structure::Material cover_material{2e3, 0.4, 1000.0};
  /// Rayleigh damping D = ε1 M + ε2 K with the damping ratio ζ at both
  /// f_zeta_low and f_zeta_high (ε1 = 2ζ ω_l ω_h/(ω_l + ω_h), ε2 = 2ζ/(ω_l
  /// + ω_h)): about ζ between them, more above (the noise of impacts).
  /// f_zeta_low = 0: stiffness-proportional only, ζ at f_zeta_high
  double zeta = 0.01;
  double f_zeta_low = 0;    ///< [Hz]
  double f_zeta_high = 100; ///< [Hz]
  /// Newmark's γ of the fold's step, β = (γ + 1/2)²/4: 1/2 is the
  /// average-acceleration rule (no numerical damping), γ > 1/2 damps the
  /// step-to-step ringing of stiff, heavily damped surface motion (in a
  /// nearly closed glottis the squeezed air film), for which the
  /// trapezoidal rule's amplification tends to −1 (E18)
  double newmark_gamma = 0.5;
  /// Generalised-α step (E18a) with this ρ∞ ∈ [0, 1] instead of Newmark's
  /// γ: second order, yet it damps the same step-to-step ringing (ρ∞ < 1);
  /// < 0: Newmark (newmark_gamma)
  double rho_inf = -1.0;
  /// Contact with the axis: "penalty" (k_c below) or "hertz" (G5 for the
  /// elastic fold: ElasticFold::hertz())
  std::string contact = "penalty";
  /// Contact penalty k_c = contact_factor · E / h_surface [Pa/m]: the
  /// penetration under a contact pressure p is p h_surface / (factor E),
  /// i.e. a fraction 1/factor of what the first cell's own stiffness
  /// allows; larger factors stiffen the Newton solves. E is the body's
  /// (material.E) for a body–cover fold too, whose softer cover so meets
  /// a penalty E/E_cover times stiffer relative to its own cells
  double contact_factor = 10;
  /// The fold as the section of a fold of the scene's length L_g
  /// (geometry.depth) clamped at its anterior and posterior ends
  /// (SolidParameters::clamped_length: an elastic foundation μ (π/L_g)² u,
  /// the first anterior–posterior harmonic). false: plane strain, a fold
  /// held only at its lateral attachment
  bool clamped_ends = false;
  /// Coupling of the fold with the flow: "explicit" (the load of the
  /// Newmark-predicted surface, one solve per step), "implicit" (iterated
  /// to the [coupling] tolerance) or "auto": explicit with the Bernoulli
  /// flow, implicit with the FE flow.
  /// - Bernoulli: the quasi-steady load has no added mass, so the explicit
  ///   scheme is stable; it gave the implicit scheme's cycle (f0 equal,
  ///   peak flow −0.35 %) at 0.4 of its cost, while the implicit iteration
  ///   stalled at 1e−5–1e−3 in about 35 steps per 0.25 s near contact
  ///   changes and diverged in a few.
  /// - FE flow: the air the surface displaces through the channel is an
  ///   added mass far above that of the fold's surface layer, and the
  ///   explicit scheme diverges (lift ×3–4 per step from the first steps,
  ///   a cell inverted at step 13: ElasticFlowGlottis.h)
  std::string coupling = "auto";
  /// Whether the fold is coupled explicitly, with a flow that has
  /// (FE) or has not (Bernoulli) an added mass
  bool explicit_coupling(bool added_mass) const
  {
    return coupling == "explicit" or (coupling == "auto" and !added_mass);
  }
  void bind(fsai::common::Parameters& p);
  void validate() const;
};

/// The [coupling] parameters of the fold's coupling loop: one application
/// of the map, unrelaxed, for an explicit coupling
coupling::CouplingParameters
elastic_coupling_parameters(bool is_explicit, coupling::CouplingParameters cp);

/// The Hertz contact of the last contact update (G5 for the elastic fold)
struct HertzState
{
  double penetration
      = 0;           ///< δ: depth of the lowest surface point below y = 0 [m]
  double radius = 0; ///< r: osculating radius there [m]
  double force = 0;  ///< F_H without damping, times L_g [N]
  /// Arc lengths (reference) of the first and last surface points below
  /// y = 0: the contact line [m]
  std::array<double, 2> line{0, 0};
};

class ElasticFold
{
public:
  /// @param[in] dt Time step [s]; contact damping b_c = contact.b_H
  ElasticFold(MPI_Comm comm, const FoldProfile& profile,
              const ElasticFoldParameters& p, const ContactParameters& contact,
              double dt);

  /// Local cells of the cover (none for a homogeneous fold)
  const std::vector<std::int32_t>& cover_cells() const { return _cover; }
  // The Hertz update captures `this`
  ElasticFold(const ElasticFold&) = delete;
  ElasticFold& operator=(const ElasticFold&) = delete;

  /// Surface points of all ranks, ordered inferior → superior
  std::size_t surface_size() const { return _X.size(); }
  /// Reference positions of the ordered surface points
  const std::vector<std::array<double, 2>>& surface_reference() const
  {
    return _X;
  }
  /// This rank's owned surface displacement (x, y per owned surface point)
  std::vector<double> surface_displacement() const;
  /// The velocity at the ordered surface points (collective)
  std::vector<std::array<double, 2>> surface_velocity() const;
  /// Its Newmark predictor u + Δt v + ½Δt² a (the next step's first guess)
  std::vector<double> surface_prediction() const;
  /// The ordered surface of all ranks moved by this rank's owned
  /// displacements `owned` (collective)
  std::vector<std::array<double, 2>>
  moved_surface(std::span<const double> owned) const;
  /// Values of a displacement-space function at the ordered surface
  /// points (collective)
  std::vector<std::array<double, 2>>
  surface_values(const dolfinx::fem::Function<double>& f) const;
  /// Pressure p at the ordered surface points [Pa]: traction −p n
  void set_pressure(std::span<const double> p);

  /// The fold's accepted state into / from a checkpoint (prefix "fold.")
  void save(io::RankState& state) const { _solver->save(state, "fold."); }
  void load(const std::vector<io::RankState>& ranks)
  {
    _solver->load(ranks, "fold.");
  }
  void save_state() { _solver->save_state(); }
  void restore_state() { _solver->restore_state(); }
  /// Length of the next steps (a cut step, ElasticFlowGlottis)
  void set_dt(double dt) { _solver->set_dt(dt); }
  /// One Newmark step under the set pressure (and contact); Newton its
  int step() { return _solver->step(); }

  /// Contact force along +y of the last step, times the depth L_g [N]
  double contact_force() const;
  /// The Hertz contact at the last Newton iterate (--elastic.contact hertz)
  const HertzState& hertz() const { return _hertz; }
  /// Sets the Hertz contact's stiffness from the current displacement, as
  /// at a step's first Newton iteration (for tests and diagnostics;
  /// collective)
  void update_contact() { update_hertz(1); }
  /// Translation h (towards the axis) of the medial surface's centre and
  /// its tilt φ (counter-clockwise, > 0 divergent) of a moved surface
  std::array<double, 2>
  medial_motion(const std::vector<std::array<double, 2>>& x) const;
  /// The fold's fields of a step's sample, for its moved surface x and the
  /// sample's gap: medial h and φ, moment 0 (a continuum has no
  /// generalised rotation), the contact force and the penetration; the
  /// coupling's iterations, and converged (always, for an explicit scheme:
  /// it has no iteration to converge; its residual, the change of the
  /// surface over the step's solve, is in coupling.csv). Then
  /// require_finite, whose error names the scene.
  void fill_sample(const std::vector<std::array<double, 2>>& x,
                   const coupling::StepReport& rep, bool explicit_scheme,
                   std::string_view scene, Sample& out) const;
  /// Force of the pressure p on the moved surface x, times L_g [N]
  std::array<double, 2>
  pressure_force(const std::vector<std::array<double, 2>>& x,
                 std::span<const double> p) const;

  structure::ElasticSolver& solver() { return *_solver; }
  MPI_Comm comm() const { return _comm; }
  const FoldProfile& profile() const { return _profile; }
  const mesh::MeshData& mesh() const { return _mesh; }
  std::int64_t dofs() const;

private:
  MPI_Comm _comm;
  const FoldProfile& _profile;
  mesh::MeshData _mesh;
  std::unique_ptr<structure::ElasticSolver> _solver;
  /// --elastic.contact hertz: the contact pressure k δ(X) (1 + b_H δ̇)
  /// with k set before the residual of Newton iteration `iteration` so
  /// that its integral is F_H
  void update_hertz(int iteration);
  /// This rank's owned surface values of a displacement-space function
  /// (x, y per owned surface point)
  std::vector<double>
  owned_surface_values(const dolfinx::fem::Function<double>& f) const;
  ContactParameters _contact;
  double _r_min = 0, _r_max = 0; // bounds of the osculating radius [m]
  HertzState _hertz;
  std::vector<std::int32_t> _cover;
  std::vector<std::int32_t> _owned; ///< owned surface dof blocks
  /// The gathered (rank-ordered) index of each ordered point
  std::vector<std::size_t> _order;
  std::vector<std::array<double, 2>> _X; // ordered reference points
  std::vector<std::array<double, 2>> _n; // their outward normals
  /// Ordered index of each of this rank's owned points
  std::vector<std::size_t> _my_ordered;
  std::size_t _i_medial = 0, _i_inf = 0, _i_sup = 0;
};
} // namespace fsai::glottis
