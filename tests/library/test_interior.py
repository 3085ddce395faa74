"""§1.11 interior orientation of scanned images (photolib.interior): synthetic ground truth."""

import numpy as np
import pytest
from hypothesis import given, settings, strategies as st

from photolib import interior
from photolib.errors import DegenerateGeometryError, InputError

# calibrated side + corner fiducials of a 230 mm frame (mm), marks 1..4 = left, right, top, bottom
SIDE = np.array([[-106.0, 0.0], [106.0, 0.0], [0.0, 106.0], [0.0, -106.0]])
CORNERS = np.array([[-106.0, -106.0], [106.0, 106.0], [-106.0, 106.0], [106.0, -106.0]])
EIGHT = np.vstack([SIDE, CORNERS])


def _camera_to_scanner(xy, a0, b0, phi, kx, ky):
    """Synthetic truth: the exact inverse of (1.11.6), written independently of the library."""
    u, v = xy[:, 0] / kx, xy[:, 1] / ky
    c, s = np.cos(phi), np.sin(phi)
    return np.column_stack([a0 + c * u - s * v, b0 + s * u + c * v])


def test_affine_exact_recovery():
    rng = np.random.default_rng(10)
    true = np.array([0.8, 1.0003, 0.0021, -1.5, -0.0019, 0.9995])     # a0 a1 a2 b0 b1 b2
    P = np.array([[true[1], true[2]], [true[4], true[5]]])
    calib = EIGHT + rng.normal(0, 0.5, EIGHT.shape)
    measured = (calib - true[[0, 3]]) @ np.linalg.inv(P).T             # x̄ = P⁻¹(x − a)
    t = interior.fit_affine(measured, calib)
    np.testing.assert_allclose([t.a0, t.a1, t.a2, t.b0, t.b1, t.b2], true, atol=1e-11)
    assert t.mu < 1e-10 and t.dof == 10
    np.testing.assert_allclose(interior.apply_affine(t, measured), calib, atol=1e-10)


def test_affine_three_fiducials_exact_and_no_redundancy():
    meas = SIDE[:3] + [3.0, -2.0]
    t = interior.fit_affine(meas, SIDE[:3])
    np.testing.assert_allclose(interior.apply_affine(t, meas), SIDE[:3], atol=1e-12)
    assert t.dof == 0 and np.isnan(t.mu)


def test_affine_inverse_matrix_and_round_trip():
    t = interior.AffineTransform(2.0, 0.999, 0.01, -3.0, -0.012, 1.001)
    np.testing.assert_allclose(t.P_inv @ t.P, np.eye(2), atol=1e-15)
    pts = np.random.default_rng(11).uniform(-115, 115, (50, 2))
    np.testing.assert_allclose(interior.invert_affine(t, interior.apply_affine(t, pts)), pts, atol=1e-12)
    # a single point stays a single point
    assert interior.apply_affine(t, [1.0, 2.0]).shape == (2,)


def test_affine_noisy_mu_matches_simulated_sigma():
    # 8 fiducials, σ = 2.5 μm, many seeded repetitions: the mean of μ² estimates σ² without bias
    rng = np.random.default_rng(12)
    sigma = 0.0025
    true = dict(a0=0.5, a1=1.0002, a2=0.003, b0=-0.7, b1=-0.0031, b2=0.9996)
    P = np.array([[true["a1"], true["a2"]], [true["b1"], true["b2"]]])
    measured = (EIGHT - [true["a0"], true["b0"]]) @ np.linalg.inv(P).T
    mu2, errs = [], []
    for _ in range(400):
        calib = EIGHT + rng.normal(0, sigma, EIGHT.shape)
        t = interior.fit_affine(measured, calib)
        mu2.append(t.mu ** 2)
        errs.append(t.a0 - true["a0"])
    assert np.sqrt(np.mean(mu2)) == pytest.approx(sigma, rel=0.05)
    # and m_a0 = μ√Q_a0a0 agrees with the scatter of the estimates
    assert np.std(errs) == pytest.approx(sigma * np.sqrt(t.Q[0, 0]), rel=0.1)


@given(a0=st.floats(-20, 20), b0=st.floats(-20, 20), phi=st.floats(-0.2, 0.2),
       sx=st.floats(0.98, 1.02), sy=st.floats(0.98, 1.02), shear=st.floats(-0.01, 0.01))
@settings(max_examples=50, deadline=None)
def test_affine_hypothesis_round_trip(a0, b0, phi, sx, sy, shear):
    c, s = np.cos(phi), np.sin(phi)
    P = np.array([[c, -s], [s, c]]) @ np.array([[sx, shear], [0.0, sy]])
    measured = (EIGHT - [a0, b0]) @ np.linalg.inv(P).T
    t = interior.fit_affine(measured, EIGHT)
    np.testing.assert_allclose(t.P, P, atol=1e-10)
    np.testing.assert_allclose(interior.invert_affine(t, EIGHT), measured, atol=1e-9)


def test_affine_bad_input():
    with pytest.raises(InputError, match="at least 3"):
        interior.fit_affine(SIDE[:2], SIDE[:2])
    with pytest.raises(DegenerateGeometryError, match="collinear"):
        interior.fit_affine([[0, 0], [1, 1], [2, 2], [5, 5]], SIDE)
    with pytest.raises(DegenerateGeometryError, match="coincide"):
        interior.fit_affine([[1, 1]] * 3, SIDE[:3])
    with pytest.raises(InputError, match="NaN"):
        interior.fit_affine([[0, 0], [1, np.nan], [2, 0]], SIDE[:3])
    with pytest.raises(InputError, match="differ in number"):
        interior.fit_affine(SIDE, SIDE[:3])
    with pytest.raises(InputError, match="6 affine"):
        interior.apply_affine([1, 2, 3], SIDE)
    with pytest.raises(DegenerateGeometryError, match="singular"):
        interior.invert_affine(interior.AffineTransform(0, 1, 2, 0, 2, 4), SIDE)


@pytest.mark.parametrize("phi_deg, vertical", [(0.5, False), (-1.3, False), (0.0, True)])
def test_similarity_recovers_synthetic(phi_deg, vertical):
    a0, b0, phi, kx, ky = 3.2, -2.7, np.radians(phi_deg), 0.9995, 1.0003
    measured = _camera_to_scanner(SIDE, a0, b0, phi, kx, ky)
    if vertical:
        assert measured[2, 0] == measured[3, 0]          # line 3–4 exactly vertical: c₂ = ∞
    Lx = Ly = 212.0
    p = interior.fiducial_similarity(measured, Lx, Ly)
    assert (p.a0, p.b0, p.phi, p.kx, p.ky) == pytest.approx((a0, b0, phi, kx, ky), abs=1e-12)
    np.testing.assert_allclose(interior.similarity_forward(p, measured), SIDE, atol=1e-11)


def test_similarity_noisy_fiducials():
    rng = np.random.default_rng(13)
    a0, b0, phi, kx, ky = 4.0, 2.5, np.radians(0.5), 0.9995, 1.0003
    errs = []
    for _ in range(200):
        measured = _camera_to_scanner(SIDE, a0, b0, phi, kx, ky) + rng.normal(0, 0.0025, (4, 2))
        p = interior.fiducial_similarity(measured, 212.0, 212.0)
        errs.append([p.a0 - a0, p.b0 - b0, p.phi - phi, p.kx - kx, p.ky - ky])
    errs = np.array(errs)
    # origin within a few μm, angle to ~1e-5 rad, scales to ~2e-5 (2.5 μm over 212 mm)
    assert np.abs(errs.mean(axis=0)).max() < 1e-3
    assert errs[:, :2].std() < 0.004 and errs[:, 2].std() < 3e-5 and errs[:, 3:].std() < 3e-5


@given(a0=st.floats(-10, 10), b0=st.floats(-10, 10), phi=st.floats(-0.5, 0.5),
       kx=st.floats(0.99, 1.01), ky=st.floats(0.99, 1.01))
@settings(max_examples=60, deadline=None)
def test_similarity_exact_inverse_round_trip(a0, b0, phi, kx, ky):
    p = interior.FiducialSimilarity(a0, b0, phi, kx, ky)
    xy = np.random.default_rng(14).uniform(-115, 115, (30, 2))
    back = interior.similarity_forward(p, interior.similarity_inverse(p, xy, exact=True))
    np.testing.assert_allclose(back, xy, atol=1e-12)
    scanner = _camera_to_scanner(xy, a0, b0, phi, kx, ky)
    np.testing.assert_allclose(interior.similarity_inverse(p, xy), scanner, atol=1e-12)


def test_book_inverse_error_proportional_to_kx_minus_ky():
    xy = np.array([[106.0, 0.0], [0.0, 106.0], [-80.0, 95.0]])
    phi = np.radians(0.7)
    errors = []
    dks = np.array([0.0, 2e-4, 4e-4, 8e-4])
    for dk in dks:
        p = interior.FiducialSimilarity(1.0, -1.0, phi, 1.0 + dk, 1.0)
        d = interior.similarity_inverse(p, xy, exact=False) - interior.similarity_inverse(p, xy, exact=True)
        # the closed form a2·(1/k_y − 1/k_x)·(y, x)
        expected = np.sin(phi) * (1 / p.ky - 1 / p.kx) * xy[:, ::-1]
        np.testing.assert_allclose(d, expected, atol=1e-13)
        errors.append(np.abs(d).max())
    assert errors[0] == 0.0
    ratios = np.array(errors[1:]) / dks[1:]
    assert ratios == pytest.approx(ratios[0], rel=1e-3)           # ∝ (k_x − k_y) to first order
    # the guide's figure: k_x/k_y = 1.0009, φ = 0.7° → about 1.2 μm at 106 mm
    p = interior.FiducialSimilarity(0, 0, phi, 1.0009, 1.0)
    d = interior.similarity_inverse(p, xy[:2], exact=False) - interior.similarity_inverse(p, xy[:2])
    assert np.abs(d).max() * 1000 == pytest.approx(1.16, abs=0.01)


def test_similarity_bad_input():
    with pytest.raises(InputError, match="exactly 4"):
        interior.fiducial_similarity(SIDE[:3], 212, 212)
    with pytest.raises(InputError, match="NaN"):
        interior.fiducial_similarity(np.where(np.eye(4, 2) > 0, np.nan, SIDE), 212, 212)
    with pytest.raises(DegenerateGeometryError, match="coincident"):
        interior.fiducial_similarity([[1, 1], [1, 1], [0, 5], [0, -5]], 212, 212)
    with pytest.raises(DegenerateGeometryError, match="parallel"):
        interior.fiducial_similarity([[-5, 0], [5, 0], [5, 1], [-5, 1]], 212, 212)
    with pytest.raises(InputError, match="positive"):
        interior.fiducial_similarity(SIDE, -212, 212)
