# Poisson problem with a manufactured solution: the forms-pipeline check.
#
# Strong form:  -Δu = f in Ω = (0,1)^d,  u = u_e on ∂Ω,
#   u_e(x) = exp(x_0) ∏_{i>0} sin(π x_i) + x_0,   f = -Δu_e (UFL derivative).
# Weak form:    find u_h ∈ V_g: (∇u_h, ∇v) = (f, v)  for all v ∈ V_0.
# Error functional: e² = ∫ (u_h - u_e)² dx, with a quadrature rule
# well above the polynomial degree so the exact solution is resolved.
# The exact solution is also compiled as an Expression at the element's
# interpolation points, for the boundary values.
import ufl
from ufl import dx, exp, grad, inner, pi, sin, div

from fsai_ufl import degree, dim, domain, interpolation_points

mesh = domain()
element = ufl.FiniteElement("Lagrange", mesh.ufl_cell(), degree())
V = ufl.FunctionSpace(mesh, element)

u = ufl.TrialFunction(V)
v = ufl.TestFunction(V)
uh = ufl.Coefficient(V)

x = ufl.SpatialCoordinate(mesh)
u_exact = exp(x[0])
for i in range(1, dim()):
    u_exact = u_exact * sin(pi * x[i])
u_exact = u_exact + x[0]
f = -div(grad(u_exact))

a = inner(grad(u), grad(v)) * dx
L = f * v * dx
error_L2 = (uh - u_exact) ** 2 * dx(metadata={"quadrature_degree": 2 * degree() + 4})

forms = [a, L, error_L2]
expressions = [(u_exact, interpolation_points())]
