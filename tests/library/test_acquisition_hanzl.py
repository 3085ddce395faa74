"""Hanzl §6 through photolib.planning: diffraction, image motion, AWAR, flight plan, Tab. 6.1 rule,
target sizes and the goniometer calibration (synthetic distortion with a known dc)."""

import math

import numpy as np
import pytest

from photolib import planning as P


def test_diffraction_radius_formula():
    assert P.diffraction_radius(4.0) == pytest.approx(1.22 * 0.55 * 4.0)
    assert P.diffraction_radius(8.0, 0.5) == pytest.approx(2 * P.diffraction_radius(4.0, 0.5))


def test_image_motion_units():
    assert P.image_motion(50.0, 0.005, 10000) == pytest.approx(25e-6)
    assert P.image_motion(0.0, 0.005, 10000) == 0.0


def test_awar_is_weighted_mean():
    A, R = np.array([4.0, 1.0, 1.0]), np.array([80.0, 40.0, 50.0])
    assert P.awar(A, R) == pytest.approx(np.average(R, weights=A))


def test_flight_plan_agrees_with_plan_block():
    hp = P.photo_flight_plan(153.0, 10000, 230.0, forward_overlap=60, side_overlap=25, terrain_height=250.0)
    assert hp.flying_height == pytest.approx(1530.0) and hp.altitude == pytest.approx(1780.0)
    assert hp.base == pytest.approx(920.0) and hp.strip_spacing == pytest.approx(1725.0)
    # the same block through Chibunichev §10.3's plan_block: pixel 0.023 mm, 10000 × 10000 px = 230 mm
    fp = P.plan_block(5000.0, 5000.0, f=153.0, pixel_size=0.023, sensor=(10000, 10000), flying_height=1530.0,
                      forward_overlap=0.6, side_overlap=0.25)
    assert fp.base == pytest.approx(hp.base) and fp.strip_spacing == pytest.approx(hp.strip_spacing)


def test_scale_from_map_rule():
    mk = np.array([500, 1000, 2000, 5000, 10000, 25000])
    assert np.allclose(P.photo_scale_from_map(mk), 200 * np.sqrt(mk))
    assert P.photo_scale_from_map(10000, constant=100) == pytest.approx(10000.0)


def test_target_sizes():
    t = P.target_sizes(12000)
    assert (t.arm_length, t.arm_width, t.square_side) == pytest.approx((1.5, 0.24, 0.4))


def _goniometer(dc_true, seed=0):
    rng = np.random.default_rng(seed)
    c_true = 153.0 + dc_true
    tau = np.radians(np.linspace(0.0, 45.0, 16))
    r_ideal = c_true * np.tan(tau)
    r = r_ideal + 0.004 * np.sin(np.linspace(0, 2 * np.pi, 16)) + rng.normal(0, 0.0005, 16)
    return r, tau


def test_goniometer_lsq_matches_closed_form_and_numpy():
    r, tau = _goniometer(0.02)
    g = P.goniometer_distortion(r, tau, 153.0, "lsq")
    t = np.tan(tau)
    assert g.dc == pytest.approx(np.sum((r - 153.0 * t) * t) / np.sum(t * t), rel=1e-12)
    assert g.dc == pytest.approx(np.linalg.lstsq(t[:, None], r - 153.0 * t, rcond=None)[0][0], rel=1e-12)
    assert g.dc == pytest.approx(0.02, abs=0.005)
    assert np.allclose(g.dr, r - g.c * t)


def test_goniometer_exact_without_distortion():
    tau = np.radians([0, 5, 10, 20, 30, 40])
    r = 152.987 * np.tan(tau)
    for crit in ("lsq", "minmax"):
        g = P.goniometer_distortion(r, tau, 153.0, crit)
        assert g.dc == pytest.approx(-0.013, abs=1e-12)
        assert np.allclose(g.dr, 0.0, atol=1e-12)


def test_goniometer_minmax_balances_extremes():
    r, tau = _goniometer(-0.01, seed=3)
    g = P.goniometer_distortion(r, tau, 153.0, "minmax")
    # independent check: a dense scan of dc cannot beat the minimax value
    t = np.tan(tau)
    grid = np.linspace(g.dc - 0.01, g.dc + 0.01, 20001)
    best = np.abs((r - 153.0 * t)[None] - grid[:, None] * t[None]).max(axis=1).min()
    assert np.abs(g.dr).max() <= best + 1e-12
    lsq = P.goniometer_distortion(r, tau, 153.0, "lsq")
    assert np.abs(g.dr).max() <= np.abs(lsq.dr).max() + 1e-12
    assert np.sum(lsq.dr ** 2) <= np.sum(g.dr ** 2) + 1e-15
    assert math.isfinite(g.c)
