"""§3.6 self-calibration, §3.8 rigs, §3.9 rolling shutter and corridors (photolib.bundle extensions).

Expected values: synthetic ground truth (seeded), the dense engine photolib.lsq.solve_normal_equations,
sympy (the models of photolib.derivations) and the book's count formulas.
"""

import numpy as np
import pytest

from photolib import synthetic
from photolib.bundle import (DISTORTION_NAMES, IO_NAMES, bundle_adjustment, check_point_statistics,
                             count_rig_unknowns, count_rolling_shutter_unknowns, count_self_calibration_unknowns,
                             rig_bundle_adjustment, rig_design_matrix, rig_image_orientation,
                             rolling_shutter_bundle_adjustment, rolling_shutter_project,
                             self_calibrating_bundle_adjustment, self_calibration_correction_equations)
from photolib.camera import InteriorOrientation
from photolib.derivations import self_calibration_model
from photolib.errors import ConvergenceError, DegenerateGeometryError, InputError
from photolib.lsq import (GlobalBlockCorrectionEquations, global_block_equations_dense, solve_block_normal_equations,
                          solve_normal_equations)

TRUE_IO = InteriorOrientation(f=100.0, x0=0.05, y0=-0.03, k1=-2e-6, k2=1e-10, k3=0.0, p1=3e-6, p2=-2e-6)


@pytest.fixture(scope="module")
def calibration_block():
    return synthetic.aerial_block(3, 6, io=TRUE_IO, strip_heights=(800, 1000, 1200), forward_overlap=0.7,
                                  side_overlap=0.5, angle_sigma=np.radians(4), relief=200, points_per_image=40,
                                  sigma=0.003, n_check=10, seed=2)


# --- the solver with block-wide unknowns ---------------------------------------------------------
def test_global_reduction_equals_dense_solution():
    rng = np.random.default_rng(0)
    nf, npt, q, g, r = 5, 12, 6, 4, 2
    fr = np.repeat(np.arange(nf), 10)
    pt = np.concatenate([rng.choice(npt, 10, replace=False) for _ in range(nf)])
    m = fr.size
    eq = GlobalBlockCorrectionEquations(frame=fr, point=pt, B1=rng.normal(size=(m, r, q)), B2=rng.normal(size=(m, r, 3)),
                                        L=rng.normal(size=(m, r)), P=rng.uniform(0.5, 2, (m, r)),
                                        B3=rng.normal(size=(m, r, g)))
    free = np.ones(npt, bool)
    free[[0, 1]] = False
    sol = solve_block_normal_equations(eq, nf, npt, free_points=free, covariance=True)
    B, L, P = global_block_equations_dense(eq, nf, npt, free)
    d, Q = solve_normal_equations(B, L, P)
    nq = nf * q
    assert np.allclose(d[:nq], sol.delta1.ravel(), atol=1e-10)
    assert np.allclose(d[nq:nq + g], sol.delta3, atol=1e-10)
    assert np.allclose(d[nq + g:], sol.delta2[free].ravel(), atol=1e-10)
    assert np.allclose(Q[nq:nq + g, nq:nq + g], sol.Q3, atol=1e-12)
    assert np.allclose(Q[:nq, nq:nq + g], sol.Q13.reshape(nq, g), atol=1e-12)
    fi = np.flatnonzero(free)
    for j, p in enumerate(fi):
        assert np.allclose(Q[nq + g + 3 * j:nq + g + 3 * j + 3, nq + g + 3 * j:nq + g + 3 * j + 3], sol.Q2[p], atol=1e-12)
        assert np.allclose(Q[nq + g + 3 * j:nq + g + 3 * j + 3, nq:nq + g], sol.Q23[p], atol=1e-12)


# --- §3.6 self-calibration ---------------------------------------------------------------------
def test_self_calibration_jacobian_matches_sympy_model(calibration_block):
    blk = calibration_block
    o = blk.observations
    sel = np.arange(0, len(o), 37)
    io = np.array([100.0, 0.05, -0.03, -2e-6, 1e-10, 1e-15, 3e-6, -2e-6])
    eq = self_calibration_correction_equations(o.image[sel], o.point[sel], o.xy[sel], blk.cameras, blk.points, io,
                                               IO_NAMES, blk.order)
    res, jac = self_calibration_model(blk.order).compile()
    c, X = blk.cameras[o.image[sel]], blk.points[o.point[sel]]
    args = [*c.T, *X.T, *io, o.xy[sel, 0], o.xy[sel, 1]]
    J = jac(*args).reshape(2, 17, -1).transpose(2, 0, 1)
    assert np.allclose(eq.B1, J[:, :, :6]) and np.allclose(eq.B2, J[:, :, 6:9]) and np.allclose(eq.B3, J[:, :, 9:])
    assert np.allclose(eq.L, res(*args).T)


def test_self_calibration_recovers_distortion_and_io_within_predicted_sigma(calibration_block):
    blk = calibration_block
    c0, p0 = blk.start_values(seed=1)
    r = self_calibrating_bundle_adjustment(blk.observations, c0, p0, InteriorOrientation(f=100.0),
                                           control={i: blk.points[i] for i in blk.control}, sigma_image=0.003,
                                           order=blk.order)
    assert 0.8 < r.mu / blk.sigma < 1.2
    for nm in IO_NAMES:
        err = getattr(r.io, nm) - getattr(TRUE_IO, nm)
        assert abs(err) < 3.5 * r.io_std[nm], (nm, err, r.io_std[nm])
    # the recovered distortion field agrees with the true one far better than no correction
    grid = np.stack(np.meshgrid(np.linspace(-45, 45, 7), np.linspace(-45, 45, 7)), -1).reshape(-1, 2)
    from photolib.camera import distortion_correction
    true_d = distortion_correction(grid, TRUE_IO)
    assert np.sqrt(np.mean((distortion_correction(grid, r.io) - true_d) ** 2)) < 0.1 * np.sqrt(np.mean(true_d ** 2))
    # the correlation report: symmetric, unit diagonal, f strongly tied to Z_S in this block
    rep = r.correlations
    assert np.allclose(np.diag(rep.among), 1) and np.allclose(rep.among, rep.among.T)
    assert abs(rep.with_eo[rep.names.index("f"), 2]) > 0.9
    assert ("f", "Z_S (an image)") in [(a, b) for a, b, _ in rep.high()]
    # checking with a plain bundle: the check points are better with self-calibration than without
    plain = bundle_adjustment(blk.observations, c0, p0, InteriorOrientation(f=100.0),
                              control={i: blk.points[i] for i in blk.control}, sigma_image=0.003, order=blk.order)
    assert plain.mu > 2 * r.mu


def test_flat_terrain_and_nadir_images_make_f_and_zs_inseparable():
    blk = synthetic.aerial_block(2, 5, relief=0.0, angle_sigma=0.0, height_sigma=0.0, sigma=0.0, seed=1)
    c0, p0 = blk.start_values(seed=1)
    with pytest.raises(DegenerateGeometryError, match=r"cannot separate.*\bf\b.*Z_S"):
        self_calibrating_bundle_adjustment(blk.observations, c0, p0, InteriorOrientation(f=100.0), calibrate=("f",),
                                           control={i: blk.points[i] for i in blk.control})


def test_self_calibration_bad_input(calibration_block):
    blk = calibration_block
    c0, p0 = blk.start_values(seed=1)
    with pytest.raises(InputError, match="calibrate"):
        self_calibrating_bundle_adjustment(blk.observations, c0, p0, InteriorOrientation(f=100.0), calibrate=("f", "q"))
    with pytest.raises(InputError, match="io0"):
        self_calibrating_bundle_adjustment(blk.observations, c0, p0, 100.0)


# --- §3.8 rigs ---------------------------------------------------------------------------------------
def test_rig_image_orientation_equals_composed_rotation():
    from photolib.rotation import rotation_matrix
    e = np.array([100.0, 200.0, 700.0, 0.02, -0.01, 0.3])
    mnt = np.array([0.2, -0.1, 0.05, 0.01, 0.7, -0.02])
    eo2 = rig_image_orientation(e, mnt, "kaw")
    A1 = rotation_matrix(*e[3:], "kaw")
    assert np.allclose(eo2[:3], e[:3] + A1 @ mnt[:3])
    assert np.allclose(rotation_matrix(*eo2[3:], "kaw"), A1 @ rotation_matrix(*mnt[3:], "kaw"))


def test_rig_adjustment_recovers_mounting_elements():
    rb = synthetic.rig_block(seed=0)
    rng = np.random.default_rng(5)
    e0 = rb.exposures + np.c_[rng.normal(0, 3, (len(rb.exposures), 3)), rng.normal(0, 0.01, (len(rb.exposures), 3))]
    m0 = rb.mounts.copy()
    m0[:, :3] = 0.0
    m0[:, 3:] += rng.normal(0, 0.01, (4, 3))
    p0 = rb.points + rng.normal(0, 3, rb.points.shape)
    res = rig_bundle_adjustment(rb.observations, rb.exposure_of_image, rb.camera_of_image, e0, m0, p0, rb.ios,
                                control={i: rb.points[i] for i in rb.control}, sigma_image=rb.sigma)
    assert 0.8 < res.mu / rb.sigma < 1.2
    assert np.all(np.abs(res.mounts - rb.mounts) < 3.5 * res.mounts_std)
    assert res.n_unknowns == count_rig_unknowns(len(rb.exposures), 5, len(rb.points) - len(rb.control), "rig")


def _fig310_rig_block():
    """The block of fig. 3.10 as a stereo rig (fig. 3.18): P1/P2 and P3/P4 two exposures of one camera pair.

    Layout reconstructed from the text (§3.5/§3.8): tie points 1, 2, 5, 6 seen in all four images,
    control 3, 4 (P1, P2) and 7, 8 (P3, P4); base 500 m along the reference camera's x axis. Noise-free.
    """
    from types import SimpleNamespace
    from photolib.single_image import project_to_images
    deg = np.pi / 180
    io = InteriorOrientation(f=100.0)
    points = np.array([[1000, 1000, 12.0], [1500, 1000, 15.0], [1000, 1250, 20.0], [1500, 1250, 5.0],
                       [1000, 500, 8.0], [1500, 500, 10.0], [1000, 250, 14.0], [1500, 250, 9.0]])
    tie = np.array([True, True, False, False, True, True, False, False])
    exposures = np.array([[1000, 1000, 1000, 0.5 * deg, 1.0 * deg, 0.3 * deg],
                          [1000, 500, 998, 0.2 * deg, -0.6 * deg, -0.4 * deg]])
    mounts = np.array([[500.0, 3.0, 2.0, -0.9 * deg, -0.2 * deg, 0.2 * deg]])
    cams = np.vstack([exposures[0], rig_image_orientation(exposures[0], mounts[0], "kaw"),
                      exposures[1], rig_image_orientation(exposures[1], mounts[0], "kaw")])
    visible = {0: [0, 1, 2, 3, 4, 5], 1: [0, 1, 2, 3, 4, 5], 2: [0, 1, 4, 5, 6, 7], 3: [0, 1, 4, 5, 6, 7]}
    image = np.concatenate([np.full(6, j) for j in range(4)])
    point = np.concatenate([visible[j] for j in range(4)])
    xy, _ = project_to_images(cams, image, points[point], io, "kaw")
    return SimpleNamespace(ios=(io, io), exposures=exposures, mounts=mounts, points=points, tie=tie,
                           exposure_of_image=np.array([0, 0, 1, 1]), camera_of_image=np.array([0, 1, 0, 1]),
                           observations=dict(image=image, point=point, xy=xy))



def test_fig318_rig_system_has_fewer_unknowns_and_the_same_equations():
    blk = _fig310_rig_block()
    free = blk.tie
    A_rig, L_rig = rig_design_matrix(blk.observations, blk.exposure_of_image, blk.camera_of_image, blk.exposures,
                                     blk.mounts, blk.points, blk.ios, free_points=free)
    A_free, L_free = rig_design_matrix(blk.observations, blk.exposure_of_image, blk.camera_of_image, blk.exposures,
                                       blk.mounts, blk.points, blk.ios, free_points=free, parameterisation="free")
    assert A_rig.shape == (48, 30) and A_free.shape == (48, 36)
    assert np.allclose(L_rig, 0, atol=1e-9) and np.allclose(L_free, 0, atol=1e-9)     # noise-free truth
    assert count_rig_unknowns(2, 2, 4, "rig") == 30 and count_rig_unknowns(2, 2, 4, "free") == 36
    # the rig system at the truth is the free one with P2/P4 columns chained through (3.8.5)/(3.8.8): full rank
    assert np.linalg.matrix_rank(A_rig) == 30


def test_rig_without_reference_image_is_rejected():
    blk = _fig310_rig_block()
    with pytest.raises(InputError, match="reference"):
        rig_bundle_adjustment(blk.observations, blk.exposure_of_image, np.array([1, 2, 0, 1]), blk.exposures,
                              blk.mounts, blk.points, blk.ios)


# --- §3.9 rolling shutter -----------------------------------------------------------------------
def test_rolling_shutter_projection_zero_rates_is_frame_projection_and_round_trips():
    blk = synthetic.aerial_block(1, 3, f=8.8, frame_size=13.2, flying_height=100.0, sigma=0.0, seed=4)
    o = blk.observations
    xy0 = rolling_shutter_project(blk.cameras, None, blk.points[o.point], blk.io, blk.order, image=o.image)
    assert np.allclose(xy0, blk.xy_true, atol=1e-10)
    rates = np.tile([0.0227, 0.001, -0.002, 4e-5, -3e-5, 5e-5], (blk.n_images, 1))
    xy, its = rolling_shutter_project(blk.cameras, rates, blk.points[o.point], blk.io, blk.order, image=o.image,
                                      return_iterations=True)
    assert its < 10
    # consistency: the frame EO of each point's own line projects it to the same place (3.9.1)/(3.9.2)
    eo_line = blk.cameras[o.image] + rates[o.image] * xy[:, :1]
    from photolib.single_image import project_to_images
    back, _ = project_to_images(eo_line, np.arange(len(o)), blk.points[o.point], blk.io, blk.order)
    assert np.allclose(back, xy, atol=1e-9)


def test_rolling_shutter_projection_raises_when_it_cannot_converge():
    blk = synthetic.aerial_block(1, 2, f=8.8, frame_size=13.2, flying_height=100.0, sigma=0.0, seed=4)
    wild = np.tile([0.0, 0.0, 0.0, 0.0, 0.0, 0.3], (blk.n_images, 1))
    first = np.zeros(len(blk.points), int)                 # every point in the first image
    with pytest.raises(ConvergenceError, match="rolling-shutter"):
        rolling_shutter_project(blk.cameras, wild, blk.points, blk.io, blk.order, image=first, max_iter=30)
    with pytest.raises(InputError, match="which one each point belongs to"):
        rolling_shutter_project(blk.cameras, wild, blk.points, blk.io, blk.order)   # several images, no `image`


@pytest.mark.parametrize("model", ["full", "linear"])
def test_rolling_shutter_adjustment_recovers_rates_noise_free(model):
    rb = synthetic.rolling_shutter_block(sigma=0.0, model=model)
    b = rb.block
    c0, p0 = b.start_values(seed=2, centre_sigma=1.0, angle_sigma=np.radians(0.5), point_sigma=1.0)
    res = rolling_shutter_bundle_adjustment(rb.observations, c0, p0, b.io, model=model,
                                            control={i: b.points[i] for i in b.control}, sigma_image=0.0015)
    assert np.allclose(res.rates, rb.rates, atol=1e-8)
    assert np.allclose(res.cameras, b.cameras, atol=1e-6)
    n_free = len(b.points) - len(b.control)
    assert res.n_unknowns == count_rolling_shutter_unknowns(b.n_images, n_free, model)


def test_rolling_shutter_adjustment_with_noise_is_statistically_honest():
    # the simplified model (9 unknowns per image); with noise the full 12-unknown model is too weakly
    # determined on this block to converge — angular and linear rates are nearly interchangeable
    rb = synthetic.rolling_shutter_block(sigma=0.0015, seed=0, model="linear")
    b = rb.block
    c0, p0 = b.start_values(seed=2, centre_sigma=1.0, angle_sigma=np.radians(0.5), point_sigma=1.0)
    res = rolling_shutter_bundle_adjustment(rb.observations, c0, p0, b.io, control={i: b.points[i] for i in b.control},
                                            sigma_image=0.0015, model="linear")
    assert 0.8 < res.mu / 0.0015 < 1.25
    z = (res.rates[:, :3] - rb.rates[:, :3]) / res.rates_std[:, :3]
    assert np.sqrt(np.mean(z ** 2)) < 1.5 and np.abs(z).max() < 4.5


# --- §3.9 corridor with a dynamic control point -----------------------------------------------------
def test_corridor_with_dynamic_control_point_beats_gnss_only():
    rms = {}
    for with_target in (False, True):
        co = synthetic.corridor_strip(with_target=with_target)
        b = co.block
        c0, p0 = b.start_values(seed=3, centre_sigma=1.0, point_sigma=2.0)
        ctrl = (b.control, b.points[b.control]) if with_target else None
        res = bundle_adjustment(b.observations, c0, p0, b.io, gnss=co.gnss, gnss_sigma=0.03, control=ctrl,
                                control_sigma=0.03 if with_target else None, sigma_image=0.002)
        rms[with_target] = check_point_statistics(res, b.points, b.check).rms
    assert rms[True][1] < 0.1 and rms[False][1] > 5 * rms[True][1]      # cross-track: the roll about the line


def test_perfectly_straight_corridor_without_ground_control_is_a_datum_defect():
    co = synthetic.corridor_strip(with_target=False, wander=0.0, gnss_sigma=0.0)
    b = co.block
    gn = co.gnss.copy()
    gn[:, 1] = 0.0
    gn[:, 2] = gn[0, 2]
    c0, p0 = b.start_values(seed=3, centre_sigma=1.0, point_sigma=2.0)
    with pytest.raises(DegenerateGeometryError, match="datum"):
        bundle_adjustment(b.observations, c0, p0, b.io, gnss=gn, gnss_sigma=0.03)


# --- counts ----------------------------------------------------------------------------------------
def test_counts_equal_system_sizes(calibration_block):
    blk = calibration_block
    o = blk.observations
    io = np.array([100.0, 0, 0, 0, 0, 0, 0, 0])
    for names in (IO_NAMES, DISTORTION_NAMES):
        eq = self_calibration_correction_equations(o.image, o.point, o.xy, blk.cameras, blk.points, io, names,
                                                   blk.order)
        B, _, _ = global_block_equations_dense(eq, blk.n_images, len(blk.points))
        assert B.shape[1] == count_self_calibration_unknowns(blk.n_images, len(blk.points), names)
    assert eq.B1.shape[2] + eq.B2.shape[2] + 8 == 17          # the 17 coefficients of (3.6.3)
    assert count_rig_unknowns(1000, 5, 0, "free") == 30000 and count_rig_unknowns(1000, 5, 0, "rig") == 6024
    assert count_rolling_shutter_unknowns(1, 0, "full") == 12 and count_rolling_shutter_unknowns(1, 0, "linear") == 9


@pytest.mark.parametrize("call", [lambda: count_rig_unknowns(10, 0, 0), lambda: count_rig_unknowns(10, 5, 0, "x"),
                                  lambda: count_rolling_shutter_unknowns(3, 0, "cubic"),
                                  lambda: count_rig_unknowns(-1, 5)])
def test_counts_reject_bad_input(call):
    with pytest.raises(InputError):
        call()
