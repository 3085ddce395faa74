"""Interior and exterior orientation of Chapter 1 (§1.2–§1.3): photolib.camera.

The distortion model (1.2.2) is checked against a value worked out by hand, its symmetry, a
sympy transcription of the printed formula, and the inverse relation between correction and
application; the ray vector (1.2.1)/(1.2.3) against its definition.
"""

import numpy as np
import pytest
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st

from photolib.camera import (
    ExteriorOrientation, InteriorOrientation, apply_distortion, as_points, correct_distortion,
    distortion_correction, image_vector,
)
from photolib.errors import DegenerateGeometryError, InputError

coord = st.floats(-45.0, 45.0)


def test_zero_coefficients_give_zero_correction():
    io = InteriorOrientation(100.0, 0.3, -0.4)
    xy = np.random.default_rng(0).uniform(-50, 50, (20, 2))
    assert not io.has_distortion
    np.testing.assert_array_equal(distortion_correction(xy, io), 0.0)
    np.testing.assert_array_equal(correct_distortion(xy, io), xy)
    np.testing.assert_array_equal(apply_distortion(xy, io), xy)


@settings(max_examples=60, deadline=None)
@given(x=coord, y=coord, k1=st.floats(-1e-4, 1e-4), k2=st.floats(-1e-7, 1e-7), k3=st.floats(-1e-10, 1e-10))
def test_radial_distortion_is_odd(x, y, k1, k2, k3):
    io = InteriorOrientation(100.0, k1=k1, k2=k2, k3=k3)
    d = distortion_correction([[x, y], [-x, -y]], io)
    np.testing.assert_allclose(d[1], -d[0], atol=1e-15)


def test_decentering_distortion_is_even():
    """The p-terms of (1.2.2) are quadratic: d(−x̄, −ȳ) = d(x̄, ȳ)."""
    io = InteriorOrientation(100.0, 1.0, 2.0, p1=3e-5, p2=-2e-5)
    xy = np.array([[5.0, 7.0], [1.0 - 4.0, 2.0 - 5.0]])        # x̄, ȳ = (4, 5) and (−4, −5)
    d = distortion_correction(xy, io)
    np.testing.assert_allclose(d[0], d[1], atol=1e-16)


def test_hand_derived_value():
    """x̄ = 3, ȳ = 4 (r² = 25), k1 = 1e-4, k2 = 1e-7, p1 = 2e-5, p2 = −1e-5:
    d_x = 3(0.0025 + 0.0000625) + 43·2e-5 + 24·(−1e-5) = 0.0083075,
    d_y = 4(0.0025 + 0.0000625) + 24·2e-5 + 57·(−1e-5) = 0.01016."""
    io = InteriorOrientation(100.0, x0=0.5, y0=-0.2, k1=1e-4, k2=1e-7, p1=2e-5, p2=-1e-5)
    d = distortion_correction([3.5, 3.8], io)[0]
    np.testing.assert_allclose(d, [0.0083075, 0.01016], rtol=1e-12)
    np.testing.assert_allclose(correct_distortion([3.5, 3.8], io)[0], [3.5083075, 3.81016], rtol=1e-14)


def test_distortion_matches_the_printed_formula_in_sympy():
    x_, y_, x0_, y0_, k1, k2, k3, p1, p2 = sp.symbols("x y x0 y0 k1 k2 k3 p1 p2", real=True)
    r2 = (x_ - x0_) ** 2 + (y_ - y0_) ** 2
    radial = r2 * k1 + r2 ** 2 * k2 + r2 ** 3 * k3
    dx = (x_ - x0_) * radial + (r2 + 2 * (x_ - x0_) ** 2) * p1 + 2 * (x_ - x0_) * (y_ - y0_) * p2      # (1.2.2)
    dy = (y_ - y0_) * radial + 2 * (x_ - x0_) * (y_ - y0_) * p1 + (r2 + 2 * (y_ - y0_) ** 2) * p2
    fn = sp.lambdify((x_, y_, x0_, y0_, k1, k2, k3, p1, p2), [dx, dy])
    rng = np.random.default_rng(1)
    coeffs = (0.2, -0.1, 3e-5, -2e-8, 5e-12, 1e-6, -2e-6)
    io = InteriorOrientation(100.0, *coeffs)
    xy = rng.uniform(-40, 40, (50, 2))
    np.testing.assert_allclose(distortion_correction(xy, io), np.column_stack(fn(xy[:, 0], xy[:, 1], *coeffs)),
                               rtol=1e-12, atol=1e-18)


@settings(max_examples=60, deadline=None)
@given(x=coord, y=coord, k1=st.floats(-1e-5, 5e-5), p1=st.floats(-5e-6, 5e-6), p2=st.floats(-5e-6, 5e-6))
def test_apply_distortion_inverts_correct_distortion(x, y, k1, p1, p2):
    # k1 ≥ −1e-5 mm⁻² keeps the whole ±45 mm square inside the region where (1.2.2) is
    # one-to-one (a barrel correction k1 < 0 folds over at r² = −1/(3k1)); see the next test.
    io = InteriorOrientation(100.0, 0.1, -0.1, k1=k1, k2=1e-9, p1=p1, p2=p2)
    measured = apply_distortion([x, y], io)
    np.testing.assert_allclose(correct_distortion(measured, io)[0], [x, y], atol=1e-10)
    np.testing.assert_allclose(apply_distortion(correct_distortion([x, y], io), io)[0], [x, y], atol=1e-9)


def test_apply_distortion_refuses_points_without_a_preimage():
    # x(1 + k1 r²) with k1 = −5e-5 mm⁻² reaches at most 2/3·r_max, r_max = √(1/(3·5e-5)) = 81.6 mm:
    # an ideal point at 60 mm radius has no measured point.
    io = InteriorOrientation(100.0, k1=-5e-5)
    r_max = np.sqrt(1 / (3 * 5e-5))
    reachable = r_max * (1 - 5e-5 * r_max ** 2)
    assert reachable < 60.0
    with pytest.raises(DegenerateGeometryError, match="no inverse"):
        apply_distortion([[60.0, 0.0]], io)
    measured = apply_distortion([[0.9 * reachable, 0.0]], io)     # inside the one-to-one region it works
    np.testing.assert_allclose(correct_distortion(measured, io), [[0.9 * reachable, 0.0]], atol=1e-10)


def test_image_vector_1_2_1_and_1_2_3():
    io = InteriorOrientation(120.0, 0.4, -0.3, k1=2e-5, p2=1e-6)
    xy = np.array([[10.0, -20.0], [0.4, -0.3]])
    ideal = image_vector(xy, io, distortion=False)
    np.testing.assert_allclose(ideal, [[9.6, -19.7, -120.0], [0.0, 0.0, -120.0]], atol=1e-14)   # (1.2.1)
    d = distortion_correction(xy, io)
    np.testing.assert_allclose(image_vector(xy, io), ideal + np.column_stack([d, np.zeros(2)]), atol=1e-15)  # (1.2.3)
    assert np.all(d[1] == 0)          # no distortion at the principal point


def test_exterior_orientation_round_trips():
    eo = ExteriorOrientation.from_degrees(1.0, 2.0, 3.0, 5.0, -10.0, 2.0)
    np.testing.assert_allclose(eo.angles_degrees, [5.0, -10.0, 2.0], atol=1e-12)
    back = ExteriorOrientation.from_matrix(eo.center, eo.matrix)
    np.testing.assert_allclose(back.vector, eo.vector, atol=1e-12)
    other = eo.with_order("wak")
    np.testing.assert_allclose(other.matrix, eo.matrix, atol=1e-12)
    assert not np.allclose(other.angles_degrees, eo.angles_degrees, atol=1e-3)
    np.testing.assert_allclose(ExteriorOrientation.from_vector(eo.vector).vector, eo.vector)


@pytest.mark.parametrize("call", [
    lambda: InteriorOrientation(0.0),
    lambda: InteriorOrientation(-1.0),
    lambda: InteriorOrientation(100.0, k1=np.nan),
    lambda: ExteriorOrientation(0.0, 0.0, np.inf),
    lambda: ExteriorOrientation(0.0, 0.0, 1.0, order="xyz"),
    lambda: ExteriorOrientation.from_vector([1.0, 2.0, 3.0]),
    lambda: as_points([[1.0, 2.0, 3.0]], 2),
    lambda: as_points([1.0, np.nan], 2),
    lambda: distortion_correction([[1.0, 2.0, 3.0]], InteriorOrientation(100.0, k1=1e-5)),
], ids=lambda c: "")
def test_bad_input_raises_input_error(call):
    with pytest.raises(InputError):
        call()


# --- the vectorised collection of exterior orientations ------------------------------------------
def test_exterior_orientations_round_trip_and_matrices():
    from photolib.camera import ExteriorOrientations
    from photolib.rotation import rotation_matrix
    rng = np.random.default_rng(3)
    centres = rng.uniform(-500, 500, (7, 3))
    angles = rng.uniform(-1.0, 1.0, (7, 3))
    eos = ExteriorOrientations(centres, angles, "wak")
    assert len(eos) == 7 and eos.order == "wak"
    one = eos[4]
    assert isinstance(one, ExteriorOrientation) and one.order == "wak"
    np.testing.assert_array_equal(one.vector, np.r_[centres[4], angles[4]])
    # each matrix is the one of the single orientation (independently: scipy's extrinsic xyz = ω–α–κ)
    from scipy.spatial.transform import Rotation
    np.testing.assert_allclose(eos.matrices(), Rotation.from_euler("XYZ", angles).as_matrix(), atol=1e-14)
    np.testing.assert_allclose(eos.matrices()[2], rotation_matrix(*angles[2], "wak"), atol=1e-15)
    back = ExteriorOrientations.from_list(eos.to_list())
    assert back == eos
    kaw = eos.with_order("kaw")
    np.testing.assert_allclose(kaw.matrices(), eos.matrices(), atol=1e-13)
    assert len(eos[1:3]) == 2 and eos[[0, 6]][1] == eos[6]
    assert repr(eos).startswith("ExteriorOrientations(7 images, order='wak'")


def test_exterior_orientations_bad_input():
    from photolib.camera import ExteriorOrientations
    with pytest.raises(InputError):
        ExteriorOrientations(np.zeros((2, 3)), np.zeros((3, 3)))
    with pytest.raises(InputError):
        ExteriorOrientations(np.full((2, 3), np.nan), np.zeros((2, 3)))
    with pytest.raises(InputError):
        ExteriorOrientations.from_list([ExteriorOrientation(0, 0, 0), "not an orientation"])
    with pytest.raises(InputError):
        ExteriorOrientations(np.zeros((2, 3)), np.zeros((2, 3)))[5]


def test_degrees_warn_and_non_rotations_are_refused():
    from photolib.errors import DegreesWarning
    with pytest.warns(DegreesWarning):
        ExteriorOrientation(0.0, 0.0, 1000.0, 2.0, 5.0, 30.0)        # degrees passed as radians
    with pytest.raises(InputError, match="not a rotation"):
        ExteriorOrientation.from_matrix([0, 0, 0], 2 * np.eye(3))
    with pytest.raises(InputError):
        ExteriorOrientation(0.0, "1", 2.0)


def test_orientation_reprs_are_short_and_in_degrees():
    eo = ExteriorOrientation.from_degrees(1000, 2000, 1500, 2, 5, 7)
    text = repr(eo)
    assert "omega=2.0000°" in text and "kappa=7.0000°" in text and "Zs=1500.000 m" in text
    assert len(text) < 150
    assert repr(InteriorOrientation(100.0)) == "InteriorOrientation(f=100.000 mm, x0=0.000 mm, y0=0.000 mm)"
