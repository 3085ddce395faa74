"""photolib.trueortho (Chapter 7, §7.5, §7.6, §7.8) against synthetic ground truth and sympy.

Expected values: brute-force ray marching (an independent implementation), the scene's known
texture and DSM (photolib.synthetic), scipy's k-d tree, closed-form projective geometry, sympy,
and the book's counts (§7.8: P = 100, S = 2 → N = 201, M = 200).
"""

import numpy as np
import pytest
import sympy as sp

from photolib.camera import ExteriorOrientation, InteriorOrientation
from photolib.derivations import orthophoto as d
from photolib.errors import DegenerateGeometryError
from photolib.rectify import RasterGrid, dem_height, frame_projector, orthorectify
from photolib.synthetic import render_image, terrain_scene
from photolib.trueortho import (index_matrix, lsq_dsm_ortho, lsq_unknown_count, ortho_from_points, true_ortho_multi,
                                visibility_mask)


def scene_grid(sc):
    """The scene's DSM as a north-up raster (rows flipped) and its grid."""
    s = sc.spacing
    return RasterGrid(sc.x[0] - s / 2, sc.y[-1] + s / 2, s, sc.surface.shape)


# --- §7.5 visibility ------------------------------------------------------------------------
def test_visibility_agrees_with_ray_marching_on_a_box_building():
    dsm = np.zeros((81, 81))
    dsm[20:30, 52:62] = 25.0
    grid = RasterGrid(0.0, 81.0, 1.0, (81, 81))
    S = (40.5, 40.5, 300.0)
    radial = visibility_mask(dsm, grid, S)
    brute = visibility_mask(dsm, grid, S, method="raymarch")
    assert (radial == brute).mean() >= 0.998
    assert 10 < (radial == 0).sum() < 100
    # the hidden cells lie behind the building, away from the nadir (north-east of it)
    r, c = np.nonzero(radial == 0)
    assert r.min() < 20 and c.max() >= 62


def test_visibility_on_a_town_agrees_with_ray_marching():
    sc = terrain_scene(extent=60.0, spacing=0.5, n_buildings=3, seed=4)
    grid, dsm = scene_grid(sc), sc.surface[::-1].copy()
    S = (15.0, 45.0, dsm.max() + 80.0)
    radial = visibility_mask(dsm, grid, S)
    brute = visibility_mask(dsm, grid, S, method="raymarch")
    assert (radial == brute).mean() >= 0.998
    assert (radial == 0).sum() > 100


def test_group_occlusion_needs_the_running_maximum():
    """A low wall hidden behind a tall one: comparing only neighbours would call it visible (pitfall 19)."""
    dsm = np.zeros((1, 30))
    dsm[0, 5] = 20.0                  # tall wall near the nadir
    dsm[0, 8] = 5.0                   # low wall in its shadow (tan α = 8/35 < 5/20)
    grid = RasterGrid(0.0, 1.0, 1.0, (1, 30))
    vis = visibility_mask(dsm, grid, (0.5, 0.5, 40.0))[0]
    # the tall wall's top (r = 5, tan α = 0.25) shadows the ground up to r = 10 (X = 10.5); the low
    # wall's own neighbour (the ramp at r = 7.5, Z = 2.5: tan α = 0.2) would not hide it
    assert vis[8] == 0 and vis[7:10].max() == 0 and vis[:6].min() == 1
    assert vis[11:].min() == 1


# --- §7.5 index matrix (Fig. 7.12) -------------------------------------------------------------
def test_index_matrix_of_a_vertical_box_matches_the_projective_geometry():
    # vertical camera, ground pixel 1 m, H = 100 m: the roof is the base scaled by H/(H − h) about the nadir
    proj = lambda X, Y, Z: (-8.0 + (-Y + 8.0) * 100 / (100 - Z), 23.0 + (X - 23.0) * 100 / (100 - Z))
    box = [5.2, 8.9, -4.4, -1.4, 0.0, 11.0]
    m = index_matrix((10, 11), proj, [box], (23.0, 8.0, 100.0))
    rows, cols = np.mgrid[0:10, 0:11]
    s = 100 / 89
    roof = ((cols >= 23 + (5.2 - 23) * s) & (cols <= 23 + (8.9 - 23) * s)
            & (rows >= -8 + (1.4 + 8) * s) & (rows <= -8 + (4.4 + 8) * s))
    assert np.array_equal(m == 1, roof)
    assert set(np.unique(m)) == {0, 1, 2}
    # the visible walls face the nadir (north and east): no wall pixel south or west of the roof
    r2, c2 = np.nonzero(m == 2)
    assert r2.max() <= np.nonzero(roof)[0].max() and c2.min() >= np.nonzero(roof)[1].min()


def test_index_matrix_reproduces_the_printed_fig_7_12():
    printed = np.zeros((10, 11), int)
    printed[2, 5:9] = 2
    printed[3:6, 3:8] = 1
    printed[3:6, 8] = 2
    eo = ExteriorOrientation(46.0, 16.0, 200.0)
    project = frame_projector(eo, InteriorOrientation(100.0), 1.0, (41, 47))
    crop = lambda X, Y, Z: (lambda r, c: (r - 28.0, c))(*project(X, Y, Z))
    box = [10.4, 17.8, -8.8, -2.8, 0.0, 22.0]
    assert np.array_equal(index_matrix((10, 11), crop, [box], eo.center), printed)


# --- §7.5 multi-image true orthophoto (Fig. 7.13) --------------------------------------------------
@pytest.fixture(scope="module")
def town():
    sc = terrain_scene(extent=60.0, spacing=0.5, n_buildings=3, building_size=(8, 14), building_height=(8, 14),
                       relief=2.0, seed=5)
    io = InteriorOrientation(35.0)
    H = sc.surface.max() + 100.0
    eos = [ExteriorOrientation(30 + dx, 30 + dy, H) for dx, dy in [(-12, -12), (12, -12), (-12, 12), (12, 12), (0, 0)]]
    shape, pix = (160, 160), 0.15
    images = [render_image(sc, io, eo, shape, pixel_size=pix, supersample=1).image for eo in eos]
    return sc, io, eos, images, shape, pix


def test_true_ortho_has_no_ghost_roofs_and_no_dead_zones(town):
    sc, io, eos, images, shape, pix = town
    dgrid = scene_grid(sc)
    dsm, dtm, albedo = sc.surface[::-1].copy(), sc.ground[::-1].copy(), sc.albedo[::-1].copy()
    grid = RasterGrid(5.0, 55.0, 0.5, (100, 100))
    X, Y = grid.centres()
    truth = dem_height(albedo, dgrid, X, Y)
    roof = dem_height(sc.buildings[::-1].astype(float), dgrid, X, Y) > 0.99
    projectors = [frame_projector(eo, io, pix, shape) for eo in eos]
    true = true_ortho_multi(images, projectors, [eo.center for eo in eos], dsm, dgrid, grid)
    over_dtm = orthorectify(images[0], projectors[0], dtm, dgrid, grid)
    over_dsm = orthorectify(images[0], projectors[0], dsm, dgrid, grid)
    # every dead zone of image 0 is filled from another image; what no image sees is the one-cell
    # wall ramp of the gridded DSM itself (seen only at grazing angles)
    dead = true.source < 0
    wall = dem_height(sc.discontinuity_distance()[::-1], dgrid, X, Y) <= 0.5
    assert dead.mean() < 0.01 and np.all(wall[dead])
    assert (true.visible[0] == 0).mean() > 0.05
    err = np.abs(true.image - truth)
    assert np.nanmean(err > 0.1) < 0.005 and np.abs(true.image[roof] - truth[roof]).mean() < 0.02
    # one image over the DTM: the roofs lean (wrong on the roof area); over the DSM: roofs right,
    # but the dead zones repeat the roof ("double roof")
    assert np.nanmean(np.abs(over_dtm[roof] - truth[roof])) > 5 * np.abs(true.image[roof] - truth[roof]).mean()
    ghost = np.abs(over_dsm - truth) > 0.1
    assert np.nanmean(ghost) > 10 * np.mean(err > 0.1)
    assert np.nanmean(np.abs(over_dsm[roof] - truth[roof])) < 0.03
    # the chosen ray is the unoccluded one closest to nadir
    tan = np.stack([np.hypot(X - eo.Xs, Y - eo.Ys) / (eo.Zs - dem_height(dsm, dgrid, X, Y)) for eo in eos])
    tan = np.where(true.visible.astype(bool), tan, np.inf)
    expected = np.where(np.isinf(tan.min(axis=0)), -1, np.argmin(tan, axis=0))
    assert np.array_equal(true.source, expected) and (true.source == 4).mean() > 0.1


# --- §7.6 orthophoto from a point cloud --------------------------------------------------------
def test_flat_cloud_gives_the_texture():
    rng = np.random.default_rng(0)
    pts = np.column_stack([rng.uniform(0, 20, 20000), rng.uniform(0, 20, 20000), np.zeros(20000)])
    d = 0.5 + 0.01 * pts[:, 0] + 0.02 * pts[:, 1]                  # a linear ramp: means are exact at centres on average
    grid = RasterGrid(2.0, 18.0, 1.0, (16, 16))
    X, Y = grid.centres()
    ramp = 0.5 + 0.01 * X + 0.02 * Y
    for method in ("accumulate", "radius_mean", "idw", "max_z"):
        out = ortho_from_points(pts, d, grid, method)
        assert np.nanmax(np.abs(out - ramp)) < 0.01, method


def test_radius_mean_equals_a_brute_force_mean():
    rng = np.random.default_rng(1)
    pts = np.column_stack([rng.uniform(0, 5, 300), rng.uniform(0, 5, 300), rng.normal(size=300)])
    d = rng.uniform(size=300)
    grid = RasterGrid(0.0, 5.0, 1.0, (5, 5))
    out = ortho_from_points(pts, d, grid, "radius_mean", max_points=300)
    X, Y = grid.centres()
    for i, j in [(0, 0), (2, 3), (4, 4)]:
        near = np.hypot(pts[:, 0] - X[i, j], pts[:, 1] - Y[i, j]) <= 1.0
        assert out[i, j] == pytest.approx(d[near].mean())


def test_max_z_rule_drops_wall_points():
    # ground (d = 0.2) and a roof (d = 0.9, Z = 10) over X > 10 and a wall of points at X = 10
    rng = np.random.default_rng(2)
    g = np.column_stack([rng.uniform(0, 20, 8000), rng.uniform(0, 10, 8000)])
    z = np.where(g[:, 0] > 10, 10.0, 0.0)
    wall = np.column_stack([np.full(2000, 10.0), rng.uniform(0, 10, 2000), rng.uniform(0, 10, 2000)])
    pts = np.vstack([np.column_stack([g, z]), wall])
    d = np.r_[np.where(z > 0, 0.9, 0.2), np.full(2000, 0.5)]                 # walls are mid-grey
    grid = RasterGrid(0.0, 10.0, 1.0, (10, 20))
    mean = ortho_from_points(pts, d, grid, "radius_mean")
    top = ortho_from_points(pts, d, grid, "max_z", z_tol=0.05)
    col_in = 10                                             # pixel centre X = 10.5 sees the wall within Δ
    assert np.all(np.abs(top[:, col_in] - 0.9) < 0.03)      # (the top 5 cm of the wall count as roof edge)
    assert np.all(np.abs(mean[:, col_in] - 0.9) > 0.1)      # the plain mean mixes the wall in
    assert np.allclose(top[:, :9], 0.2) and np.allclose(top[:, 11:], 0.9)


# --- §7.8 counts and least squares --------------------------------------------------------------
def test_counts_of_the_book():
    assert lsq_unknown_count(100, 2) == (201, 200)          # the book's example: N > M
    N, M = lsq_unknown_count(100, 3)
    assert M == 300 and N < M
    assert lsq_unknown_count(100, 2, eo_known=False) == (213, 200)


def test_sympy_checks_of_the_model():
    assert d.check_782_equals_732("wak") and d.check_782_equals_732("kaw")
    h = d.height_partials()
    assert sp.simplify(h["dx_dZ"] - h["dx_dZ_closed"]) == 0
    assert sp.simplify(h["dy_dZ"] - h["dy_dZ_closed"]) == 0
    c = d.correction_coefficients()
    assert c["a1"] == 1 and c["a3"] == -d.image_function(*sp.symbols("x_i y_i", real=True))
    assert len([k for k in d.correction_coefficients(eo_unknown=True) if k.startswith("a")]) == 9


def test_height_partials_function_against_finite_differences():
    from photolib.single_image import project
    eo = ExteriorOrientation(3.0, -2.0, 150.0, 0.05, -0.2, 0.3)
    io = InteriorOrientation(50.0, 0.01, -0.02)
    P = np.array([[10.0, 5.0, 20.0], [-30.0, 12.0, 5.0]])
    fn = d.height_partials_function(eo.order)
    got = fn(P[:, 0], P[:, 1], P[:, 2], *eo.vector, io.f, io.x0, io.y0)
    h = 1e-5
    up, dn = P.copy(), P.copy()
    up[:, 2] += h
    dn[:, 2] -= h
    fd = (project(up, eo, io) - project(dn, eo, io)) / (2 * h)
    assert np.allclose(got.T, fd, rtol=1e-6, atol=1e-9)


@pytest.fixture(scope="module")
def lsq_scene():
    sc = terrain_scene(extent=40.0, spacing=0.5, n_buildings=0, relief=6.0, relief_scale=15.0, texture_scale=1.5,
                       seed=3)
    io = InteriorOrientation(50.0)
    H = 250.0
    eos = []
    for a in np.radians([90.0, 210.0, 330.0]):
        dx, dy = 40 * np.cos(a), 40 * np.sin(a)
        eos.append(ExteriorOrientation(20 + dx, 20 + dy, H, -np.arctan(dy / 150), np.arctan(dx / 150), 0.0))
    gains = [1.0, 1.15, 0.9]
    images = [g * render_image(sc, io, eo, (240, 240), pixel_size=0.04).image for eo, g in zip(eos, gains)]
    grid = RasterGrid(16.0, 24.0, 0.25, (32, 32))
    X, Y = grid.centres()
    Zt = dem_height(sc.surface[::-1], scene_grid(sc), X, Y)
    Ft = dem_height(sc.albedo[::-1], scene_grid(sc), X, Y)
    from scipy.ndimage import gaussian_filter
    noise = gaussian_filter(np.random.default_rng(1).normal(size=Zt.shape), 2)
    return images, eos, io, grid, Zt, Ft, Zt + 0.3 * noise / noise.std()


def test_lsq_three_images_converge(lsq_scene):
    images, eos, io, grid, Zt, Ft, z0 = lsq_scene
    res = lsq_dsm_ortho(images, eos, io, 0.04, grid, z0)
    e0, e = np.abs(z0 - Zt), np.abs(res.dsm - Zt)
    assert np.median(e) < 0.2 * np.median(e0) and np.median(e) < 0.03
    assert np.sqrt(np.mean(e ** 2)) < 0.5 * np.sqrt(np.mean(e0 ** 2))
    assert res.gains[0] == 1.0
    assert res.gains[1:] == pytest.approx([1 / 1.15, 1 / 0.9], abs=2e-3)      # k = 1/gain
    assert np.median(np.abs(res.ortho - Ft)) < 0.01
    assert res.counts == lsq_unknown_count(32 * 32, 3)


def test_lsq_two_images_are_rank_deficient(lsq_scene):
    images, eos, io, grid, Zt, Ft, z0 = lsq_scene
    with pytest.raises(DegenerateGeometryError, match="N = 2049"):
        lsq_dsm_ortho(images[:2], eos[:2], io, 0.04, grid, z0)


def test_lsq_textureless_images_are_degenerate(lsq_scene):
    images, eos, io, grid, Zt, Ft, z0 = lsq_scene
    flat = [np.full_like(im, 0.5) for im in images]
    with pytest.raises(DegenerateGeometryError):
        lsq_dsm_ortho(flat, eos, io, 0.04, grid, z0, sigma_z0=np.inf)


def test_single_image_over_a_dense_dsm_blanks_exactly_the_restricted_pixels(town):
    """§7.5/§7.6: one image over a DSM with the ortho spacing, times the restriction matrix."""
    sc, io, eos, images, shape, pix = town
    dgrid = scene_grid(sc)
    dsm, albedo = sc.surface[::-1].copy(), sc.albedo[::-1].copy()
    grid = dgrid.window(10, 10, 100, 100)                  # ortho pixels on the DSM nodes
    one = true_ortho_multi(images[:1], [frame_projector(eos[0], io, pix, shape)], [eos[0].center], dsm, dgrid, grid)
    X, Y = grid.centres()
    restriction = visibility_mask(dem_height(dsm, dgrid, X, Y), grid, eos[0].center)
    dead = one.source < 0
    assert np.array_equal(dead, restriction == 0) and dead.mean() > 0.03
    assert np.all(np.isnan(one.image[dead]))
    truth = dem_height(albedo, dgrid, X, Y)
    assert np.mean(np.abs(one.image[~dead] - truth[~dead]) > 0.1) < 0.01


# --- §7.8 unknown exterior orientation (7.8.4) ------------------------------------------------------
def test_eo_partials_are_the_chapter_1_collinearity_partials():
    """a₄…a₉ of (7.8.4) by the chain rule through the §1.8 model (sympy) and its numpy code (finite differences)."""
    assert d.check_784_chain_rule("kaw") and d.check_784_chain_rule("wak")
    from photolib.single_image import project
    io = InteriorOrientation(50.0, 0.01, -0.02)
    P = np.array([[10.0, 5.0, 20.0], [-30.0, 12.0, 5.0]])
    for order in ("kaw", "wak"):
        eo = ExteriorOrientation(3.0, -2.0, 150.0, 0.05, -0.2, 0.3, order=order)
        got = d.eo_partials_function(order)(P[:, 0], P[:, 1], P[:, 2], *eo.vector, io.f, io.x0, io.y0)
        for j in range(6):
            h = 1e-4 if j < 3 else 1e-7
            up, dn = eo.vector.copy(), eo.vector.copy()
            up[j] += h
            dn[j] -= h
            fd = (project(P, ExteriorOrientation(*up, order=order), io, distortion=False)
                  - project(P, ExteriorOrientation(*dn, order=order), io, distortion=False)) / (2 * h)
            assert np.allclose(got[:, j].T, fd, rtol=1e-5, atol=1e-8), (order, j)


def _gcps(eos, io):
    """Five ground control points on the scene surface and their exact image coordinates (mm)."""
    from photolib.single_image import project
    sc = terrain_scene(extent=40.0, spacing=0.5, n_buildings=0, relief=6.0, relief_scale=15.0, texture_scale=1.5,
                       seed=3)
    xy = np.array([[8.0, 8.0], [32.0, 8.0], [8.0, 32.0], [32.0, 32.0], [20.0, 20.0]])
    G = np.column_stack([xy, dem_height(sc.surface[::-1], scene_grid(sc), xy[:, 0], xy[:, 1])])
    return G, np.stack([project(G, eo, io) for eo in eos])


def test_lsq_unknown_eo_recovers_the_orientation_and_the_dsm(lsq_scene):
    images, eos, io, grid, Zt, Ft, z0 = lsq_scene
    G, meas = _gcps(eos, io)
    rng = np.random.default_rng(7)
    start = [ExteriorOrientation(*(eo.vector + np.r_[rng.choice([-1, 1], 3) * 0.5, rng.choice([-1, 1], 3) * 1e-3]))
             for eo in eos]                                   # 0.5 m in the centres, 1 mrad in the angles
    known = lsq_dsm_ortho(images, eos, io, 0.04, grid, z0, sigma_z0=20.0)
    res = lsq_dsm_ortho(images, start, io, 0.04, grid, z0, sigma_z0=20.0, estimate_eo=True, gcp_xyz=G, gcp_xy=meas,
                        sigma_gcp=0.1)
    centre = np.abs([e.center - t.center for e, t in zip(res.eos, eos)])
    angle = np.abs([e.vector[3:] - t.vector[3:] for e, t in zip(res.eos, eos)])
    assert centre.max() < 0.02 and angle.max() < 1e-4          # from 0.5 m and 1e-3 rad
    e_known, e = np.median(np.abs(known.dsm - Zt)), np.median(np.abs(res.dsm - Zt))
    assert e < 0.02 * np.median(np.abs(z0 - Zt)) and e < 1.5 * e_known
    assert res.gains[0] == 1.0 and res.gains[1:] == pytest.approx([1 / 1.15, 1 / 0.9], abs=2e-3)
    # the solver carries exactly N = 2P + (S − 1) + 6S unknowns: dof = photometric + GCP rows − N
    P, S = 32 * 32, 3
    N, M = lsq_unknown_count(P, S, eo_known=False)
    assert res.counts == (N, M) and res.adjustment.frames.shape == (S, 7)
    assert res.adjustment.dof == M + 2 * G.shape[0] * S - N


@pytest.mark.parametrize("n_gcp", [0, 2])
def test_lsq_unknown_eo_without_enough_gcps_names_the_datum_defect(lsq_scene, n_gcp):
    images, eos, io, grid, Zt, Ft, z0 = lsq_scene
    G, meas = _gcps(eos, io)
    kw = {} if n_gcp == 0 else {"gcp_xyz": G[:n_gcp], "gcp_xy": meas[:, :n_gcp]}
    with pytest.raises(DegenerateGeometryError, match="datum defect of 7"):
        lsq_dsm_ortho(images, eos, io, 0.04, grid, z0, estimate_eo=True, **kw)


def test_lsq_unknown_eo_collinear_gcps_are_refused(lsq_scene):
    images, eos, io, grid, Zt, Ft, z0 = lsq_scene
    G, meas = _gcps(eos, io)
    line = [0, 3, 4]                                          # (8, 8), (32, 32), (20, 20): one line in plan
    G2 = G[line].copy()
    G2[:, 2] = G2[:, 0]                                       # and in space
    with pytest.raises(DegenerateGeometryError, match="collinear"):
        lsq_dsm_ortho(images, eos, io, 0.04, grid, z0, estimate_eo=True, gcp_xyz=G2, gcp_xy=meas[:, line])
