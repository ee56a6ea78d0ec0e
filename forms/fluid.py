# Incompressible Navier–Stokes in ALE form with P1/P1 stabilisation
# (docs/model.md E8–E11, E19, E20), triangles and tetrahedra.
#
# Strong form on the moving domain Ω_t, mesh velocity w, body force f:
#   ρ (∂v/∂t|_A + ((v − w)·∇) v) − μ Δv + ∇p + σ_P χ (v − w) = ρ f,  ∇·v = 0
# (the ALE time derivative at fixed reference points is the derivative of
# the nodal values on the moving mesh; E8's conservative form differs from
# this one by (∇·w) v, which the geometric conservation law makes vanish
# for the discrete BDF on a mesh moved consistently).
#
# Time: BDF (E19) with coefficients a0, a1, a2 (already divided by Δt):
#   ∂v/∂t ≈ a0 v + a1 v_n + a2 v_nn; BDF1 (1, −1, 0)/Δt, BDF2 (3/2, −2, 1/2)/Δt,
#   steady problems a0 = a1 = a2 = 0.
# Linearisation (E20): the convecting velocity b = v* − w with v* given by
#   the caller (2v_n − v_nn: Oseen with extrapolation; the last iterate:
#   Picard), so every solve is linear.
# Galerkin weak form (gradient form of the viscous term, which gives the
# boundary conditions of E11 as natural ones):
#   ρ(a0 v + (∇v) b, φ) + μ(∇v, ∇φ) − (p, ∇·φ) + (∇·v, q) + σ_P(χ v, φ)
#     = −ρ(a1 v_n + a2 v_nn, φ) + σ_P(χ w, φ) + ρ(f, φ)
# Boundaries (ds ids bound at run time; zero unless facets are given):
#   ds(1) inlet, E11a penalty form, ε [s/m]:
#     + ∫ [ (ρ/ε)(v − v_in) + p_in n − ½ρ (b·n)⁻ v ]·φ
#   ds(2) outlet, E11c directional do-nothing:
#     + ∫ [ p_out n − ½ρ (b·n)⁻ v ]·φ
#   The −½ρ(b·n)⁻ term, (x)⁻ = min(x, 0), cancels the energy that the
#   convective term would bring in through backflow (Braack & Mucha 2014);
#   with it ½∫(b·n)|v|² becomes ½∫(b·n)⁺|v|² ≥ 0.
#   ε → 0: Dirichlet v = v_in; ε → ∞: pressure inlet p = p_in (E11a).
# Stabilisation (E20), each term switched by a 0/1 constant:
#   R_m = ρ(a0 v + a1 v_n + a2 v_nn + (∇v) b − f) + ∇p + σ_P χ (v − w)
#     (−μΔv vanishes on P1)
#   SUPG   + Σ_K τ_m (R_m, (∇φ) b)_K
#   PSPG   + Σ_K (τ_m/ρ) (R_m, ∇q)_K
#   div-div + Σ_K ρ τ_c (∇·v, ∇·φ)_K
#   τ_m = [(2/Δt)² + (2|b|/h)² + (4ν/h²)²]^(−1/2), τ_c = h|b|/2 (Tezduyar
#   1992; the Δt term is dropped for steady problems), h the cell diameter.
import ufl
from ufl import (FacetNormal, CellDiameter, conditional, div, dot, ds,
                 grad, inner, lt, sqrt, split)

from fsai_ufl import dim, domain

mesh = domain()
cell = mesh.ufl_cell()
P1v = ufl.VectorElement("Lagrange", cell, 1)
P1 = ufl.FiniteElement("Lagrange", cell, 1)
DG0 = ufl.FiniteElement("DG", cell, 0)
W = ufl.FunctionSpace(mesh, ufl.MixedElement([P1v, P1]))
V = ufl.FunctionSpace(mesh, P1v)

(phi, q) = ufl.TestFunctions(W)
up = ufl.Coefficient(W)        # a solution (residual, forces, flux)
v_n = ufl.Coefficient(V)
v_nn = ufl.Coefficient(V)
v_star = ufl.Coefficient(V)    # convecting flow velocity (extrapolated/iterate)
w = ufl.Coefficient(V)         # mesh velocity
v_in = ufl.Coefficient(V)      # inlet velocity (E11a)
f = ufl.Coefficient(V)         # body force per unit mass [m/s²]
chi = ufl.Coefficient(ufl.FunctionSpace(mesh, DG0))  # porous indicator

rho = ufl.Constant(mesh)
mu = ufl.Constant(mesh)
a0 = ufl.Constant(mesh)
a1 = ufl.Constant(mesh)
a2 = ufl.Constant(mesh)
inv_dt = ufl.Constant(mesh)    # 1/Δt in τ_m (0 for steady problems)
supg = ufl.Constant(mesh)
pspg = ufl.Constant(mesh)
graddiv = ufl.Constant(mesh)
sigma_p = ufl.Constant(mesh)   # inverse permeability σ_P [kg/(m³ s)]
tau_porous = ufl.Constant(mesh)  # 1: τ_m holds the porous term (E20), 0: not
inv_eps = ufl.Constant(mesh)   # 1/ε of the inlet penalty [m/s]
p_in = ufl.Constant(mesh)
p_out = ufl.Constant(mesh)

# Quadrature degree of the cell integrals, compiled twice (the solver picks
# one, --fluid.quadrature_degree): 4 (6 points per triangle, 14 per
# tetrahedron), the default, or 2 (3 and 4 points). The Galerkin terms are
# at most quadratic on P1, so both integrate them exactly; they differ only
# in the stabilisation terms, quadratic times the non-polynomial τ, which
# degree 2 samples at fewer points. UFL's own estimate for τ_m (a −1/2
# power) was degree 10 (33 points per triangle), which made assembly 5x
# dearer for no accuracy.
dx4 = ufl.Measure("dx", domain=mesh, metadata={"quadrature_degree": 4})
dx2 = ufl.Measure("dx", domain=mesh, metadata={"quadrature_degree": 2})

n = FacetNormal(mesh)
h = CellDiameter(mesh)
b = v_star - w
bn = dot(b, n)
bn_minus = conditional(lt(bn, 0), bn, 0)
nu = mu / rho
bnorm = sqrt(dot(b, b) + 1e-30)
# 1/sqrt rather than (…)**−0.5: FFCx emits pow() for the latter, which
# took a third of the matrix kernel's time (perf)
# With tau_porous = 1, τ_m also holds the porous reaction σ_P χ/ρ (E20): in
# Ω^P the PSPG term then tends to the Darcy pressure operator (1/σ_P)(∇p, ∇q)
# instead of nearly cancelling it (without it, τ_m σ_P/ρ ≈ 40 there)
tau_m = 1 / sqrt((2 * inv_dt) ** 2 + (2 * bnorm / h) ** 2 + (4 * nu / h**2) ** 2
                 + (tau_porous * sigma_p * chi / rho) ** 2)
tau_c = 0.5 * h * bnorm


def residual(v, p, dx):
    """Full weak residual F((v, p); (φ, q)); linear in (v, p) for fixed b;
    dx: the cell measure (its quadrature degree)"""
    R_m = (rho * (a0 * v + a1 * v_n + a2 * v_nn + grad(v) * b - f) + grad(p)
           + sigma_p * chi * (v - w))
    F = (rho * inner(a0 * v + a1 * v_n + a2 * v_nn + grad(v) * b, phi) * dx
         + mu * inner(grad(v), grad(phi)) * dx
         - p * div(phi) * dx + div(v) * q * dx
         + sigma_p * chi * inner(v - w, phi) * dx
         - rho * inner(f, phi) * dx
         + supg * tau_m * inner(R_m, grad(phi) * b) * dx
         + pspg * tau_m / rho * inner(R_m, grad(q)) * dx
         + graddiv * rho * tau_c * div(v) * div(phi) * dx
         + inner(rho * inv_eps * (v - v_in) + p_in * n
                 - 0.5 * rho * bn_minus * v, phi) * ds(1)
         + inner(p_out * n - 0.5 * rho * bn_minus * v, phi) * ds(2))
    return F


(v_tr, p_tr) = ufl.TrialFunctions(W)
a, L = ufl.system(residual(v_tr, p_tr, dx4))
a_q2, L_q2 = ufl.system(residual(v_tr, p_tr, dx2))

# Residual of a given solution: forces on a boundary are its entries at
# that boundary's velocity dofs (E12, consistent traction); with the same
# quadrature as the system solved, or the traction is not consistent
(v_h, p_h) = split(up)
F_res = residual(v_h, p_h, dx4)
F_res_q2 = residual(v_h, p_h, dx2)

# Flow rate through the facets bound to ds(1)
flux = dot(v_h, n) * ds(1)

# ∫|∇p|²: grows with spurious pressure modes (P1/P1 without PSPG)
grad_p_sq = inner(grad(p_h), grad(p_h)) * dx4

# Pressure convection–diffusion (PCD) Schur approximation of the iterative
# solver (docs/model.md E20b), on the pressure space: the Laplacian K_p, the
# velocity block's operator acting on pressures F_p (transient, porous,
# viscous, convective and SUPG streamline-diffusion terms, with the same b
# and τ_m as the system), the lumped mass m_p and the div-div weight g_p
# (∫ ρ τ_c φ_i, the augmented-Lagrangian part of the Schur complement)
Q = ufl.FunctionSpace(mesh, P1)
p_pcd, q_pcd = ufl.TrialFunction(Q), ufl.TestFunction(Q)
K_p = inner(grad(p_pcd), grad(q_pcd)) * dx2
F_p = ((rho * a0 + sigma_p * chi) * p_pcd * q_pcd * dx2
       + mu * inner(grad(p_pcd), grad(q_pcd)) * dx2
       + rho * dot(b, grad(p_pcd)) * q_pcd * dx2
       + supg * tau_m * rho * dot(b, grad(p_pcd)) * dot(b, grad(q_pcd)) * dx2)
m_p = q_pcd * dx2
g_p = graddiv * rho * tau_c * q_pcd * dx2

forms = [a, L, F_res, a_q2, L_q2, F_res_q2, flux, grad_p_sq, K_p, F_p, m_p,
         g_p]
