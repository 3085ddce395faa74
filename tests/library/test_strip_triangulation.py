"""Chapter 3, §3.2–§3.4: continuation, strip polynomials, independent strips and models.

Expected values come from synthetic ground truth (photolib.strip_triangulation.layout_block) or
from the book's counting formulas; nothing is copied from our own output.
"""

import numpy as np
import pytest

from photolib import strip_triangulation as st
from photolib.errors import DegenerateGeometryError, InputError
from photolib.image_pair import SimilarityTransform
from photolib.rotation import rot_z, rotation_matrix


@pytest.fixture(scope="module")
def strip():
    blk = st.layout_block(1, 7, principal_rows=True, seed=1)
    return blk, st.layout_models(blk)


@pytest.fixture(scope="module")
def fig38():
    blk = st.layout_block(2, 4, seed=38)
    models = st.layout_models(blk)
    control = {p: blk.truth([p])[0] for p in (blk.point_at(*g) for g in
                                               [(0, 0.5), (3, 0.5), (3, -0.5), (0, -1.5), (3, -1.5)])}
    gnss = {st.centre_id(k): blk.cameras[k, :3] for k in range(8)}
    return blk, models, control, gnss, st.grid_adjacency(2, 3)


def _control(blk, grid):
    return {p: blk.truth([p])[0] for p in (blk.point_at(*g) for g in grid)}


def test_continuation_recovers_truth_noise_free(strip):
    blk, models = strip
    cs = st.continuation_strip(models)
    assert len(cs.transforms) == len(models)
    control = _control(blk, [(0, 0.5), (0, -0.5), (3, 0.0), (6, 0.5), (6, -0.5)])
    T, obj = st.orient_strip(cs.model, control)
    np.testing.assert_allclose(obj, blk.truth(cs.model.ids), atol=1e-6)


def test_double_determinations_agree_and_expose_a_blunder(strip):
    blk, models = strip
    cs = st.continuation_strip(models)
    # every interior column point (3 rows) and every interior centre is determined twice
    assert len(cs.differences) == (len(models) - 1) * 4
    assert all(cs.determinations[p] == 2 for p in cs.differences)
    assert np.all(cs.rms_difference < 1e-9)
    # a blunder in one model's tie point shows up in the differences
    bad = [m for m in models]
    p = blk.point_at(3, 0.5)
    i = bad[3].ids.index(p)
    pts = bad[3].points.copy()
    pts[i, 2] += 5.0                       # model units ≈ metres (base_length = b)
    bad[3] = st.UnitModel(bad[3].name, bad[3].ids, pts, bad[3].images)
    cs_bad = st.continuation_strip(bad)
    worst = max(cs_bad.differences, key=lambda q: np.max(np.abs(cs_bad.differences[q])))
    assert worst == p
    assert p in cs_bad.blunders(1.0)


def test_join_requires_three_points_and_the_shared_centre(strip):
    _, models = strip
    a, b = models[0], models[1]
    two = [p for p in a.common(b) if not str(p).startswith("S")][:2]
    small = st.UnitModel("b", two, b.coords(two), b.images)
    with pytest.raises(InputError, match="at least 3"):
        st.join_model(a, small)
    no_centre = [p for p in a.common(b) if not str(p).startswith("S")]
    with pytest.raises(InputError, match="projection centre"):
        st.join_model(a, st.UnitModel("b", no_centre, b.coords(no_centre), b.images))


def test_polynomial_reduces_a_quadratic_bend():
    # an uncorrected radial distortion (k1) bends the strip quadratically (§3.2)
    blk = st.layout_block(1, 10, principal_rows=True, distortion_k1=5e-9, seed=1)
    cs = st.continuation_strip(st.layout_models(blk))
    ctl_grid = [(0, 0.5), (0, -0.5), (5, 0.0), (9, 0.5), (9, -0.5), (2, 0.5), (7, -0.5)]
    control = _control(blk, ctl_grid)
    T, obj = st.orient_strip(cs.model, control)
    ids = list(cs.model.ids)
    truth = blk.truth(ids)
    check = [i for i, p in enumerate(ids) if p not in control and not str(p).startswith("S")]
    ctl_idx = [ids.index(p) for p in control]
    poly = st.fit_strip_polynomial(obj[ctl_idx], truth[ctl_idx], st.strip_axis_angle(T))
    before = np.sqrt(np.mean((obj - truth)[check] ** 2, axis=0))
    after = np.sqrt(np.mean((poly.apply(obj) - truth)[check] ** 2, axis=0))
    assert before[2] > 0.3                 # the bend is real: decimetres in Z
    assert after[2] < 0.1 * before[2]
    assert np.linalg.norm(after) < 0.1 * np.linalg.norm(before)
    assert poly.dof == 3 * len(control) - 15


def test_polynomial_exact_for_a_known_polynomial_and_rotation_invariant():
    rng = np.random.default_rng(3)
    kappa = np.radians(35.0)
    A = rot_z(kappa)
    along = np.column_stack([rng.uniform(0, 5000, 12), rng.uniform(-400, 400, 12), rng.uniform(100, 200, 12)])
    coef = np.array([[0.2, 1e-4, -2e-4, 1e-8, 3e-8], [-0.1, 2e-5, 1e-4, -2e-8, 1e-8], [0.3, -1e-4, 5e-5, 4e-8, 6e-8]])
    c = along[:, :2].mean(axis=0)
    u, v = along[:, 0] - c[0], along[:, 1] - c[1]
    mono = np.column_stack([np.ones_like(u), u, v, u * v, u * u])
    corrected = along + mono @ coef.T        # (3.2.4) in the strip-aligned system
    net, geo = along @ A.T, corrected @ A.T   # the strip runs at κ_M = 35° in the object frame
    poly = st.fit_strip_polynomial(net, geo, kappa)
    np.testing.assert_allclose(poly.apply(net), geo, atol=1e-7)
    np.testing.assert_allclose(poly.coefficients, coef, rtol=1e-6, atol=1e-12)
    np.testing.assert_allclose(poly.centre, c, atol=1e-9)


def test_polynomial_bad_input():
    net = np.column_stack([np.linspace(0, 4000, 6), np.zeros(6), np.full(6, 150.0)])
    with pytest.raises(InputError, match="at least 5"):
        st.fit_strip_polynomial(net[:4], net[:4])
    with pytest.raises(DegenerateGeometryError, match="one line"):
        st.fit_strip_polynomial(net, net)       # collinear control along the strip axis


def test_independent_strips_recover_truth():
    blk = st.layout_block(3, 5, principal_rows=True, seed=5)
    strips = [st.continuation_strip(st.layout_models(blk, [s]), name=f"strip{s}").model for s in range(3)]
    control = _control(blk, [(0, 0.5), (4, 0.5), (0, -2.5), (4, -2.5), (2, -1.5)])
    res = st.adjust_independent_units(strips, control)
    # (2, -1.5) lies in the overlap of strips 2 and 3: measured in both, k = 4 + 2 = 6
    assert res.shape == (3 * len(st.tie_pairs(strips)) + 3 * 6, 21)
    assert len(st.tie_pairs(strips)) == 2 * 5            # 5 columns in each of the two overlaps
    ids = list(res.points)
    np.testing.assert_allclose(np.array([res.points[p] for p in ids]), blk.truth(ids), atol=1e-6)


def test_independent_models_recover_truth_and_image_orientation(fig38):
    blk, models, control, gnss, adjacency = fig38
    res = st.adjust_independent_units(models, control, adjacency=adjacency)
    ids = list(res.points)
    np.testing.assert_allclose(np.array([res.points[p] for p in ids]), blk.truth(ids), atol=1e-6)
    eos = st.image_orientations(models, res.transforms)
    for k, eo in eos.items():
        np.testing.assert_allclose(eo.center, blk.cameras[k, :3], atol=1e-6)
        np.testing.assert_allclose(eo.matrix, rotation_matrix(*blk.cameras[k, 3:], blk.order), atol=1e-9)


def test_independent_models_with_noise_and_perturbed_start(fig38):
    blk = st.layout_block(2, 4, seed=38, sigma=0.005)
    models = st.layout_models(blk)
    _, _, control, gnss, adjacency = fig38
    x0 = st.initial_transforms(models, control)
    x0[:, 3:6] += np.radians(1.0)
    res = st.adjust_independent_units(models, control, gnss, adjacency=adjacency, initial=x0,
                                      sigma_gnss=0.1, sigma_control=0.05, sigma_tie=0.1)
    ids = list(res.points)
    err = np.array([res.points[p] for p in ids]) - blk.truth(ids)
    assert res.adjustment.iterations >= 2
    assert np.sqrt(np.mean(err ** 2)) < 0.5          # 5 µm image noise at 1:10 000, ~ decimetres


def test_gnss_block_full_rank_gnss_strip_singular(fig38):
    blk, models, _, gnss, adjacency = fig38
    res = st.adjust_independent_units(models, None, gnss, adjacency=adjacency)   # no ground control
    ids = list(res.points)
    np.testing.assert_allclose(np.array([res.points[p] for p in ids]), blk.truth(ids), atol=1e-6)
    s1 = st.layout_block(1, 6, principal_rows=True, seed=2)
    m1 = st.layout_models(s1)
    g1 = {st.centre_id(k): s1.cameras[k, :3] for k in range(6)}
    with pytest.raises(DegenerateGeometryError, match="roll about"):
        st.adjust_independent_units(m1, None, g1)
    one = _control(s1, [(2, 0.5)])
    x0 = st.initial_transforms(m1, one, g1)
    B, _, _ = st.unit_equations(m1, x0, None, g1)
    assert np.linalg.matrix_rank(B) == 7 * len(m1) - 1                     # the roll about the flight line
    B1, _, _ = st.unit_equations(m1, x0, one, g1)
    assert np.linalg.matrix_rank(B1) == 7 * len(m1)
    res1 = st.adjust_independent_units(m1, one, g1)
    ids = list(res1.points)
    np.testing.assert_allclose(np.array([res1.points[p] for p in ids]), s1.truth(ids), atol=1e-6)


def test_fig38_design_sizes_equal_counts(fig38):
    blk, models, control, gnss, adjacency = fig38
    x0 = st.initial_transforms(models, control)
    c = st.structure_counts(models, control, gnss, adjacency)
    assert (c["n"], c["m"], c["k"], c["S"]) == (6, 18, 6, 36)               # the book's m, k, S = 6n
    for g in (None, gnss):
        B, L, rows = st.unit_equations(models, x0, control, g, adjacency)
        N, M, S = st.count_independent_models(c["n"], c["m"], c["k"], gnss=g is not None)
        assert B.shape == (M, N) == ((108 if g else 72), 42)
        assert sum(r.kind == "gnss" for r in rows) == S


def test_counts_with_planimetric_and_height_control(fig38):
    blk, models, control, _, adjacency = fig38
    mixed = dict(control)
    ids = list(mixed)
    mixed[ids[0]] = np.array([*mixed[ids[0]][:2], np.nan])          # planimetric
    mixed[ids[1]] = np.array([np.nan, np.nan, mixed[ids[1]][2]])     # height
    c = st.structure_counts(models, mixed, None, adjacency)
    B, _, _ = st.unit_equations(models, st.initial_transforms(models, control), mixed, None, adjacency)
    N, M = st.count_independent_strips(c["n"], c["m"], c["k"], c["i"], c["l"])   # same M without S
    assert (c["i"], c["l"]) == (1, 1) and B.shape == (M, N)


def test_count_functions_book_values():
    assert st.count_independent_strips(3, 14, 8) == (21, 66)
    assert st.count_independent_models(6, 18, 6) == (42, 72, 0)
    assert st.count_independent_models(6, 18, 6, gnss=True) == (42, 108, 36)
    with pytest.raises(InputError):
        st.count_independent_strips(0, 1, 1)
    with pytest.raises(InputError):
        st.count_independent_models(2, -1, 1)


def test_bad_input(fig38):
    blk, models, control, gnss, adjacency = fig38
    with pytest.raises(InputError, match="no datum"):
        st.adjust_independent_units(models)
    with pytest.raises(DegenerateGeometryError):
        st.adjust_independent_units(models, dict(list(control.items())[:1]), adjacency=adjacency)
    # collinear control on a single strip: the roll about their line is free
    s1 = st.layout_block(1, 6, principal_rows=True, relief=0.0, seed=2)     # flat: the axis row is a line
    m1 = st.layout_models(s1)
    line = _control(s1, [(c, 0.0) for c in range(6)])
    with pytest.raises(DegenerateGeometryError, match="one line"):
        st.adjust_independent_units(m1, line)
    with pytest.raises(InputError, match="X, Y, Z"):
        st.adjust_independent_units(models, {1: [np.nan, 1.0, 2.0]})
    with pytest.raises(InputError, match="not unique"):
        st.UnitModel("u", [1, 1], np.zeros((2, 3)))
    with pytest.raises(InputError, match="not in the strip"):
        st.orient_strip(models[0], {"nope": [0, 0, 0]})
    with pytest.raises(InputError, match="at least two"):
        st.continuation_strip(models[:1])


def test_similarity_sign_convention(fig38):
    """B from the sympy model equals a finite-difference Jacobian of L = computed − given."""
    blk, models, control, gnss, adjacency = fig38
    x0 = st.initial_transforms(models, control, gnss)
    B, L, _ = st.unit_equations(models, x0, control, gnss, adjacency)
    rng = np.random.default_rng(0)
    dx = rng.normal(0, 1e-6, x0.shape)
    _, L2, _ = st.unit_equations(models, x0 + dx, control, gnss, adjacency)
    np.testing.assert_allclose(L2 - L, B @ dx.ravel(), atol=1e-8)
    assert isinstance(st.SimilarityTransform(*x0[0]), SimilarityTransform)
