# Concrete that cracks (cpp/bulk/CrackBand.h, cpp/model/BulkCracking.h;
# docs/cracking.md): the crack band's stress and tangent enter the bulk at
# the quadrature points of the concrete that may crack, as coefficients of a
# Quadrature element (point values, no interpolation).
#
# The linear bulk K of forms/elasticity.py stays assembled once (its
# cracking cells at these forms' points: a_rule below); these forms add
# what cracking changes, where it changes it:
#
#   f_crack(v) = int (sigma - C : eps_e) : eps(v) dx
#   a_crack(u, v) = int eps(u) : (C_t - C) : eps(v) dx
#
# sigma and C_t the crack band's stress and consistent tangent at the point,
# eps_e = eps(u) - alpha dT I the strain that the stress works on (the
# thermal strain of the retraction is free, as in forms/elasticity.py). Both
# differences are exactly zero at a point that has not cracked, so uncracked
# concrete costs nothing and K keeps its meaning.
#
# Voigt order as in cpp/bulk/Voigt.h: stress [xx, yy, zz, yz, xz, xy],
# strain [xx, yy, zz, 2 yz, 2 xz, 2 xy].
#
# The points: basix's default rule of degree 2 on the hexahedron (2 x 2 x 2
# Gauss-Jacobi), the same rule for the Quadrature element's values, for the
# integrals (metadata below) and for the expressions that evaluate the
# strain and the position there, so that value i of a cell is at point i.
#
# Units: mm, N, MPa. Compiled by FFCx at build time (see CMakeLists.txt).
import basix
from ufl import (Coefficient, Constant, FiniteElement, FunctionSpace, Identity, Mesh,
                 SpatialCoordinate, TensorElement, TestFunction, TrialFunction,
                 VectorElement, as_matrix, as_vector, dot, dx, grad, hexahedron, inner,
                 sym, tr)

DEGREE = 2  # of the quadrature rule
coordinate_element = VectorElement("Lagrange", hexahedron, 1)
mesh = Mesh(coordinate_element)

V = FunctionSpace(mesh, VectorElement("Lagrange", hexahedron, 1))
Q = FunctionSpace(mesh, FiniteElement("DG", hexahedron, 0))
S = FunctionSpace(mesh, VectorElement("Quadrature", hexahedron, DEGREE, dim=6,
                                      quad_scheme="default"))
T = FunctionSpace(mesh, VectorElement("Quadrature", hexahedron, DEGREE, dim=36,
                                      quad_scheme="default"))
P = FunctionSpace(mesh, FiniteElement("Quadrature", hexahedron, DEGREE, quad_scheme="default"))

d_sigma = Coefficient(S)  # sigma - C : eps_e at the points [MPa]
d_C = Coefficient(T)      # C_t - C at the points, 6 x 6 row-major [MPa]
alpha = Coefficient(Q)    # thermal expansion coefficient per cell [1/degC]
dT = Constant(mesh)       # temperature change of the thermal step [degC]
u_h = Coefficient(V)      # displacement [mm]
point_value = Coefficient(P)  # a value per point, to integrate (the energy dissipated per volume)

u = TrialFunction(V)
v = TestFunction(V)


def voigt_strain(w):
    """eps(w) in Voigt order with engineering shears."""
    e = sym(grad(w))
    return as_vector([e[0, 0], e[1, 1], e[2, 2], 2 * e[1, 2], 2 * e[0, 2], 2 * e[0, 1]])


# Over the cracking cells only: tagged REGION by cpp/model/BulkCracking.cpp.
REGION = 1
at_points = dx(REGION, metadata={"quadrature_degree": DEGREE, "quadrature_rule": "default"})
d_C_matrix = as_matrix([[d_C[6 * i + j] for j in range(6)] for i in range(6)])

# L_crack also gives the gradient of the energy the cracks release
# (dissipation control), with d_sigma its density per point.
L_crack = inner(d_sigma, voigt_strain(v)) * at_points
a_crack = inner(dot(d_C_matrix, voigt_strain(u)), voigt_strain(v)) * at_points
# The integral of a value per point: the energy the concrete's cracks
# dissipated or release [N mm].
M_points = point_value * at_points

# The stiffness of the cracking cells at these points. forms/elasticity.py
# integrates K with FFCx's own rule (3 x 3 x 3 points), a_crack takes C
# away at the 2 x 2 x 2 points: on a hexahedron that is not a
# parallelepiped the two rules differ (by some 2e-4 of a cell's stiffness),
# so a crack whose band lost its stiffness would keep that much of C.
# K + a_rule integrates the cracking cells at the points where the crack
# band answers (cpp/model/BulkCracking.h, add_elastic_rule). in_K has no
# metadata and the integrand of elasticity.py's a, so FFCx picks it a's
# rule. The thermal load needs no such change: its integrand, a constant
# stress against eps(v) times the Jacobian's determinant, is a polynomial
# that both rules integrate exactly.
E_c = Constant(mesh)   # the concrete's Young's modulus [MPa]
nu_c = Constant(mesh)  # the concrete's Poisson's ratio [-]


def hooke(eps):
    """The concrete's C : eps [MPa] (as forms/elasticity.py's sigma)."""
    lmbda = E_c * nu_c / ((1 + nu_c) * (1 - 2 * nu_c))
    mu = E_c / (2 * (1 + nu_c))
    return lmbda * tr(eps) * Identity(3) + 2 * mu * eps


in_K = dx(REGION)
a_rule = (inner(hooke(sym(grad(u))), sym(grad(v))) * at_points
          - inner(hooke(sym(grad(u))), sym(grad(v))) * in_K)

points, _ = basix.make_quadrature(basix.CellType.hexahedron, DEGREE)
strain = voigt_strain(u_h) - alpha * dT * as_vector([1.0, 1.0, 1.0, 0.0, 0.0, 0.0])
position = SpatialCoordinate(mesh)

# The cracks' share of the cell-averaged stress that fields.xdmf writes
# (cpp/output/StressProjection.cpp, with forms/elasticity.py's L_stress: the
# elastic C : eps_e): d_sigma as a tensor against the DG0 tensor test
# function of that projection.
S_cell = FunctionSpace(mesh, TensorElement("DG", hexahedron, 0))
tau = TestFunction(S_cell)
d_sigma_tensor = as_matrix([[d_sigma[0], d_sigma[5], d_sigma[4]],
                            [d_sigma[5], d_sigma[1], d_sigma[3]],
                            [d_sigma[4], d_sigma[3], d_sigma[2]]])
L_stress_crack = inner(d_sigma_tensor, tau) * at_points

forms = [L_crack, a_crack, M_points, L_stress_crack, a_rule]
expressions = [(strain, points), (position, points)]
