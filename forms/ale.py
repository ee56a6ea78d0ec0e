# ALE mesh motion: the fluid-mesh displacement d as an extension of the
# interface displacement into Ω^f (docs/model.md §3, E13),
# triangles and tetrahedra, P1 (the flow's velocity space, so that the mesh
# velocity w = BDF(d) lives where the flow needs it).
#
# Solved on the reference configuration Ω^f_0 (x = X + d, no drift):
#   harmonic (elastic = 0):       (k ∇d, ∇z) = 0
#   pseudo-elastic (elastic = 1): (k [2 ε(d) : ε(z) + λ_m (∇·d)(∇·z)]) = 0
# with d given on the interface, zero on fixed walls, one component zero on
# slip lines (symmetry axis). k is a cell-wise stiffening coefficient,
#   k_K = (V_max / V_K)^χ,  V_K the reference cell volume
# (Jacobian-based stiffening, Stein, Tezduyar & Benney 2003): χ = 0 is the
# plain extension; χ > 0 makes small cells — those packed in the glottal gap
# and along the fold — stiffer, so they move almost rigidly and the large
# cells away from the gap take up the deformation. The stiffening is
# computed in C++ (src/ale/MeshMotion) and passed as a DG0 coefficient.
import ufl
from ufl import div, dx, grad, inner, sym

from fsai_ufl import dim, domain

mesh = domain()
V = ufl.FunctionSpace(mesh, ufl.VectorElement("Lagrange", mesh.ufl_cell(), 1))
Q = ufl.FunctionSpace(mesh, ufl.FiniteElement("DG", mesh.ufl_cell(), 0))

d = ufl.TrialFunction(V)
z = ufl.TestFunction(V)
k = ufl.Coefficient(Q)          # stiffening coefficient (≥ 1)
elastic = ufl.Constant(mesh)    # 0: harmonic, 1: pseudo-elastic
lmbda = ufl.Constant(mesh)      # λ_m / μ_m of the pseudo-elastic medium

a = k * ((1 - elastic) * inner(grad(d), grad(z))
         + elastic * (2 * inner(sym(grad(d)), sym(grad(z)))
                      + lmbda * div(d) * div(z))) * dx

# Lumped interface mass ∫_Γ z_k ds (ds(1) bound to the interface facets):
# nodal forces / lumped mass = the nodal traction handed to the solid
e = ufl.Constant(mesh, shape=(dim(),))
lumped = inner(e, z) * ufl.ds(1)

forms = [a, lumped]
