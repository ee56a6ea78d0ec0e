// Copyright (C) 2026 fsai developers
#include "ElasticFold.h"
#include <algorithm>
#include <cmath>
#include <common/Parameters.h>
#include <common/Runtime.h>
#include <common/errors.h>
#include <common/mpi_gather.h>
#include <dolfinx/fem/utils.h>
#include <limits>
#include <mesh/glottis_channel.h>
#include <mesh/vocal_fold.h>
#include <numeric>

//-----------------------------------------------------------------------------
void fsai::glottis::ElasticFoldParameters::bind(fsai::common::Parameters& p)
{
  p.add("elastic.degree", degree,
        "--fold elastic: Lagrange degree of the displacement (1, 2)");
  p.add("elastic.h_surface", h_surface,
        "--fold elastic: mesh size on the fold surface [m]");
  p.add("elastic.h_far", h_far, "--fold elastic: mesh size inside [m]");
  p.add("elastic.E", material.E, "--fold elastic: Young's modulus [Pa]");
  p.add("elastic.nu", material.nu, "--fold elastic: Poisson's ratio");
  p.add("elastic.rho", material.rho, "--fold elastic: density [kg/m^3]");
  p.add("elastic.layers", layers,
        "--fold elastic: 1 (homogeneous) or 2 (body and cover, "
        "--elastic.cover*)");
  p.add("elastic.cover_thickness", cover,
        "--fold elastic --elastic.layers 2: cover thickness [m]");
  p.add("elastic.cover.E", cover_material.E,
        "--elastic.layers 2: Young's modulus of the cover [Pa]");
  p.add("elastic.cover.nu", cover_material.nu,
        "--elastic.layers 2: Poisson's ratio of the cover");
  p.add("elastic.cover.rho", cover_material.rho,
        "--elastic.layers 2: density of the cover [kg/m^3]");
  p.add("elastic.attachment_band", attachment_band,
        "--fold elastic: the fold within this distance of the wall held "
        "fixed (the body on the cartilage, as the 2-DOF fold's "
        "glottis.taper band); 0: held only along the wall [m]");
  p.add("elastic.zeta", zeta,
        "--fold elastic: damping ratio at elastic.f_zeta_low and _high "
        "(Rayleigh damping)");
  p.add("elastic.f_zeta_low", f_zeta_low,
        "--fold elastic: lower frequency of zeta (0: stiffness-proportional "
        "damping) [Hz]");
  p.add("elastic.f_zeta_high", f_zeta_high,
        "--fold elastic: upper frequency of zeta [Hz]");
  p.add("elastic.newmark_gamma", newmark_gamma,
        "--fold elastic: Newmark gamma (beta = (gamma + 1/2)^2 / 4; > 1/2 "
        "damps step-to-step ringing)");
  p.add("elastic.rho_inf", rho_inf,
        "--fold elastic: generalised-alpha step with this spectral radius at "
        "infinite frequency in [0, 1] (second order; replaces "
        "elastic.newmark_gamma); < 0: Newmark");
  p.add_choice("elastic.contact", contact, {"penalty", "hertz"},
               "--fold elastic: contact with the axis, penalty "
               "(--elastic.contact_factor) or hertz (F_H = k_H delta^1.5 (1 + "
               "b_H d(delta)/dt), --contact.*, at the lowest surface point's "
               "osculating radius)");
  p.add("elastic.contact_factor", contact_factor,
        "--fold elastic: contact penalty k_c = factor * E / h_surface");
  p.add("elastic.clamped_ends", clamped_ends,
        "--fold elastic: the section of a fold clamped at its anterior and "
        "posterior ends, geometry.depth apart (false: plane strain)");
  p.add_choice("elastic.coupling", coupling, {"auto", "explicit", "implicit"},
               "--fold elastic: coupling with the flow (explicit: one flow "
               "and fold solve per step; implicit: iterated, --coupling.*; "
               "auto: explicit with --flow bernoulli, implicit with fe)");
}
//-----------------------------------------------------------------------------
void fsai::glottis::ElasticFoldParameters::validate() const
{
  fsai::require(degree == 1 or degree == 2, "--elastic.degree", "1 or 2",
                degree);
  fsai::require_positive("--elastic.h_surface", h_surface);
  fsai::require(h_far >= h_surface, "--elastic.h_far", ">= --elastic.h_surface",
                h_far);
  material.validate("--elastic");
  fsai::require(layers == 1 or layers == 2, "--elastic.layers", "1 or 2",
                layers);
  fsai::require(cover >= h_surface, "--elastic.cover_thickness",
                ">= --elastic.h_surface (at least one layer of cells)", cover);
  cover_material.validate("--elastic.cover");
  fsai::require(attachment_band >= 0, "--elastic.attachment_band", ">= 0",
                attachment_band);
  fsai::require(zeta >= 0 and zeta < 1, "--elastic.zeta", "in [0, 1)", zeta);
  fsai::require_positive("--elastic.f_zeta_high", f_zeta_high);
  fsai::require(f_zeta_low >= 0 and f_zeta_low < f_zeta_high,
                "--elastic.f_zeta_low", "in [0, f_zeta_high)", f_zeta_low);
  fsai::require_positive("--elastic.contact_factor", contact_factor);
  fsai::require_range("--elastic.newmark_gamma", newmark_gamma, 0.5, 1.0);
  fsai::require(rho_inf < 0 or rho_inf <= 1, "--elastic.rho_inf",
                "in [0, 1] (generalised-alpha) or < 0 (Newmark)", rho_inf);
  fsai::require(contact == "penalty" or contact == "hertz", "--elastic.contact",
                "penalty or hertz", contact);
  fsai::require(coupling == "auto" or coupling == "explicit"
                    or coupling == "implicit",
                "--elastic.coupling", "auto, explicit or implicit", coupling);
}
//-----------------------------------------------------------------------------
fsai::coupling::CouplingParameters
fsai::glottis::elastic_coupling_parameters(bool is_explicit,
                                           coupling::CouplingParameters cp)
{
  if (is_explicit)
  {
    cp.max_iterations = 1;
    cp.accelerator.method = "constant";
    cp.accelerator.omega = 1.0;
  }
  return cp;
}
//-----------------------------------------------------------------------------
fsai::glottis::ElasticFold::ElasticFold(MPI_Comm comm,
                                        const FoldProfile& profile,
                                        const ElasticFoldParameters& p,
                                        const ContactParameters& contact,
                                        double dt)
    : _comm(comm), _profile(profile), _contact(contact)
{
  p.validate();
  _mesh = mesh::glottis_channel_and_fold(
              comm, profile, {.h_far = p.h_far, .h_gap = p.h_surface})
              .solid;
  structure::SolidParameters sp;
  sp.degree = p.degree;
  sp.material = p.material;
  sp.clamped_length = p.clamped_ends ? profile.geometry().depth : 0.0;
  sp.newmark_gamma = p.newmark_gamma;
  sp.newmark_beta = 0.25 * (p.newmark_gamma + 0.5) * (p.newmark_gamma + 0.5);
  sp.rho_inf = p.rho_inf;
  sp.set_damping_ratio(p.zeta, p.f_zeta_low, p.f_zeta_high);
  // The contact term makes the linear body's step nonlinear, but its
  // Jacobian changes only when surface dofs enter or leave the contact:
  // modified Newton keeps the factorisation while it contracts (a step
  // without contact changes converges in 2 iterations on one factorisation)
  sp.newton_reuse = true;
  // PETSc's LU of this small 2D system (configure_direct_solver: RCM
  // ordering) took 33 ms per factorisation at 3.4k unknowns, AMD 3.3 ms
  // (nested dissection 6.3 ms). The options database still decides
  common::set_option_default("solid_pc_factor_mat_ordering_type", "amd");
  const auto fold = _mesh.facet_tags->find(_mesh.facet_tag("fold"));
  _solver = std::make_unique<structure::ElasticSolver>(
      _mesh.mesh, _mesh.facet_tags->find(_mesh.facet_tag("attachment")), fold,
      sp, dt);
  if (p.layers == 2)
  {
    // Thinner than the fold (≈ 3 mm deep at the medial surface), so the
    // cells within `cover` of the profile are the cover
    _cover = mesh::cells_near_curve(*_mesh.mesh, profile.points(), p.cover);
    _solver->set_material(_cover, p.cover_material);
  }
  if (p.attachment_band > 0)
  {
    // Every dof (owned and ghost) within the band; the cells the band's edge
    // cuts are held at their dofs inside it
    const auto& g = profile.geometry();
    fsai::require(p.attachment_band
                      < g.half_height - g.rest_gap - 2 * g.medial_radius,
                  "--elastic.attachment_band",
                  "< glottis.half_height - rest_gap - 2 medial_radius (the "
                  "medial surface must vibrate)",
                  p.attachment_band);
    const double y0 = g.half_height - p.attachment_band;
    _solver->fix_where([y0](auto x) { return x[1] >= y0; });
  }
  if (p.contact == "hertz")
  {
    // The osculating radius is resolved down to the surface's mesh size; a
    // face flatter than the medial surface is long meets the axis as a
    // flat punch, beyond Hertz's law: r is held within [h/2, T_m]
    _r_min = 0.5 * p.h_surface;
    _r_max = profile.geometry().medial_thickness;
    _solver->set_contact(0.0, contact.b_H, 0.0);
    _solver->set_contact_update([this](int it) { update_hertz(it); });
  }
  else
    _solver->set_contact(p.contact_factor * p.material.E / p.h_surface,
                         contact.b_H, 0.0);

  // Owned surface dofs, ordered along the profile polyline by arc length
  const auto V = _solver->space();
  const auto dofs = dolfinx::fem::locate_dofs_topological(*V, 1, fold);
  const std::int32_t n_owned = V->dofmap()->index_map->size_local();
  const std::vector<double> Xd = V->tabulate_dof_coordinates(false);
  std::vector<double> loc; // (s, X, Y) per owned point
  for (auto d : dofs)
  {
    if (d >= n_owned)
      continue;
    _owned.push_back(d);
    const double x = Xd[3 * d], y = Xd[3 * d + 1];
    loc.insert(loc.end(), {profile.arc_length({x, y}), x, y});
  }
  const auto all = common::allgather(comm, loc);
  const std::size_t n = all.size() / 3;
  fsai::require(n >= 20, "elastic fold: surface points", ">= 20", long(n));
  _order.resize(n);
  std::iota(_order.begin(), _order.end(), 0);
  std::stable_sort(_order.begin(), _order.end(),
                   [&](auto a, auto b) { return all[3 * a] < all[3 * b]; });
  std::vector<std::size_t> ordered_of(n);
  _X.resize(n);
  for (std::size_t k = 0; k < n; ++k)
  {
    ordered_of[_order[k]] = k;
    _X[k] = {all[3 * _order[k] + 1], all[3 * _order[k] + 2]};
  }
  // This rank's points follow the lower ranks' in the gathered list
  std::int64_t mine = std::int64_t(_owned.size()), first = 0;
  MPI_Exscan(&mine, &first, 1, MPI_INT64_T, MPI_SUM, comm);
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  if (rank == 0)
    first = 0; // MPI_Exscan leaves rank 0's result undefined
  for (std::size_t i = 0; i < _owned.size(); ++i)
    _my_ordered.push_back(ordered_of[first + i]);

  // Outward normals (the fold lies to the left of the point order)
  _n.resize(n);
  for (std::size_t k = 0; k < n; ++k)
  {
    const auto& a = _X[k == 0 ? 0 : k - 1];
    const auto& b = _X[k + 1 == n ? n - 1 : k + 1];
    const double tx = b[0] - a[0], ty = b[1] - a[1], l = std::hypot(tx, ty);
    _n[k] = {ty / l, -tx / l};
  }

  // Medial surface: its centre and its two ends (reference)
  const auto& g = profile.geometry();
  auto nearest = [&](double x, double y)
  {
    std::size_t best = 0;
    double dmin = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < n; ++k)
    {
      const double d = std::hypot(_X[k][0] - x, _X[k][1] - y);
      if (d < dmin)
      {
        dmin = d;
        best = k;
      }
    }
    return best;
  };
  _i_medial = nearest(g.medial_x, g.rest_gap);
  _i_inf = nearest(g.medial_x - 0.5 * g.medial_thickness, g.rest_gap);
  _i_sup = nearest(g.medial_x + 0.5 * g.medial_thickness, g.rest_gap);
}
//-----------------------------------------------------------------------------
std::int64_t fsai::glottis::ElasticFold::dofs() const
{
  const auto& im = *_solver->space()->dofmap()->index_map;
  return im.size_global() * _solver->space()->dofmap()->index_map_bs();
}
//-----------------------------------------------------------------------------
std::vector<double> fsai::glottis::ElasticFold::owned_surface_values(
    const dolfinx::fem::Function<double>& f) const
{
  const auto u = f.x()->array();
  std::vector<double> out;
  out.reserve(2 * _owned.size());
  for (auto d : _owned)
    out.insert(out.end(), {u[2 * d], u[2 * d + 1]});
  return out;
}
//-----------------------------------------------------------------------------
std::vector<double> fsai::glottis::ElasticFold::surface_displacement() const
{
  return owned_surface_values(*_solver->displacement());
}
//-----------------------------------------------------------------------------
std::vector<std::array<double, 2>>
fsai::glottis::ElasticFold::surface_velocity() const
{
  return surface_values(*_solver->velocity());
}
//-----------------------------------------------------------------------------
std::vector<double> fsai::glottis::ElasticFold::surface_prediction() const
{
  const auto u = _solver->displacement()->x()->array();
  const auto v = _solver->velocity()->x()->array();
  const auto a = _solver->acceleration()->x()->array();
  const double dt = _solver->dt();
  std::vector<double> out;
  out.reserve(2 * _owned.size());
  for (auto d : _owned)
    for (int c = 0; c < 2; ++c)
    {
      const std::size_t i = 2 * d + c;
      out.push_back(u[i] + dt * v[i] + 0.5 * dt * dt * a[i]);
    }
  return out;
}
//-----------------------------------------------------------------------------
std::vector<std::array<double, 2>>
fsai::glottis::ElasticFold::moved_surface(std::span<const double> owned) const
{
  const auto all = common::allgather(
      _comm, std::vector<double>(owned.begin(), owned.end()));
  std::vector<std::array<double, 2>> x(_X.size());
  for (std::size_t k = 0; k < _X.size(); ++k)
  {
    const std::size_t g = _order[k];
    x[k] = {_X[k][0] + all[2 * g], _X[k][1] + all[2 * g + 1]};
  }
  return x;
}
//-----------------------------------------------------------------------------
std::vector<std::array<double, 2>> fsai::glottis::ElasticFold::surface_values(
    const dolfinx::fem::Function<double>& f) const
{
  auto x = moved_surface(owned_surface_values(f));
  for (std::size_t k = 0; k < x.size(); ++k)
    x[k] = {x[k][0] - _X[k][0], x[k][1] - _X[k][1]};
  return x;
}
//-----------------------------------------------------------------------------
void fsai::glottis::ElasticFold::set_pressure(std::span<const double> p)
{
  auto& T = _solver->traction();
  auto t = T.x()->mutable_array();
  std::fill(t.begin(), t.end(), 0.0);
  for (std::size_t i = 0; i < _owned.size(); ++i)
  {
    const std::size_t k = _my_ordered[i];
    t[2 * _owned[i]] = -p[k] * _n[k][0];
    t[2 * _owned[i] + 1] = -p[k] * _n[k][1];
  }
  T.x()->scatter_fwd();
}
//-----------------------------------------------------------------------------
namespace
{
// Newton iterations of a step whose iterate sets the Hertz stiffness
constexpr int hertz_updates = 4;
} // namespace

void fsai::glottis::ElasticFold::update_hertz(int iteration)
{
  // G5 for the elastic fold: the lowest surface point x_max of the current
  // iterate has crossed the axis by δ; F_H = k_H(r) δ^{3/2} (the force on
  // the whole depth L_g) is spread over the overlapping surface as the
  // pressure k δ(X) (1 + b_H δ̇(X)), k = F_H / (L_g ∫ δ dS), so that its
  // undamped integral is F_H. k follows the iterate for the first
  // iterations of a step, then stays: updated at every iteration it kept
  // Newton from converging once in 0.2 s at 1.2 kPa (a surface point
  // entering the overlap jumps ∫ δ dS)
  if (iteration > hertz_updates)
    return;
  const auto x = moved_surface(surface_displacement());
  const std::size_t n = x.size();
  std::size_t k = 0;
  for (std::size_t i = 1; i < n; ++i)
    if (x[i][1] < x[k][1])
      k = i;
  _hertz = HertzState{};
  _hertz.penetration = std::max(0.0, -x[k][1]);
  if (_hertz.penetration == 0)
  {
    _solver->set_contact(0.0, _contact.b_H, 0.0);
    return;
  }
  // The contact line: the points below the axis on either side of x_max;
  // the osculating circle through x_max and the second points beyond it
  // (outside the overlap, which the contact pressure flattens)
  std::size_t a = k, b = k;
  while (a > 0 and x[a - 1][1] < 0)
    --a;
  while (b + 1 < n and x[b + 1][1] < 0)
    ++b;
  _hertz.line = {_profile.arc_length(_X[a]), _profile.arc_length(_X[b])};
  const auto& p = x[a >= 2 ? a - 2 : 0];
  const auto& q = x[k];
  const auto& r = x[std::min(n - 1, b + 2)];
  const double lpq = std::hypot(q[0] - p[0], q[1] - p[1]),
               lqr = std::hypot(r[0] - q[0], r[1] - q[1]),
               lpr = std::hypot(r[0] - p[0], r[1] - p[1]);
  const double area2
      = (q[0] - p[0]) * (r[1] - p[1]) - (q[1] - p[1]) * (r[0] - p[0]);
  // Circumradius |pq||qr||pr| / (2 |(q − p) × (r − p)|); collinear: flat
  const double radius
      = std::abs(area2) > 0 ? lpq * lqr * lpr / (2 * std::abs(area2)) : _r_max;
  _hertz.radius = std::clamp(radius, _r_min, _r_max);
  _hertz.force = hertz_stiffness(_contact, _hertz.radius)
                 * std::pow(_hertz.penetration, 1.5);
  const double overlap = _solver->contact_overlap();
  const double depth = _profile.geometry().depth;
  _solver->set_contact(overlap > 0 ? _hertz.force / (depth * overlap) : 0.0,
                       _contact.b_H, 0.0);
}
//-----------------------------------------------------------------------------
double fsai::glottis::ElasticFold::contact_force() const
{
  return _solver->contact_force() * _profile.geometry().depth;
}
//-----------------------------------------------------------------------------
std::array<double, 2> fsai::glottis::ElasticFold::medial_motion(
    const std::vector<std::array<double, 2>>& x) const
{
  const double h = _X[_i_medial][1] - x[_i_medial][1];
  const double phi
      = std::atan2(x[_i_sup][1] - x[_i_inf][1], x[_i_sup][0] - x[_i_inf][0])
        - std::atan2(_X[_i_sup][1] - _X[_i_inf][1],
                     _X[_i_sup][0] - _X[_i_inf][0]);
  return {h, phi};
}
//-----------------------------------------------------------------------------
void fsai::glottis::ElasticFold::fill_sample(
    const std::vector<std::array<double, 2>>& x,
    const coupling::StepReport& rep, bool explicit_scheme,
    std::string_view scene, Sample& out) const
{
  const auto m = medial_motion(x);
  out.h = m[0];
  out.phi = m[1];
  out.moment = 0;
  out.iterations = rep.iterations;
  out.converged = explicit_scheme or rep.converged;
  out.contact_force = contact_force();
  out.penetration = std::max(0.0, -out.gap);
  require_finite(out, scene);
}
//-----------------------------------------------------------------------------
std::array<double, 2> fsai::glottis::ElasticFold::pressure_force(
    const std::vector<std::array<double, 2>>& x,
    std::span<const double> p) const
{
  // Into the fold: the fold lies to the left of the point order
  std::array<double, 2> f{};
  const double Lg = _profile.geometry().depth;
  for (std::size_t i = 0; i + 1 < x.size(); ++i)
  {
    const double tx = x[i + 1][0] - x[i][0], ty = x[i + 1][1] - x[i][1];
    const double pm = 0.5 * (p[i] + p[i + 1]);
    f[0] -= pm * ty * Lg;
    f[1] += pm * tx * Lg;
  }
  return f;
}
