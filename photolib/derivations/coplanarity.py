"""The coplanarity condition and relative orientation: Chapter 2, §2.7–§2.8.

* :func:`coplanarity_expression` — φ of (2.7.3) with all eight parameters;
  :func:`coplanarity_model` — the condition in the independent (2.7.4) or dependent (2.7.5) system.
* The book's printed derivatives of §2.8 (:func:`printed_relative_orientation_partials`,
  :func:`printed_ray_partials`, :func:`printed_coplanarity_partials`) and the numpy function of
  the printed coefficients for the "as printed" mode of
  :func:`photolib.image_pair.relative_orientation` (:func:`printed_coplanarity_jacobian`).
"""

from __future__ import annotations

from functools import lru_cache

import sympy as sp

from ..errors import InputError
from ..rotation import check_order
from .model import Model, _printed_function
from .rotation import rotation_matrix_symbolic
from .symbols import alpha1, alpha2, b_y, b_z, f1, f2, kappa1, kappa2, omega1, omega2, x1, x2, y1, y2

__all__ = ["RELATIVE_ORIENTATION_SYSTEMS", "RELATIVE_ORIENTATION_PARAMETERS", "coplanarity_expression",
           "coplanarity_model", "coplanarity_all_parameters_model", "printed_relative_orientation_partials",
           "derived_relative_orientation_partials", "printed_ray_partials", "printed_coplanarity_partials",
           "printed_coplanarity_jacobian"]

RELATIVE_ORIENTATION_SYSTEMS = {
    # α'1 κ'1 ω'2 α'2 κ'2 with b_y = b_z = ω'1 = 0: condition (2.7.4)
    "independent": (alpha1, kappa1, omega2, alpha2, kappa2),
    # b_y b_z ω'2 α'2 κ'2 with ω'1 = α'1 = κ'1 = 0 (A'1 = E): condition (2.7.5)
    "dependent": (b_y, b_z, omega2, alpha2, kappa2),
}
"""The two systems of relative-orientation elements of §2.7 and their unknowns."""

RELATIVE_ORIENTATION_PARAMETERS = (b_y, b_z, omega1, alpha1, kappa1, omega2, alpha2, kappa2)
"""All eight parameters of the coplanarity condition (2.7.3); a system fixes three of them to 0."""


def _check_system(system):
    if not isinstance(system, str) or system not in RELATIVE_ORIENTATION_SYSTEMS:
        raise InputError(f"unknown system {system!r}; use 'independent' or 'dependent'")
    return system


def coplanarity_expression(order: str = "kaw"):
    """φ of (2.7.3): det[[1, b_y, b_z], [X'₁, Y'₁, Z'₁], [X'₂, Y'₂, Z'₂]] with all eight parameters.

    (X'ᵢ, Y'ᵢ, Z'ᵢ)ᵀ = A'ᵢ (xᵢ, yᵢ, −fᵢ)ᵀ, A'ᵢ = A(ω'ᵢ, α'ᵢ, κ'ᵢ) of the rotation sequence ``order``.

    Parameters
    ----------
    order : {"kaw", "wak"}, optional
        Rotation sequence of A'₁, A'₂.

    Returns
    -------
    sympy.Expr
        φ in :data:`RELATIVE_ORIENTATION_PARAMETERS` and x₁, y₁, f₁, x₂, y₂, f₂.

    Raises
    ------
    InputError
        If ``order`` is unknown.

    References
    ----------
    Chibunichev (2022), §2.7, eq. (2.7.3).

    Examples
    --------
    >>> from photolib.derivations import RELATIVE_ORIENTATION_PARAMETERS as P
    >>> coplanarity_expression("kaw").subs({p: 0 for p in P})
    f_1*y_2 - f_2*y_1
    """
    r1 = rotation_matrix_symbolic(order, omega1, alpha1, kappa1) * sp.Matrix([x1, y1, -f1])
    r2 = rotation_matrix_symbolic(order, omega2, alpha2, kappa2) * sp.Matrix([x2, y2, -f2])
    return sp.Matrix([[1, b_y, b_z], [r1[0], r1[1], r1[2]], [r2[0], r2[1], r2[2]]]).det(method="berkowitz")


@lru_cache(maxsize=None)
def coplanarity_model(system: str = "dependent", order: str = "kaw") -> Model:
    """The relative-orientation condition (2.7.3) in one of the two systems of §2.7.

    ``"independent"``: unknowns α'₁, κ'₁, ω'₂, α'₂, κ'₂, with b_y = b_z = ω'₁ = 0 — (2.7.4).
    ``"dependent"``: unknowns b_y, b_z, ω'₂, α'₂, κ'₂, with A'₁ = E — (2.7.5).

    Parameters
    ----------
    system : {"dependent", "independent"}, optional
        The system of relative-orientation elements.
    order : {"kaw", "wak"}, optional
        Rotation sequence.

    Returns
    -------
    Model
        Data: reduced image coordinates and focal lengths (x₁, y₁, f₁, x₂, y₂, f₂). The rows of B
        are the coefficients a₁…a₅ of the correction equation (2.8.1), derived by sympy.

    Raises
    ------
    InputError
        If ``system`` or ``order`` is unknown.

    References
    ----------
    Chibunichev (2022), §2.7, eqs. (2.7.3)–(2.7.5); §2.8, eq. (2.8.1).

    Examples
    --------
    >>> m = coplanarity_model("dependent", "kaw")
    >>> [str(p) for p in m.parameters]
    ['b_y', 'b_z', 'omega_2', 'alpha_2', 'kappa_2']
    """
    check_order(order)
    unknowns = RELATIVE_ORIENTATION_SYSTEMS[_check_system(system)]
    fixed = {p: 0 for p in RELATIVE_ORIENTATION_PARAMETERS if p not in unknowns}
    phi = coplanarity_expression(order).subs(fixed)
    return Model(f"coplanarity-{system}-{order}", unknowns, (x1, y1, f1, x2, y2, f2), (phi,))


@lru_cache(maxsize=None)
def coplanarity_all_parameters_model(order: str = "kaw") -> Model:
    """The coplanarity condition (2.7.3) with all eight parameters unknown (none fixed).

    Its Jacobian has rank 5 at a generic pair (§2.6–§2.7: three of the eight parameters only
    turn the model frame); the book layer counts the elements of relative orientation with it.

    Parameters
    ----------
    order : {"kaw", "wak"}, optional
        Rotation sequence of A'₁, A'₂.

    Returns
    -------
    Model
        Parameters :data:`RELATIVE_ORIENTATION_PARAMETERS`; data x₁, y₁, f₁, x₂, y₂, f₂.

    Raises
    ------
    InputError
        If ``order`` is unknown.

    References
    ----------
    Chibunichev (2022), §2.6–§2.7, eq. (2.7.3).

    Examples
    --------
    >>> m = coplanarity_all_parameters_model("kaw")
    >>> len(m.parameters), m.name
    (8, 'coplanarity-all-8')
    """
    check_order(order)
    return Model("coplanarity-all-8", RELATIVE_ORIENTATION_PARAMETERS, (x1, y1, f1, x2, y2, f2),
                 (coplanarity_expression(order),))


def printed_relative_orientation_partials() -> dict:
    """∂X'₂/∂θ, ∂Y'₂/∂θ, ∂Z'₂/∂θ (θ = ω'₂, α'₂, κ'₂) as printed in §2.8 (seed lines 1361–1368).

    The OCR repeats fragments such as "+ y₂ sin ω₂ sin ω₂ …"; these are dropped and the
    remaining terms kept as printed. x, y, f carry the index 2 (symbols ``x_2, y_2, f_2``). They
    equal ∂A/∂θ·(x₂, y₂, **+f₂**)ᵀ for the κ–α–ω matrix (1.3.5), i.e. every f-term has the wrong
    sign for the book's ray (x₂, y₂, −f₂): compare :func:`derived_relative_orientation_partials`.

    Returns
    -------
    dict
        Keys ``("X", "omega")``, ``("Y", "alpha")`` … (nine), values sympy expressions.

    Raises
    ------
    InputError
        Never (no input).

    References
    ----------
    Chibunichev (2022), §2.8, the derivatives after (2.8.1).

    Examples
    --------
    >>> import sympy as sp
    >>> printed = printed_relative_orientation_partials()
    >>> derived = derived_relative_orientation_partials("kaw", z_sign=+1)
    >>> all(sp.expand(printed[k] - derived[k]) == 0 for k in printed)
    True
    """
    c, s = sp.cos, sp.sin
    w, a, k, xx, yy, ff = omega2, alpha2, kappa2, x2, y2, f2
    return {
        ("X", "omega"): yy * c(k) * s(a) * c(w) + yy * s(k) * s(w) + ff * c(w) * s(k) - ff * s(w) * s(a) * c(k),
        ("Y", "omega"): yy * c(w) * s(a) * s(k) - yy * c(k) * s(w) - ff * c(w) * c(k) - ff * s(w) * s(a) * s(k),
        ("Z", "omega"): yy * c(w) * c(a) - ff * s(w) * c(a),
        ("X", "alpha"): -xx * c(k) * s(a) + yy * c(k) * c(a) * s(w) + ff * c(w) * c(a) * c(k),
        ("Y", "alpha"): -xx * s(k) * s(a) + yy * s(w) * c(a) * s(k) + ff * c(w) * c(a) * s(k),
        ("Z", "alpha"): -xx * c(a) - yy * s(w) * s(a) - ff * c(w) * s(a),
        ("X", "kappa"): -xx * s(k) * c(a) - yy * s(k) * s(a) * s(w) - yy * c(k) * c(w)
                        + ff * s(w) * c(k) - ff * c(w) * s(a) * s(k),
        ("Y", "kappa"): xx * c(k) * c(a) + yy * s(w) * s(a) * c(k) - yy * s(k) * c(w)
                        + ff * s(w) * s(k) + ff * c(w) * s(a) * c(k),
        ("Z", "kappa"): sp.Integer(0),
    }


def derived_relative_orientation_partials(order: str = "kaw", z_sign: int = -1) -> dict:
    """∂(A'₂ r₂)/∂θ derived by sympy, r₂ = (x₂, y₂, z_sign·f₂); the book's ray has z_sign = −1 (2.7.3).

    Parameters
    ----------
    order : {"kaw", "wak"}, optional
        Rotation sequence of A'₂.
    z_sign : {-1, 1}, optional
        Sign of the third component of the ray (−1: the book's (x₂, y₂, −f₂)).

    Returns
    -------
    dict
        Keys like :func:`printed_relative_orientation_partials`.

    Raises
    ------
    InputError
        If ``order`` is unknown or ``z_sign`` is not ±1.

    References
    ----------
    Chibunichev (2022), §2.7, eq. (2.7.3); §2.8.

    Examples
    --------
    >>> derived_relative_orientation_partials("kaw")[("Z", "kappa")]
    0
    """
    if z_sign not in (-1, 1) or isinstance(z_sign, bool):
        raise InputError(f"z_sign must be -1 or +1, got {z_sign!r}")
    A = rotation_matrix_symbolic(order, omega2, alpha2, kappa2)
    r = A * sp.Matrix([x2, y2, z_sign * f2])
    return {(C, name): sp.diff(r[i], th) for i, C in enumerate("XYZ")
            for name, th in (("omega", omega2), ("alpha", alpha2), ("kappa", kappa2))}


# --- as-printed derivatives: the "as printed" mode of relative orientation -----------------------
_IMAGE1_SUBS = {omega2: omega1, alpha2: alpha1, kappa2: kappa1, x2: x1, y2: y1, f2: f1}
_RO_ANGLE_OF = {omega1: (1, "omega"), alpha1: (1, "alpha"), kappa1: (1, "kappa"),
                omega2: (2, "omega"), alpha2: (2, "alpha"), kappa2: (2, "kappa")}


def printed_ray_partials(image: int = 2) -> dict:
    """The printed ∂X'ᵢ/∂θ, ∂Y'ᵢ/∂θ, ∂Z'ᵢ/∂θ of §2.8 for image 1 or 2.

    The book prints them for image 2 only (seed lines 1361–1368); its worked example also
    solves for α'₁, κ'₁, and its program evidently used the same expressions with the index 1
    (which is what reproduces the published accuracy).

    Parameters
    ----------
    image : {1, 2}, optional
        The image whose derivatives are wanted.

    Returns
    -------
    dict
        Keys as in :func:`printed_relative_orientation_partials`.

    Raises
    ------
    InputError
        If ``image`` is not 1 or 2.

    References
    ----------
    Chibunichev (2022), §2.8, the derivatives after (2.8.1).

    Examples
    --------
    >>> printed_ray_partials(1)[("Z", "omega")]
    -f_1*sin(omega_1)*cos(alpha_1) + y_1*cos(alpha_1)*cos(omega_1)
    """
    if isinstance(image, bool) or image not in (1, 2):
        raise InputError(f"image must be 1 or 2, got {image!r}")
    printed = printed_relative_orientation_partials()
    if image == 2:
        return printed
    return {k: sp.sympify(v).xreplace(_IMAGE1_SUBS) for k, v in printed.items()}


def printed_coplanarity_partials(system: str = "independent") -> tuple:
    """The coefficients a₁…a₅ of (2.8.1) as the book computes them, for a system of §2.7.

    a for b_y, b_z: the printed determinants (they equal the sympy derivatives); a for an angle θ
    of image i: the determinant (2.7.3) with the row of image i replaced by the printed
    (∂X'ᵢ/∂θ, ∂Y'ᵢ/∂θ, ∂Z'ᵢ/∂θ) of :func:`printed_ray_partials`. κ–α–ω matrix (1.3.5) only.
    The fixed parameters of the system are substituted by 0.

    Parameters
    ----------
    system : {"independent", "dependent"}, optional
        The system of relative-orientation elements.

    Returns
    -------
    tuple of sympy.Expr
        a₁…a₅ in the order of the system's unknowns.

    Raises
    ------
    InputError
        If ``system`` is unknown.

    References
    ----------
    Chibunichev (2022), §2.8, eq. (2.8.1).

    Examples
    --------
    >>> len(printed_coplanarity_partials("dependent"))
    5
    """
    unknowns = RELATIVE_ORIENTATION_SYSTEMS[_check_system(system)]
    fixed = {p: 0 for p in RELATIVE_ORIENTATION_PARAMETERS if p not in unknowns}
    r1 = rotation_matrix_symbolic("kaw", omega1, alpha1, kappa1) * sp.Matrix([x1, y1, -f1])
    r2 = rotation_matrix_symbolic("kaw", omega2, alpha2, kappa2) * sp.Matrix([x2, y2, -f2])
    rows = [sp.Matrix([[1, b_y, b_z]]), r1.T, r2.T]
    phi = sp.Matrix.vstack(*rows).det(method="berkowitz")
    coefficients = []
    for p in unknowns:
        if p in (b_y, b_z):
            coefficients.append(sp.diff(phi, p))
            continue
        image, name = _RO_ANGLE_OF[p]
        partial = printed_ray_partials(image)
        drow = sp.Matrix([[partial[(C, name)] for C in "XYZ"]])
        M = list(rows)
        M[image] = drow
        coefficients.append(sp.Matrix.vstack(*M).det(method="berkowitz"))
    return tuple(sp.sympify(c).subs(fixed) for c in coefficients)


def _printed_coplanarity_build(system):
    unknowns = RELATIVE_ORIENTATION_SYSTEMS[system]
    return list(unknowns) + [x1, y1, f1, x2, y2, f2], list(printed_coplanarity_partials(system)), 5


@lru_cache(maxsize=None)
def printed_coplanarity_jacobian(system: str = "independent"):
    """Numpy function of ``(*unknowns, x₁, y₁, f₁, x₂, y₂, f₂)`` giving the printed a₁…a₅, shape (5, n).

    Parameters
    ----------
    system : {"independent", "dependent"}, optional
        The system of relative-orientation elements.

    Returns
    -------
    callable
        Returns an array of shape (5, n).

    Raises
    ------
    InputError
        If ``system`` is unknown.

    References
    ----------
    Chibunichev (2022), §2.8, eq. (2.8.1).

    Examples
    --------
    >>> jac = printed_coplanarity_jacobian("independent")
    >>> jac(0, 0, 0, 0, 0, 1.0, 2.0, 100.0, -80.0, 2.0, 100.0).shape
    (5,)
    """
    _check_system(system)
    return _printed_function(f"printed-coplanarity-{system}", lambda: _printed_coplanarity_build(system))
