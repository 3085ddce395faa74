"""Chapter 6, §6.1–6.3: epipolar segment, vertical-line DSM, multi-image DSM — against rendered ground truth."""

import numpy as np
import pytest
from scipy.interpolate import RegularGridInterpolator

from photolib.camera import ExteriorOrientation, InteriorOrientation
from photolib.single_image import project
from photolib.surface import dsm_multi_image, dsm_vertical_line, epipolar_segment
from photolib.synthetic import render_image, terrain_scene


def test_segment_holds_the_true_match():
    """The guide's seg.py pair: f = 100 mm, (x0, y0) = (0.02, −0.01), M = (1290, 2140, 137), Z in [100, 200]."""
    io = InteriorOrientation(100.0, 0.02, -0.01)
    e1 = ExteriorOrientation(1000, 2000, 1500, 0.010, -0.020, 0.30, order="wak")
    e2 = ExteriorOrientation(1600, 2010, 1495, -0.015, 0.012, 0.31, order="wak")
    M = np.array([[1290.0, 2140.0, 137.0]])
    m1, m2 = project(M, e1, io), project(M, e2, io)
    c, d = epipolar_segment(m1, e1, e2, io, 100.0, 200.0)
    v, w = (d - c)[0], (m2 - c)[0]
    t = v @ w / (v @ v)
    assert 0 < t < 1 and round(t, 3) == 0.353           # (137 − 100)/(200 − 100) in projective measure
    assert abs(v[0] * w[1] - v[1] * w[0]) / np.linalg.norm(v) < 1e-9


def test_segment_normal_case_parallax():
    io = InteriorOrientation(100.0)
    c, d = epipolar_segment([[5.0, 3.0]], ExteriorOrientation(0, 0, 1000), ExteriorOrientation(400, 0, 1000),
                            io, 0.0, 500.0)
    np.testing.assert_allclose(c, [[5.0 - 40.0, 3.0]])  # p = b·f/H: 400·100/1000
    np.testing.assert_allclose(d, [[5.0 - 80.0, 3.0]])  # 400·100/500


def test_flat_plane_and_z_min_itself():
    """A plane exactly at Z_min is found with one coarse step: Z_i starts at i = 0 (the book's i = 1 would miss it)."""
    sc = terrain_scene(extent=60.0, spacing=0.25, relief=0.0, n_buildings=0, seed=2)
    io = InteriorOrientation(35.0)
    eos = [ExteriorOrientation(26.0, 30.0, 250.0), ExteriorOrientation(34.0, 30.0, 250.0)]
    imgs = [render_image(sc, io, e, (160, 160), pixel_size=0.02).image for e in eos]
    X, Y = np.meshgrid(np.arange(28.5, 31.6, 1.0), np.arange(27.0, 33.1, 1.5))   # inside the overlap
    r = dsm_vertical_line(imgs, io, eos, X, Y, 100.0, 110.0, pixel_size=0.02, steps=(1.0,), window_spacing=0.25)
    assert r.valid.all()
    np.testing.assert_array_equal(r.Z, 100.0)
    r = dsm_vertical_line(imgs, io, eos, X, Y, 95.0, 110.0, pixel_size=0.02, steps=(0.7, 0.1, 0.02),
                          window_spacing=0.25)
    # B/H = 8/150, GSD 0.086 m: 0.1 px of parallax is 0.16 m of height
    assert np.max(np.abs(r.Z - 100.0)) <= 0.16 and abs(np.mean(r.Z) - 100.0) < 0.05


@pytest.fixture(scope="module")
def block():
    """Four vertical images over a town (≈ 65 % overlap both ways), GSD ≈ 0.14 m, B/H = 0.08."""
    sc = terrain_scene(extent=120.0, spacing=0.25, n_buildings=5, n_trees=4, seed=7)
    io = InteriorOrientation(35.0)
    cs = [(50, 50), (70, 50), (50, 70), (70, 70)]
    eos = [ExteriorOrientation(x, y, 350.0, *np.random.default_rng(i).normal(0, 0.01, 3)) for i, (x, y) in enumerate(cs)]
    imgs = [render_image(sc, io, e, (400, 400), pixel_size=0.02, noise=0.01, seed=i).image for i, e in enumerate(eos)]
    X, Y = np.meshgrid(np.arange(45.0, 75.1, 2.0), np.arange(45.0, 75.1, 2.0))
    dist = RegularGridInterpolator((sc.y, sc.x), sc.discontinuity_distance(1.0))(
        np.column_stack([Y.ravel(), X.ravel()])).reshape(X.shape)
    return sc, io, eos, imgs, X, Y, sc.surface_at(X, Y), dist


def test_vertical_line_recovers_the_terrain(block):
    sc, io, eos, imgs, X, Y, truth, dist = block
    r = dsm_vertical_line(imgs[:2], io, eos[:2], X, Y, 90.0, 135.0, pixel_size=0.02, half_window=3,
                          window_spacing=0.25)
    err = r.Z - truth
    away = dist > 2.0                                   # more than 2 m from walls and canopy edges
    assert away.sum() > 150
    assert np.nanmedian(np.abs(err[away])) < 0.12       # ≈ GSD; ΔZ ends at 0.05 m
    assert np.mean(~(np.abs(err[away]) < 1.0)) < 0.02   # gross errors (or no height) < 2 %


def test_multi_image_beats_one_pair_at_discontinuities(block):
    sc, io, eos, imgs, X, Y, truth, dist = block
    kw = dict(pixel_size=0.02, half_window=3, window_spacing=0.25)
    pair = dsm_vertical_line(imgs[:2], io, eos[:2], X, Y, 90.0, 135.0, **kw)
    multi = dsm_multi_image(imgs, io, eos, X, Y, 90.0, 135.0, **kw)
    assert len(multi.pairs) == 6 and set(np.unique(multi.pair[multi.valid])) <= set(range(6))
    gross = [np.mean(~(np.abs(r.Z - truth) < 1.0)) for r in (pair, multi)]
    near = dist <= 2.0
    gross_near = [np.mean(~(np.abs(r.Z - truth)[near] < 1.0)) for r in (pair, multi)]
    assert gross[1] < gross[0] and gross_near[1] < gross_near[0]
    away = dist > 2.0
    assert np.nanmedian(np.abs((multi.Z - truth)[away])) < 0.12
    # R of the chosen pair is the maximum over pairs, so never below the single pair's
    both = np.isfinite(pair.correlation) & np.isfinite(multi.correlation)
    assert np.all(multi.correlation[both] >= pair.correlation[both] - 1e-12)


def test_nodes_outside_the_overlap_are_not_guessed(block):
    sc, io, eos, imgs, X, Y, truth, dist = block
    Xo, Yo = np.meshgrid([5.0, 60.0], [60.0])            # X = 5 m is outside both images
    r = dsm_vertical_line(imgs[:2], io, eos[:2], Xo, Yo, 90.0, 135.0, pixel_size=0.02, window_spacing=0.25)
    assert not r.valid[0, 0] and np.isnan(r.Z[0, 0]) and r.pair[0, 0] == -1
    assert r.valid[0, 1]
