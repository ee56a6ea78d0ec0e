"""Shared UFL helpers for fsai form files.

Every form file is compiled by FFCx once per *variant* (cell type x polynomial
degree). CMake generates a small wrapper per variant (see
cmake/ffcx_variant.py.in) that calls `set_variant` and then executes the form
file, so one UFL source serves triangles and tetrahedra, P1 and P2.
"""

import basix
import ufl

_variant = {"cell": None, "degree": None}


def set_variant(cell, degree):
    """Select the cell name ('triangle', 'tetrahedron') and degree."""
    _variant["cell"] = cell
    _variant["degree"] = int(degree)


def _get(key):
    value = _variant[key]
    if value is None:
        raise RuntimeError("fsai_ufl: variant not set; compile form files "
                           "through the CMake helper fsai_add_form")
    return value


def cell():
    """The UFL cell of the current variant."""
    return ufl.Cell(_get("cell"))


def dim():
    """Geometric (= topological) dimension of the current variant."""
    return cell().geometric_dimension()


def degree():
    """Polynomial degree of the current variant."""
    return _get("degree")


def domain():
    """Affine (P1 geometry) mesh of the current cell."""
    return ufl.Mesh(ufl.VectorElement("Lagrange", cell(), 1))


def interpolation_points(deg=None):
    """Reference points at which a Lagrange element of degree `deg` (default:
    the variant's degree) interpolates; used for `expressions = [...]`."""
    deg = degree() if deg is None else deg
    celltype = {"triangle": basix.CellType.triangle,
                "tetrahedron": basix.CellType.tetrahedron}[_get("cell")]
    # FFCx 0.5 maps ufl "Lagrange" to basix's GLL-warped variant
    element = basix.create_element(basix.ElementFamily.P, celltype, deg,
                                   basix.LagrangeVariant.gll_warped)
    return element.points
