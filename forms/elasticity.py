# Bulk elasticity of the steel tube and the concrete slice (paper §4.1):
# small-strain, linear elastic, isotropic, with a thermal strain alpha*dT
# that models the retraction (shrinkage) of the concrete (paper §4.2).
#
# Units: mm, N, MPa. Compiled by FFCx at build time (see CMakeLists.txt).
#
# The bulk is linear: the stiffness `a` is assembled once, the thermal load
# `L_thermal` once per thermal step. The interface (joint elements) is not
# here: its forces come from cpp/interface/ (see the comment there for why).
from ufl import (Coefficient, Constant, FiniteElement, FunctionSpace, Identity,
                 Mesh, TensorElement, TestFunction, TrialFunction,
                 VectorElement, dx, grad, hexahedron, inner, sym, tr)

coordinate_element = VectorElement("Lagrange", hexahedron, 1)
mesh = Mesh(coordinate_element)

V = FunctionSpace(mesh, VectorElement("Lagrange", hexahedron, 1))
Q = FunctionSpace(mesh, FiniteElement("DG", hexahedron, 0))
S = FunctionSpace(mesh, TensorElement("DG", hexahedron, 0))

E = Coefficient(Q)      # Young's modulus per cell [MPa] (steel or concrete)
nu = Coefficient(Q)     # Poisson's ratio per cell [-]
alpha = Coefficient(Q)  # thermal expansion coefficient per cell [1/degC]
dT = Constant(mesh)     # temperature change of the thermal step [degC]
u_h = Coefficient(V)    # displacement, for the stress output [mm]

u = TrialFunction(V)
v = TestFunction(V)

lmbda = E * nu / ((1 + nu) * (1 - 2 * nu))  # Lame's first parameter [MPa]
mu = E / (2 * (1 + nu))                     # shear modulus [MPa]


def epsilon(w):
    return sym(grad(w))


def sigma(eps):
    """Hooke's law, isotropic [MPa]."""
    return lmbda * tr(eps) * Identity(3) + 2 * mu * eps


eps_thermal = alpha * dT * Identity(3)

# Stiffness K: K u = f_thermal + interface and support forces.
a = inner(sigma(epsilon(u)), epsilon(v)) * dx
# Equivalent nodal forces of the free thermal strain.
L_thermal = inner(sigma(eps_thermal), epsilon(v)) * dx

# Cell-averaged Cauchy stress for ParaView output [MPa]: the DG0 projection
# is L_stress / L_volume per cell.
stress = sigma(epsilon(u_h) - eps_thermal)
tau = TestFunction(S)
q = TestFunction(Q)
L_stress = inner(stress, tau) * dx
L_volume = q * dx

# The same with a triquadratic displacement (mesh.degree = 2, on the same
# trilinear geometry): a locking check on the trilinear bulk.
V2 = FunctionSpace(mesh, VectorElement("Lagrange", hexahedron, 2))
u2, v2 = TrialFunction(V2), TestFunction(V2)
u_h2 = Coefficient(V2)  # displacement, for the stress output [mm]
a_q2 = inner(sigma(epsilon(u2)), epsilon(v2)) * dx
L_thermal_q2 = inner(sigma(eps_thermal), epsilon(v2)) * dx
L_stress_q2 = inner(sigma(epsilon(u_h2) - eps_thermal), tau) * dx

forms = [a, L_thermal, L_stress, L_volume, a_q2, L_thermal_q2, L_stress_q2]
