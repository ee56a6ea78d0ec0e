# Acoustic wave equation with Lighthill's source (docs/model.md E14, E15,
# E21), compiled for triangles (2D planar and axisymmetric) and tetrahedra.
#
# Strong form, acoustic pressure p' in a fixed domain Ω^a:
#   (1/c0²) ∂²p'/∂t² − Δp' = ∂²T_ij/∂x_i∂x_j,   T_ij = χ ρ0 v_i v_j   (E14, E15)
# with χ ∈ [0, 1] a taper that vanishes before the end of the flow region.
# Boundaries (each form's ds(1) is bound at run time to the facets of one
# role, so the form file does not depend on the mesh's tag numbers):
#   sound-hard wall      ∂p'/∂n = 0                     (natural)
#   vibrating wall       ∂p'/∂n = −ρ0 a·n               (L_wall)
#   volume-velocity inlet ∂p'/∂n = ρ0 du/dt, u the normal velocity into the
#                        domain                          (b_inlet, times du/dt)
#   radiation            (1/c0) ∂p'/∂t + ∂p'/∂n + β p' = 0   (c, k)
#     β = 0: first-order Sommerfeld; β = 1/R (spherical) or 1/(2R)
#     (cylindrical, planar 2D): Bayliss–Turkel first-order condition on a
#     circle/sphere of radius R centred on the source, exact for a
#     monopole in 3D.
# Absorbing layer (alternative to a bare radiation condition): a damping
# function σ(x) ≥ 0, zero outside the layer, in
#   (1/c0²)(p̈ + 2σ ṗ + σ² p) − Δp = 0,
# whose 1D solution p = exp(−σx/c0) g(t − x/c0) travels without dispersion
# and decays: a layer exact for normal incidence (not perfectly matched at
# oblique incidence; the measured reflection is in docs/benchmarks.md).
#
# Weak form (E21): M P̈ + C Ṗ + K P = b(t) with
#   M = ∫ (1/c0²) p q w dx
#   C = ∫ (1/c0) p q w ds_rad + ∫ (2σ/c0²) p q w dx
#   K = ∫ ∇p·∇q w dx + β ∫ p q w ds_rad + ∫ (σ²/c0²) p q w dx
#   b = −∫ (∇·T)_w · ∇q dx − ρ0 ∫ (a·n) q w ds_wall + (du/dt) ρ0 ∫ q w ds_in
# The weight w is 1 (planar, 3D) or r = x[1] (axisymmetric about the x-axis,
# the common factor 2π dropped); `axisymmetric` is a Constant 0/1 so one
# kernel serves both. In the axisymmetric case the divergence of T is the
# cylindrical one for swirl-free flow: r (∇·T) = r div_xr(T) + T[:, r].
# The source term is integrated by parts once: ∫ ∂i∂j T_ij q = −∫ ∂j T_ij ∂i q
# (boundary term dropped: T = 0 on the boundary where χ vanishes, and v = 0
# on walls).
import ufl
from ufl import as_vector, div, dot, ds, dx, grad, inner, outer, pi, cos

from fsai_ufl import cell, degree, dim, domain, interpolation_points

mesh = domain()
P = ufl.FiniteElement("Lagrange", mesh.ufl_cell(), degree())
P1v = ufl.VectorElement("Lagrange", mesh.ufl_cell(), 1)
P1 = ufl.FiniteElement("Lagrange", mesh.ufl_cell(), 1)
DG0 = ufl.FiniteElement("DG", mesh.ufl_cell(), 0)

V = ufl.FunctionSpace(mesh, P)
p = ufl.TrialFunction(V)
q = ufl.TestFunction(V)

c0 = ufl.Constant(mesh)            # speed of sound [m/s]
rho0 = ufl.Constant(mesh)          # air density [kg/m³]
axisymmetric = ufl.Constant(mesh)  # 1: weight by r = x[1]; 0: planar/3D
beta = ufl.Constant(mesh)          # curvature term of the radiation condition [1/m]

sigma = ufl.Coefficient(ufl.FunctionSpace(mesh, DG0))   # layer damping [1/s]
v = ufl.Coefficient(ufl.FunctionSpace(mesh, P1v))       # flow velocity [m/s]
taper = ufl.Coefficient(ufl.FunctionSpace(mesh, P1))    # χ of the source
a_wall = ufl.Coefficient(ufl.FunctionSpace(mesh, P1v))  # wall acceleration [m/s²]

x = ufl.SpatialCoordinate(mesh)
n = ufl.FacetNormal(mesh)
w = (1 - axisymmetric) + axisymmetric * x[1]

m = (1 / c0**2) * p * q * w * dx
c = (1 / c0) * p * q * w * ds(1) + (2 * sigma / c0**2) * p * q * w * dx
k = (inner(grad(p), grad(q)) * w * dx + beta * p * q * w * ds(1)
     + (sigma**2 / c0**2) * p * q * w * dx)

# source_scale (DG0) is 1 except in a glottal slit (below), where
# Lighthill's force ∇·T either enters the slit's momentum law beside ∇p'
# (scaled by κ like it) or is left out
source_scale = ufl.Coefficient(ufl.FunctionSpace(mesh, DG0))
T = taper * rho0 * outer(v, v)
divT_w = w * div(T) + axisymmetric * as_vector([T[i, 1] for i in range(dim())])
L_source = -source_scale * inner(divT_w, grad(q)) * dx
L_wall = -rho0 * dot(a_wall, n) * q * w * ds(1)
b_inlet = rho0 * q * w * ds(1)

# Glottal slit (dx(1) bound at run time to its cells): the acoustic domain
# is fixed with the glottis at rest, so in the cells under the fold the
# momentum balance is that of the flow's actual slit rather than air at
# rest (docs/model.md E14 with a local momentum law):
#   ρ' ∂v/∂t + r' v = −∇p',
# ρ' = ρ0 g0/g (the inertance of a slit g/g0 as wide as the mesh's) and r'
# = (g0/g) r, r the slit's resistance per unit length (viscous and the
# jet's kinetic loss; Flanagan's glottal impedance, distributed). The
# continuity equation is unchanged, so in the weak form the slit cells'
# ∫ ∇p·∇q becomes −ρ0 ∫ ∂v/∂t·∇q; with v by backward Euler per cell
# (L-stable: r'Δt/ρ' ≫ 1 when the fold closes),
#   v_{n+1} = (ρ'/Δt v_n − ∇p_{n+1}) / (ρ'/Δt + r'),
#   −ρ0 ∂v/∂t = κ (∇p_{n+1} + r' v_n),   κ = 1 / (ρ'/ρ0 + r'Δt/ρ0)
# (and κ ∇·T for Lighthill's force if it is kept there, L_source):
# the stiffness of the slit cells scaled by κ (k_section: the change from
# κ = 1, added to K and, times βΔt², to the Newmark matrix), and the load
# L_section from the slit's velocity (slit_flux = κ r' v_n). ρ' = ρ0,
# r' = 0 is the plain equation (κ = 1, no load); r' → ∞ closes the slit.
# The compliance (mass term) keeps the mesh's volume: the fold's volume
# displacement enters through the vibrating wall as before.
DG0v = ufl.VectorElement("DG", mesh.ufl_cell(), 0)
kappa = ufl.Coefficient(ufl.FunctionSpace(mesh, DG0))  # slit stiffness scale κ
slit_flux = ufl.Coefficient(ufl.FunctionSpace(mesh, DG0v))  # κ r' v_n [Pa/m]
k_section = (kappa - 1) * inner(grad(p), grad(q)) * w * dx(1)
L_section = -inner(slit_flux, grad(q)) * w * dx(1)

# Weighted measure of the facets bound to ds(1) (inlet area / 2π, or width)
one = ufl.Constant(mesh)
boundary_measure = one * w * ds(1)

# Verification (closed rigid box (0,1)^d): the standing mode
#   p_e = cos(ω t) ∏ cos(π x_i),  ω = c0 π sqrt(d),
# solves E14 with ∂p/∂n = 0 and no source; e² = ∫ (p_h − p_e)² dx.
ph = ufl.Coefficient(V)
t_exact = ufl.Constant(mesh)
p_exact = cos(c0 * pi * dim() ** 0.5 * t_exact)
for i in range(dim()):
    p_exact = p_exact * cos(pi * x[i])
error_L2 = (ph - p_exact) ** 2 * dx(metadata={"quadrature_degree": 2 * degree() + 4})

forms = [m, c, k, L_source, L_wall, b_inlet, boundary_measure, error_L2,
         k_section, L_section]
