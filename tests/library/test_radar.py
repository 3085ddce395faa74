"""photolib.radar (Chapter 8, §8.9–8.13): side-looking radar positioning, radar stereo, InSAR.

Expected values: synthetic ground truth (points placed by hand, ranges measured with numpy
norms), sympy (photolib.derivations.radar), an independent unwrapper (scikit-image's
unwrap_phase, Herráez et al. 2002) and the real SRTM DEM (../shared/data) as height truth.
"""

import numpy as np
import pytest
import sympy as sp

from photolib import radar as r
from photolib.derivations import radar as dr
from photolib.errors import DegenerateGeometryError
from photolib.rotation import rotation_matrix

S = np.array([1000.0, -2000.0, 8000.0])
A_TILT = rotation_matrix(0.02, -0.01, 0.3, "wak")


def _unit(phi, s=1):
    return np.array([0.0, s * np.sin(phi), -np.cos(phi)])


# --------------------------------------------------------------------------- §8.9, §8.11
def test_slant_range_and_its_inverse():
    y = np.array([0.0, 12.5, 4000.0])
    D = r.slant_range(y, 850e3, 7.8)
    np.testing.assert_allclose(D, 850e3 + 7.8 * y)
    np.testing.assert_allclose(r.range_coordinate(D, 850e3, 7.8), y, atol=1e-9)


def test_range_vector_is_the_rotated_nadir_ray():
    # (8.11.4): nadir (0, 0, -1) turned about x by s*phi; against the sympy derivation
    for side, s in (("left", 1), ("right", -1)):
        expr = dr.radar_range_vector_symbolic(side)
        num = np.array([float(e.subs({dr.D: 7.0, dr.phi: 0.4})) for e in expr])
        np.testing.assert_allclose(r.range_vector(7.0, 0.4, side), num, atol=1e-14)
        np.testing.assert_allclose(num, 7.0 * _unit(0.4, s), atol=1e-14)


@pytest.mark.parametrize("side", ["left", "right"])
@pytest.mark.parametrize("method", ["closed", "newton"])
def test_single_image_round_trip_with_known_height(side, method):
    s = 1 if side == "left" else -1
    M = S + 12000.0 * A_TILT @ _unit(0.75, s)            # the point placed by hand
    phi = r.look_angle_from_height(S, A_TILT, 12000.0, M[2], side, method=method)
    assert phi == pytest.approx(0.75, abs=1e-12)
    np.testing.assert_allclose(r.radar_point(S, A_TILT, 12000.0, phi, side), M, atol=1e-8)
    D, ph, x = r.radar_project(S, A_TILT, M, side)
    assert D == pytest.approx(12000.0) and ph == pytest.approx(0.75) and abs(x) < 1e-8


def test_vertical_formula_exact_only_without_roll_and_pitch():
    # (8.11.7) cos(phi) = H/D: exact for A = I or a pure kappa rotation, not with omega, alpha != 0
    for A in (np.eye(3), rotation_matrix(0.0, 0.0, 0.7, "wak")):
        M = S + 12000.0 * A @ _unit(0.75)
        assert r.look_angle_vertical(S[2] - M[2], 12000.0) == pytest.approx(0.75, abs=1e-12)
    M = S + 12000.0 * A_TILT @ _unit(0.75)
    assert abs(r.look_angle_vertical(S[2] - M[2], 12000.0) - 0.75) > 0.01


def test_range_that_does_not_reach_the_plane_is_named():
    with pytest.raises(DegenerateGeometryError, match="does not reach"):
        r.look_angle_from_height(S, np.eye(3), 5000.0, 0.0)        # 8 km below, 5 km range
    with pytest.raises(DegenerateGeometryError, match="does not reach"):
        r.look_angle_vertical(8000.0, 5000.0)


def test_layover_equal_ranges_share_one_pixel():
    # Fig. 8.18: a valley point and a mountain point at one slant range are one image pixel
    D = 10000.0
    low = r.radar_point(S, np.eye(3), D, r.look_angle_from_height(S, np.eye(3), D, 0.0))
    high = r.radar_point(S, np.eye(3), D, r.look_angle_from_height(S, np.eye(3), D, 2500.0))
    assert np.linalg.norm(low - S) == pytest.approx(np.linalg.norm(high - S))
    assert abs(low[2] - high[2]) == pytest.approx(2500.0) and np.linalg.norm(low - high) > 2000
    # the mirror root is the same range on the other side of the nadir
    m = r.look_angle_from_height(S, np.eye(3), D, 0.0, root="mirror")
    assert m == pytest.approx(-np.arccos(0.8))
    # a steep slope facing the radar: ranges fall along ground range -> layover
    u = np.linspace(5000, 7000, 41)
    h = np.where((u > 6000) & (u < 6100), (u - 6000) * 3.0, 0.0)
    h[u >= 6100] = 300.0
    Dr = np.hypot(u, 8000.0 - h)
    mask = r.layover_mask(Dr)
    brute = [any((k < j and Dr[k] >= Dr[j]) or (k > j and Dr[k] <= Dr[j]) for k in range(len(Dr)))
             for j in range(len(Dr))]
    assert mask.tolist() == brute and mask.any() and not mask[:3].any() and not mask[-5:].any()
    assert not r.layover_mask(np.hypot(u, 8000.0)).any()


# --------------------------------------------------------------------------- §8.12
def _fix_plane(Sx, A, M):
    """Turn A about the radar z axis so that M lies in its emission plane (zero Doppler)."""
    for _ in range(30):
        w = A.T @ (M - Sx)
        A = A @ rotation_matrix(0.0, 0.0, -np.arctan2(w[0], w[1]), "wak")
    return A


@pytest.mark.parametrize("S2", [np.array([0.0, 3000.0, 9500.0]), np.array([0.0, 0.0, 9500.0]),
                                np.array([200.0, -1500.0, 8000.0])])
def test_radar_stereo_round_trip(S2):
    S1, M = np.array([0.0, 0.0, 8000.0]), np.array([50.0, 6000.0, 300.0])
    A1 = _fix_plane(S1, rotation_matrix(0.01, 0.0, 0.0, "wak"), M)
    A2 = _fix_plane(S2, rotation_matrix(-0.02, 0.01, 0.0, "wak"), M)
    D1, D2 = np.linalg.norm(M - S1), np.linalg.norm(M - S2)
    res = r.radar_stereo(S1, A1, D1, S2, A2, D2)
    np.testing.assert_allclose(res.point, M, atol=1e-6)
    assert res.misclosure < 1e-6
    adj = r.radar_intersection(np.stack([S1, S2]), np.stack([A1, A2]), [D1, D2])
    np.testing.assert_allclose(adj.x, M, atol=1e-6)


def test_radar_intersection_overdetermined_with_noise():
    rng = np.random.default_rng(3)
    M = np.array([100.0, 7000.0, 250.0])
    Ss = np.array([[0.0, 0.0, 8000.0], [0.0, 0.0, 9000.0], [0.0, 800.0, 8500.0], [0.0, -600.0, 9800.0]])
    As = np.stack([_fix_plane(s_, np.eye(3), M) for s_ in Ss])
    D = np.linalg.norm(M - Ss, axis=1) + rng.normal(0, 0.5, 4)
    adj = r.radar_intersection(Ss, As, D)
    assert adj.dof == 5
    bound = 4 * 0.5 * np.sqrt(np.diag(adj.Q))            # a-priori σ_D = 0.5 m, Q = N⁻¹
    assert np.all(np.abs(adj.x - M) < bound)


def test_stereo_jacobian_matches_sympy_and_finite_differences():
    m = dr.radar_stereo_model()
    J = m.jacobian()
    assert J.shape == (3, 2)
    p1 = m.parameters[0]
    # coefficient a1 of (8.12.6) = dF_X/dphi1 = D1 (b12 cos phi1 + b13 sin phi1)
    b12, b13, D1 = sp.symbols("b12 b13 D1", real=True)
    assert sp.simplify(J[0, 0] - D1 * (b12 * sp.cos(p1) + b13 * sp.sin(p1))) == 0


# --------------------------------------------------------------------------- §8.13
def test_insar_formulas_against_the_geometry():
    g = r.InsarGeometry()
    phi, D1, H = 0.41, 850e3, g.H
    Sv1 = np.array([0.0, H])
    M = Sv1 + D1 * np.array([np.sin(phi), -np.cos(phi)])
    Sv2 = Sv1 - g.B * np.array([np.cos(g.alpha), np.sin(g.alpha)])
    D2 = np.linalg.norm(M - Sv2)
    assert r.insar_look_angle(D1, D2, g.B, g.alpha) == pytest.approx(phi, abs=1e-9)
    assert r.insar_look_angle_from_difference(D1, D2 - D1, g.B, g.alpha) == pytest.approx(phi, abs=1e-9)
    assert r.insar_height(H, D1, phi) == pytest.approx(M[1], abs=1e-6)
    dphi = r.range_difference_to_phase(D2 - D1, g.wavelength)
    assert r.phase_to_range_difference(dphi, g.wavelength) == pytest.approx(D2 - D1)
    assert r.range_difference_to_phase(1.0, 0.5, "bistatic") == pytest.approx(
        r.range_difference_to_phase(1.0, 0.5) / 2)


def test_height_precision_is_the_derivative():
    # (8.13.5) against a numerical derivative of h(Phi) through (8.13.3), (8.13.4), (8.13.2)
    g = r.InsarGeometry()
    D, phi = 858e3, np.radians(23)
    Sv2 = -g.B * np.array([np.cos(g.alpha), np.sin(g.alpha)])

    def h_of_phase(dphi):
        dD = r.phase_to_range_difference(dphi, g.wavelength)
        return r.insar_height(g.H, D, r.insar_look_angle_from_difference(D, dD, g.B, g.alpha))

    M = D * np.array([np.sin(phi), -np.cos(phi)])
    dphi0 = r.range_difference_to_phase(np.linalg.norm(M - Sv2) - D, g.wavelength)
    numeric = (h_of_phase(dphi0 + 0.5) - h_of_phase(dphi0 - 0.5)) / 1.0
    Bp = r.perpendicular_baseline(g.B, g.alpha, phi)
    assert abs(numeric) == pytest.approx(r.height_precision(D, g.wavelength, phi, Bp, 1.0), rel=1e-3)
    assert r.height_of_ambiguity(D, g.wavelength, phi, Bp) == pytest.approx(
        r.height_precision(D, g.wavelength, phi, Bp, 2 * np.pi))


def test_critical_baseline_envisat_and_sympy():
    rel = dr.insar_relations()
    s = rel["symbols"]
    expr = rel["critical_baseline"].subs({s["D1"]: 850e3, s["lambda"]: 0.05624, s["phi_0"]: np.radians(23),
                                          s["delta_D"]: r.range_resolution(16e6)})
    val = r.critical_baseline(850e3, 0.05624, np.radians(23), r.range_resolution(16e6))
    assert val == pytest.approx(float(expr))
    assert 1050 < val < 1150                                # the book's "about 1100 m"
    assert r.critical_baseline(850e3, 0.05624, 0.4, 9.37, "bistatic") == pytest.approx(
        2 * r.critical_baseline(850e3, 0.05624, 0.4, 9.37))


def test_critical_baseline_decorrelates_the_fringes():
    # at B_perp = B_crit the flat-ground phase turns by 2π per slant-range resolution cell
    # (geometry by hand: ground points at slant ranges D ± δ_D/2 from S1, ranges from S2 by numpy)
    H, lam, phi, alpha, dD = 790e3, 0.05624, np.radians(23), np.radians(20), 9.37
    D = H / np.cos(phi)
    Bc = r.critical_baseline(D, lam, phi, dD)
    B = Bc / np.cos(phi - alpha)                         # so that B_perp = B_crit
    S1, S2 = np.array([0.0, H]), np.array([0.0, H]) - B * np.array([np.cos(alpha), np.sin(alpha)])
    phase = []
    for Dx in (D - dD / 2, D + dD / 2):
        M = np.array([np.sqrt(Dx ** 2 - H ** 2), 0.0])
        phase.append(4 * np.pi / lam * (np.linalg.norm(M - S2) - np.linalg.norm(M - S1)))
    assert abs(phase[1] - phase[0]) == pytest.approx(2 * np.pi, rel=2e-3)


def test_unwrap_ls_exact_without_aliasing_and_like_skimage():
    skr = pytest.importorskip("skimage.restoration")
    y, x = np.mgrid[0:60, 0:80]
    true = 30 * np.exp(-((x - 40) ** 2 + (y - 30) ** 2) / 300.0) + 0.2 * x
    w = r.wrap_phase(true)
    u = r.unwrap_phase_ls(w)
    assert np.abs((u - u.mean()) - (true - true.mean())).max() < 1e-9
    sk = skr.unwrap_phase(w)
    assert np.abs((u - u.mean()) - (sk - sk.mean())).max() < 1e-9


def test_wrap_phase_range():
    p = np.linspace(-20, 20, 1001)
    w = r.wrap_phase(p)
    assert w.min() > -np.pi and w.max() <= np.pi
    np.testing.assert_allclose(np.cos(w), np.cos(p), atol=1e-12)


def _pipeline(h, sigma):
    ifg = r.simulate_interferogram(h, 25.0, sigma_phase=sigma, seed=1)
    true = ifg.phase - ifg.flat_phase
    u = r.unwrap_phase_ls(ifg.wrapped)
    hh = r.insar_heights(u, ifg.D1, ifg.geometry, ([0], [0], [h[0, 0]]))
    return ifg, true, u, hh


def test_synthetic_dem_heights_recovered():
    from photolib.synthetic import terrain_height
    Y, X = np.mgrid[0:120, 0:100] * 25.0
    h = terrain_height(X, Y, mean=500.0, relief=300.0, wavelength=3000.0)
    ifg, true, u, hh = _pipeline(h, 0.0)
    assert np.abs(hh - h).max() < 1e-5
    ifg, true, u, hh = _pipeline(h, 0.3)
    g = ifg.geometry
    pred = r.height_precision(ifg.D1.mean(), g.wavelength, g.look_angle,
                              r.perpendicular_baseline(g.B, g.alpha, g.look_angle), 0.3)
    rms = np.sqrt(np.mean((hh - h - np.mean(hh - h)) ** 2))
    assert 0.9 * pred < rms < 1.15 * pred


def test_real_dem_interferogram_unwrapped_and_heights():
    from photolib.datasets import DataUnavailableError
    skr = pytest.importorskip("skimage.restoration")
    pytest.importorskip("rasterio")
    try:
        h = r.load_dem_local(window=(360, 640, 80, 80), pixel_size=25.0)
    except DataUnavailableError:
        pytest.skip("real data absent: ../shared/data/dem/srtm_ref.tif (set PHOTOLIB_DATA)")
    assert np.ptp(h) > 800                               # SRTM relief of the window
    ifg, true, u, hh = _pipeline(h, 0.0)
    k = (u - true)
    assert np.abs(k - k.mean()).max() < 1e-6             # LS unwrapping = truth + constant
    sk = skr.unwrap_phase(ifg.wrapped)
    c = (sk - true) / (2 * np.pi)                        # scikit-image: truth + 2πk
    assert np.abs(c - np.round(c.mean())).max() < 1e-6
    assert np.abs(hh - h).max() < 1e-5
    ifg, true, u, hh = _pipeline(h, 0.3)
    err = hh - h
    g = ifg.geometry
    pred = r.height_precision(ifg.D1.mean(), g.wavelength, g.look_angle,
                              r.perpendicular_baseline(g.B, g.alpha, g.look_angle), 0.3)
    assert 0.9 * pred < np.std(err) < 1.15 * pred
