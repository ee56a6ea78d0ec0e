# Elastodynamics of the vocal fold and the benchmark solids (docs/model.md
# E1, E4, E6, E7, E16–E18), compiled for triangles (plane strain) and
# tetrahedra, P1 and P2.
#
# Strong form (reference configuration Ω^s):
#   ρ ü + D u̇ − ∇·(F S) = ρ g  in Ω^s,   u = 0 on Γ_D,   (F S)·N = T on Γ_T
# with F = I + ∇u, E = ½(FᵀF − I), S = λ tr(E) I + 2μ E (St.Venant–Kirchhoff,
# E6). `nonlinear` = 0 gives linear elasticity (E = sym ∇u, F S → σ, E16).
# Rayleigh damping D = ε1 M + ε2 K with K the stiffness at the reference
# state (E17).
#
# Newmark (E18): with ũ = u_n + Δt v_n + (½ − β)Δt² a_n and
#   a = (u − ũ)/(βΔt²),  v = v_n + Δt((1 − γ) a_n + γ a),
# the residual for the new displacement u is
#   R(u; w) = d [ (ρ a, w) + ε1 (ρ v, w) + ε2 (σ_lin(v), ∇w) ]
#             + (F S, ∇w) − (ρ g, w) − s (T, w)_Γ_T
#             − (p_c e_y, w)_Γ_T
# with d = 1 (dynamic) or 0 (static; load factor s scales g and T for load
# stepping). J = ∂R/∂u by UFL differentiation.
#
# Generalised-α (Chung–Hulbert, E18a): the inertia at t_{n+1−αm} and every
# other force at t_{n+1−αf}, x_{n+1−α} = (1 − α) x_{n+1} + α x_n, with
# a_n, v_n, u_n and the previous step's traction T_n; αm = αf = 0 is
# Newmark. Static solves (d = 0) take αf = 0.
#
# Contact with the plane y = y_c (the symmetry axis of the glottis scene,
# where the two folds meet): a penalty pressure on the loaded boundary
#   p_c = k_c δ max(0, 1 + b_c δ̇ d),   δ = max(0, y_c − (X_y + u_y)),
# δ̇ = −v_y (Hunt–Crossley damping, never adhesive). It is part of R, so
# Newton treats the contact implicitly; k_c = 0 (the default) removes it.
#
# Materials are cell-wise (DG0 λ, μ, ρ), so layered folds (body/cover) need
# no extra forms.
#
# Clamped section (2D only; kz2 = 0 is plane strain): a fold of length L
# clamped at its anterior and posterior ends z = 0, L, reduced to its first
# anterior–posterior harmonic u(x, y, z) = û(x, y) sin(πz/L), u_z = 0. The
# shear strains ε_xz, ε_yz = ½ ∂_z u then add μ (π/L)² |û|² to the strain
# energy density of the section (both energies carry the same factor ½
# from the z-average of sin² and cos²): an elastic foundation
#   + kz2 μ û·w,   kz2 = (π/L)²,
# in the residual, the Rayleigh stiffness term and K. Being a restriction
# of the clamped 3D fold's displacements, its frequencies bound the 3D
# fold's from above (Rayleigh–Ritz); with a uniform μ/ρ it shifts every
# plane-strain mode by ω² → ω² + (μ/ρ)(π/L)². Kept linear in the
# St.Venant–Kirchhoff model.
#
# Modal analysis: K (linear stiffness) and M (mass) as bilinear forms.
import ufl
from ufl import (Identity, derivative, ds, dx, grad, inner, sym, tr)

from fsai_ufl import degree, dim, domain

mesh = domain()
element = ufl.VectorElement("Lagrange", mesh.ufl_cell(), degree())
DG0 = ufl.FiniteElement("DG", mesh.ufl_cell(), 0)
V = ufl.FunctionSpace(mesh, element)
Q = ufl.FunctionSpace(mesh, DG0)

du = ufl.TrialFunction(V)
w = ufl.TestFunction(V)
u = ufl.Coefficient(V)       # unknown displacement at t_{n+1}
u_n = ufl.Coefficient(V)
v_n = ufl.Coefficient(V)
a_n = ufl.Coefficient(V)
traction = ufl.Coefficient(V)  # T on Γ_T (ds(1)) [Pa]
traction_n = ufl.Coefficient(V)  # T at t_n (generalised-α) [Pa]

lmbda = ufl.Coefficient(Q)   # Lamé λ [Pa]
mu = ufl.Coefficient(Q)      # Lamé μ [Pa]
rho = ufl.Coefficient(Q)     # density [kg/m³]

dt = ufl.Constant(mesh)
beta = ufl.Constant(mesh)
gamma = ufl.Constant(mesh)
alpha_m = ufl.Constant(mesh)     # generalised-α weights (0, 0: Newmark)
alpha_f = ufl.Constant(mesh)
eps1 = ufl.Constant(mesh)    # Rayleigh mass coefficient [1/s]
eps2 = ufl.Constant(mesh)    # Rayleigh stiffness coefficient [s]
dynamic = ufl.Constant(mesh)     # 1: Newmark, 0: static
nonlinear = ufl.Constant(mesh)   # 1: St.Venant–Kirchhoff, 0: linear
load = ufl.Constant(mesh)        # load factor s
g = ufl.Constant(mesh, shape=(dim(),))  # body acceleration [m/s²]
k_c = ufl.Constant(mesh)         # contact penalty [Pa/m] (0: no contact)
b_c = ufl.Constant(mesh)         # contact damping [s/m]
y_c = ufl.Constant(mesh)         # contact plane y = y_c [m]
kz2 = ufl.Constant(mesh)         # (π/L)² of a clamped section [1/m²]
X = ufl.SpatialCoordinate(mesh)

I = Identity(dim())


def sigma_lin(x):
    eps = sym(grad(x))
    return lmbda * tr(eps) * I + 2 * mu * eps


def stiffness(x, y):
    """Linear stiffness density of x against y, with the clamped section's
    foundation"""
    return inner(sigma_lin(x), grad(y)) + kz2 * mu * inner(x, y)


# Newmark kinematics
u_tilde = u_n + dt * v_n + (0.5 - beta) * dt**2 * a_n
a = (u - u_tilde) / (beta * dt**2)
v = v_n + dt * ((1 - gamma) * a_n + gamma * a)

# Generalised-α mid-step states (static: the new state itself)
af = alpha_f * dynamic
a_m = (1 - alpha_m) * a + alpha_m * a_n
v_f = (1 - af) * v + af * v_n
u_f = (1 - af) * u + af * u_n
T_f = (1 - af) * traction + af * traction_n

# St.Venant–Kirchhoff first Piola–Kirchhoff stress (linear when nonlinear=0)
H = grad(u_f)
E = sym(H) + nonlinear * 0.5 * H.T * H
S = lmbda * tr(E) * I + 2 * mu * E
P = (I + nonlinear * H) * S

# Contact pressure on the plane y = y_c
delta = ufl.max_value(y_c - (X[1] + u_f[1]), 0.0)
p_c = k_c * delta * ufl.max_value(1.0 + b_c * dynamic * (-v_f[1]), 0.0)

R = (dynamic * (rho * inner(a_m, w) + eps1 * rho * inner(v_f, w)
                + eps2 * stiffness(v_f, w)) * dx
     + (inner(P, grad(w)) + kz2 * mu * inner(u_f, w)) * dx
     - load * rho * inner(g, w) * dx
     - load * inner(T_f, w) * ds(1)
     - p_c * w[1] * ds(1))
J = derivative(R, u, du)

# Total contact force along +y on the loaded boundary (per unit depth in 2D)
contact_force = p_c * ds(1)

# Modal analysis and diagnostics
k = stiffness(du, w) * dx
m = rho * inner(du, w) * dx

forms = [R, J, k, m, contact_force]
