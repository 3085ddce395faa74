"""photolib/derivations/_generated.py is printed from the sympy models and must be up to date.

Regenerate with ``python -m photolib.derivations._codegen``. The keys are hashes of the models'
sympy forms; they must not depend on Python's hash seed.
"""

import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import sympy as sp

from photolib import derivations as D
from photolib.derivations import _codegen, _generated
from photolib.derivations.model import _model_key


def test_generated_module_is_up_to_date_with_the_sympy_models():
    path = Path(_generated.__file__)
    assert path.read_text(encoding="utf-8") == _codegen.generated_source()


def test_every_library_model_uses_the_printed_code():
    for _, model in _codegen._models():
        assert _model_key(model) in _generated.MODELS, model.name


def test_model_keys_do_not_depend_on_the_hash_seed():
    code = ("from photolib.derivations import collinearity_model, gnss_coplanarity_model\n"
            "from photolib.derivations.model import _model_key\n"
            "print(_model_key(collinearity_model('kaw')), _model_key(gnss_coplanarity_model()))")
    keys = {subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True,
                           env={**os.environ, "PYTHONHASHSEED": seed}).stdout for seed in ("1", "2")}
    assert len(keys) == 1


def test_a_model_outside_the_generated_table_is_lambdified():
    a, t = sp.symbols("a t")
    res, jac = D.Model("test-line", (a,), (t,), (a * t - 1,)).compile()
    np.testing.assert_array_equal(jac(2.0, np.array([1.0, 3.0])), [[1.0, 3.0]])


def test_gnss_coplanarity_coefficients_by_rows_equal_the_model_jacobian():
    """The product-rule derivation of (5) equals the derivative of the expanded determinant (1)."""
    m = D.gnss_coplanarity_model()
    _, jac = m.compile()
    derived = D.derived_gnss_coplanarity_coefficients()
    fn = sp.lambdify(list(m.parameters) + list(m.data), [derived[k] for k in D.GNSS_COEFFICIENTS])
    rng = np.random.default_rng(3)
    for _ in range(5):
        v = (list(rng.uniform(-0.5, 0.5, 6)) + list(rng.uniform(-100, 100, 4)) + [120.0, 0.01, -0.02]
             + list(rng.uniform(-800, 800, 3)))
        np.testing.assert_allclose(np.ravel(fn(*v)), jac(*v).ravel(), rtol=1e-12)
    # and exactly, for one coefficient (sympy expansion of the difference)
    a = derived["a"] - m.jacobian()[0]
    assert sp.expand(a) == 0


def test_gnss_coplanarity_written_by_its_first_row_is_the_determinant():
    """The GNSS coplanarity φ of (1) is written out by its first row (short printed code); it must
    be exactly the 3×3 determinant of the base and the two image-space vectors."""
    import sympy as sp
    from photolib.derivations import gnss as G
    r1 = G._gnss_image_space(G.x1, G.y1, G.alpha1, G.omega1, G.chi1)
    r2 = G._gnss_image_space(G.x2, G.y2, G.alpha2, G.omega2, G.chi2)
    determinant = sp.Matrix([[G.B_Y, G.B_X, G.B_Z], list(r1), list(r2)]).det(method="berkowitz")
    assert sp.expand(G._gnss_coplanarity_expression() - determinant) == 0
