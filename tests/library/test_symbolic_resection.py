"""sympy checks of §1.8 (1.8.3) and §1.9 partial derivatives: printed vs derived, term by term."""

import numpy as np
import pytest
import sympy as sp

from photolib import derivations as d

# Book statuses (textbook fragment): of the twelve printed coefficients only b4 is right.
AGREE = {"b4"}


def _point(seed):
    """A random rational point in general position (x0 = y0 = 0, the book's setting)."""
    rng = np.random.default_rng(seed)
    vals = {d.Xs: rng.uniform(-50, 50), d.Ys: rng.uniform(-50, 50), d.Zs: rng.uniform(800, 1200),
            d.omega: rng.uniform(-0.4, 0.4), d.alpha: rng.uniform(-0.4, 0.4), d.kappa: rng.uniform(-3, 3),
            d.X: rng.uniform(-400, 400), d.Y: rng.uniform(-400, 400), d.Z: rng.uniform(0, 200),
            d.f: rng.uniform(50, 200), d.x0: 0, d.y0: 0, d.x: 0, d.y: 0}
    return {k: sp.Rational(v).limit_denominator(10 ** 6) for k, v in vals.items()}


@pytest.mark.parametrize("name", d.RESECTION_COEFFICIENTS)
def test_printed_coefficient_status(name):
    """Evaluated by sympy at exact rational points: equal everywhere (b4) or different somewhere."""
    printed = d.printed_resection_partials()[name]
    derived = d.derived_resection_partials("kaw")[name]
    diffs = [abs(float((printed - derived).subs(_point(s)).evalf(30))) for s in range(3)]
    scale = abs(float(derived.subs(_point(0)).evalf(30)))
    if name in AGREE:
        assert max(diffs) < 1e-20 * max(scale, 1)
        assert sp.simplify((printed - derived).subs({d.x0: 0, d.y0: 0})) == 0
    else:
        assert max(diffs) > 1e-6 * scale


def _corrected():
    """The corrected coefficients, typed from the derivation ∂F/∂p = −(f X*_p + ξ Z*_p)/Z* (kaw)."""
    A = d.rotation_matrix_symbolic("kaw")
    a = lambda i, j: A[i - 1, j - 1]  # noqa: E731
    Xst, Yst, Zst = d.collinearity_terms("kaw")
    xi, eta = -d.f * Xst / Zst, -d.f * Yst / Zst            # x′ − x0, y′ − y0
    dX, dY, dZ = d.X - d.Xs, d.Y - d.Ys, d.Z - d.Zs
    c, s, w, al, k, f = sp.cos, sp.sin, d.omega, d.alpha, d.kappa, d.f
    h = dX * c(k) + dY * s(k)
    return {
        "a1": (f * a(1, 1) + a(1, 3) * xi) / Zst, "a2": (f * a(2, 1) + a(2, 3) * xi) / Zst,
        "a3": (f * a(3, 1) + a(3, 3) * xi) / Zst, "a4": xi / Zst * (a(1, 2) * dX + a(2, 2) * dY + a(3, 2) * dZ),
        "a5": -f / Zst * (a(3, 1) * h - c(al) * dZ) - xi / Zst * (a(3, 3) * h - s(al) * c(w) * dZ),
        "a6": -f / Zst * (a(1, 1) * dY - a(2, 1) * dX) - xi / Zst * (a(1, 3) * dY - a(2, 3) * dX),
        "b1": (f * a(1, 2) + a(1, 3) * eta) / Zst, "b2": (f * a(2, 2) + a(2, 3) * eta) / Zst,
        "b3": (f * a(3, 2) + a(3, 3) * eta) / Zst,
        "b4": -f / Zst * (a(1, 3) * dX + a(2, 3) * dY + a(3, 3) * dZ) + eta / Zst * (a(1, 2) * dX + a(2, 2) * dY + a(3, 2) * dZ),
        "b5": -f / Zst * (a(3, 2) * h - s(al) * s(w) * dZ) - eta / Zst * (a(3, 3) * h - s(al) * c(w) * dZ),
        "b6": -f / Zst * (a(1, 2) * dY - a(2, 2) * dX) - eta / Zst * (a(1, 3) * dY - a(2, 3) * dX),
    }


@pytest.mark.parametrize("name", d.RESECTION_COEFFICIENTS)
def test_corrected_coefficients_equal_sympy(name):
    """The 'correct' forms recorded in the errata are the sympy derivatives (exact zero difference)."""
    diff = _corrected()[name] - d.derived_resection_partials("kaw")[name]
    assert sp.simplify(sp.expand_trig(sp.together(diff))) == 0


@pytest.mark.parametrize("order", ["kaw", "wak"])
def test_derived_jacobian_matches_finite_differences(order):
    res, jac = d.collinearity_model(order).compile()
    rng = np.random.default_rng(5)
    p = np.r_[rng.uniform(-50, 50, 2), 1000.0, rng.uniform(-0.3, 0.3, 3)]
    data = (rng.uniform(-400, 400, 7), rng.uniform(-400, 400, 7), rng.uniform(0, 100, 7),
            rng.uniform(-50, 50, 7), rng.uniform(-50, 50, 7), 100.0, 0.02, -0.01)
    J = jac(*p, *data)                                   # (12, n)
    for k, hstep in enumerate([1e-4] * 3 + [1e-7] * 3):
        e = np.zeros(6)
        e[k] = hstep
        fd = (res(*(p + e), *data) - res(*(p - e), *data)) / (2 * hstep)      # (2, n)
        np.testing.assert_allclose(J[k], fd[0], rtol=1e-6, atol=1e-9)
        np.testing.assert_allclose(J[6 + k], fd[1], rtol=1e-6, atol=1e-9)


@pytest.mark.parametrize("name", ["a1", "b1", "c1"])
def test_printed_angle_partials_equal_sympy(name):
    model = d.angle_equality_model()
    var = {"a1": d.Xs, "b1": d.Ys, "c1": d.Zs}[name]
    derived = sp.diff(model.residuals[0], var)
    assert sp.simplify(d.printed_angle_equality_partials()[name] - derived) == 0
