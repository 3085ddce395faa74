"""Book layer, §3.5/§3.7: the rebuilt blocks of figs. 3.10/3.13, their counts, the (3.5.x) sympy checks,
and the §3.7 helper with the transcribed tolerances (photolib.book.ch03_layouts).

Expected values: the book's printed counts (via textbook/ch03.toml), the per-point image counts
of fig. 3.13 as printed, exact sympy/rational algebra, and synthetic ground truth.
"""

import numpy as np
import pytest

from photolib.book import ch03
from photolib.book import ch03_layouts as tl
from photolib.errors import InputError
from photolib.lsq import solve_normal_equations, solve_partitioned_normal_equations
from photolib.book.textbook import load_chapter


@pytest.fixture(scope="module")
def b10():
    return tl.fig_3_10_block()


@pytest.fixture(scope="module")
def b13():
    return tl.fig_3_13_block()


# --- layouts and counts ---------------------------------------------------------------------------
def test_fig_3_10_layout_reproduces_the_reconstruction(b10):
    seen = {lab: [b10.image_labels[i] for i in np.flatnonzero(row)] for lab, row in zip(b10.point_labels, b10.visibility)}
    everywhere = ["P1", "P2", "P3", "P4"]
    assert seen == {"1": everywhere, "2": everywhere, "5": everywhere, "6": everywhere,
                    "3": ["P1", "P2"], "4": ["P1", "P2"], "7": ["P3", "P4"], "8": ["P3", "P4"]}
    assert b10.visibility.sum(axis=0).tolist() == [6, 6, 6, 6]          # "по шесть точек" (line 2083)


def test_fig_3_13_images_per_point_as_printed(b13):
    printed = [[2, 3, 3, 2], [2, 3, 3, 2], [4, 6, 6, 4], [2, 3, 3, 2], [2, 3, 3, 2]]   # fig. 3.13
    assert tl.images_per_point(b13).reshape(5, 4).tolist() == printed
    corners_and_mid_right = {0, 3, 16, 19, 11}
    assert set(b13.control.tolist()) == corners_and_mid_right


def test_fig_3_13_grid_needs_30_percent_side_overlap():
    """At 60 % side overlap (s = 0.4L) the same grid is seen on more images: the figure is 60 %/30 %."""
    L, b, s = 1.0, 0.4, 0.4
    centres = [(i * b, 0.0) for i in range(4)] + [(i * b, -s) for i in range(4)]
    pts = [(c * b, y) for y in (s / 2, 0, -s / 2, -s, -1.5 * s) for c in range(4)]
    counts = tl.footprint_visibility(pts, centres, L).sum(axis=1).reshape(5, 4)
    assert counts.tolist() != [[2, 3, 3, 2], [2, 3, 3, 2], [4, 6, 6, 4], [2, 3, 3, 2], [2, 3, 3, 2]]


@pytest.mark.parametrize("which, N, M, nnz", [("b10", 36, 48, 384), ("b13", 108, 159, 120 * 9 + 15 + 24)])
def test_counts_equal_the_built_design_matrix(which, N, M, nnz, request):
    blk = request.getfixturevalue(which)
    c = tl.block_counts(blk)
    system = tl.correction_equation_system(blk)
    assert (c["N"], c["M"]) == (N, M)                                   # (3.5.20)/(3.5.21), book values
    assert system.shape == (M, N)
    assert system.nnz == nnz                                            # 32·9 + 16·6 = 384 for fig. 3.10
    assert system.rank == N                                             # no datum defect
    cams0, pts0 = blk.start_values(seed=3)                             # same pattern away from the truth
    assert tl.correction_equation_system(blk, cams0, pts0).nnz == nnz


def test_book_counts_from_textbook(b10, b13):
    ch = load_chapter(3)
    for ex_id, fn in (("3.5-fig3.10-counts", ch03.fig_3_10_counts), ("3.5-fig3.13-counts", ch03.fig_3_13_counts)):
        ex = ch.example(ex_id)
        got = fn(ex.inputs)
        for q in ex.quantities:
            if q.status == "reproduced":
                assert got[q.name] == q.value, (ex_id, q.name)


def test_normal_matrix_structure(b10, b13):
    s10 = tl.normal_matrix_structure(tl.correction_equation_system(b10))
    s13 = tl.normal_matrix_structure(tl.correction_equation_system(b13))
    assert s10["N11_block"] == s13["N11_block"] == "6×6"
    assert s10["N22_block"] == s13["N22_block"] == "3×3"
    assert s10["N12_zero_fraction"] == 0.0 and s10["N12_pattern"] == "dense"
    assert s13["N12_zero_fraction"] == pytest.approx(1 - 60 / 160)      # 60 of 8·20 image–point blocks filled


def test_count_formulas_on_variants():
    assert ch03.count_formula_check({"formula": "3.5.20"})["printed_equals_derived"]
    assert ch03.count_formula_check({"formula": "3.5.21"})["printed_equals_derived"]
    assert tl.bundle_unknowns(8, 20) == 108 and tl.bundle_equations(60, c=5, s=8) == 159
    with pytest.raises(InputError):
        tl.bundle_equations(-1)


# --- the bundle adjustment of the rebuilt blocks ------------------------------------------------------
def test_noise_free_blocks_recover_the_truth():
    for blk in (tl.fig_3_10_block(sigma=0.0), tl.fig_3_13_block(sigma=0.0, control_sigma=0.05)):
        res = blk.adjust(seed=2)
        tie = blk.kind != tl.CONTROL
        if blk.gnss is None:
            np.testing.assert_allclose(res.points[tie], blk.points[tie], atol=1e-5)
            np.testing.assert_allclose(res.cameras[:, :3], blk.cameras[:, :3], atol=1e-5)
        else:   # the noisy control and GNSS observations move the block by ≈ their σ
            assert np.abs(res.points - blk.points).max() < 0.2


@pytest.mark.parametrize("maker, runs", [(tl.fig_3_10_block, 40), (tl.fig_3_13_block, 25)])
def test_check_point_rms_agrees_with_predicted_sigma(maker, runs):
    """Monte-Carlo over seeded noise (geometry fixed; image noise, GNSS and control noise redrawn).

    Every run converges. μ² averages σ² (dof 12 resp. 51 per run: the mean of μ²/σ² over the runs
    has a standard error ≈ 0.065 resp. 0.04; we accept ±25 %). The check points are the tie points
    (fig. 3.10: 1, 2, 5, 6; fig. 3.13: the 15 non-control points). Their squared errors over the
    a-priori variance σ₀²Q_jj have expectation 1 (linear model); the per-axis means over all runs
    must lie in 0.7–1.35 (standard error ≈ √(2/runs) ≈ 0.22 resp. 0.28 if a run's points were fully
    correlated, ≈ 0.1 if independent) — and so must the check-point r.m.s.² over the predicted σ².
    """
    base = maker()
    mu2, z2, e2, p2 = [], [], [], []
    for run in range(runs):
        blk = base.with_noise(1000 + run)
        res = blk.adjust(seed=run)
        assert res.iterations < 15
        mu2.append((res.mu / blk.sigma) ** 2)
        acc = tl.check_point_accuracy(blk, res)
        pred = tl.predicted_point_sigma(res, blk.sigma)[acc["indices"]]
        z2.append((acc["errors"] / pred) ** 2)
        e2.append(acc["rms"] ** 2)
        p2.append(acc["predicted"] ** 2)
    assert np.mean(mu2) == pytest.approx(1.0, abs=0.25)
    z = np.mean(np.concatenate(z2), axis=0)
    assert np.all((0.7 < z) & (z < 1.35)), z
    ratio = np.mean(e2, axis=0) / np.mean(p2, axis=0)
    assert np.all((0.7 < ratio) & (ratio < 1.35)), ratio


# --- the (3.5.x) formulas --------------------------------------------------------------------------------
@pytest.mark.parametrize("form, expected", [("3.5.8", True), ("3.5.9", True), ("3.5.10", False)])
def test_normal_equation_forms(form, expected):
    assert ch03.normal_equation_check({"form": form})["printed_equals_derived"] is expected


@pytest.mark.parametrize("form, expected", [("3.5.13", False), ("3.5.14", False), ("3.5.15-line", True),
                                            ("3.5.15", False), ("3.5.16-line", False), ("3.5.16", True)])
def test_partitioned_forms(form, expected):
    assert ch03.partitioned_check({"form": form})["printed_equals_derived"] is expected


def test_printed_3510_is_the_negative_solution(b10):
    """Numerically on the fig. 3.10 system: +QLᴺ is exactly −δ of the engine (3.5.9)."""
    cams0, pts0 = b10.start_values(seed=4)
    s = tl.correction_equation_system(b10, cams0, pts0)
    delta, Q = solve_normal_equations(s.A, s.L, s.P)
    N, LN = s.normal()
    np.testing.assert_allclose(Q @ LN, -delta, rtol=1e-9, atol=1e-12)


def test_printed_3515_returns_minus_delta2(b10):
    """On the fig. 3.10 normal equations: printed (3.5.15) gives −δ₂, the corrected form and (3.5.16) δ."""
    cams0, pts0 = b10.start_values(seed=4)
    s = tl.correction_equation_system(b10, cams0, pts0)
    N, LN = s.normal()
    L = -LN                                                           # the (3.5.13) convention N·δ = Lᴺ
    q = s.n_eo
    scale = 1 / np.sqrt(np.diag(N))                                   # equilibrate metres vs radians
    Ns, Ls = N * np.outer(scale, scale), L * scale
    full = np.linalg.solve(Ns, Ls)
    n11, n12, n22, l1, l2 = Ns[:q, :q], Ns[:q, q:], Ns[q:, q:], Ls[:q], Ls[q:]
    printed = np.linalg.solve(n12.T @ np.linalg.solve(n11, n12) - n22, l2 - n12.T @ np.linalg.solve(n11, l1))
    np.testing.assert_allclose(printed, -full[q:], rtol=1e-6, atol=1e-9 * np.abs(full).max())
    d1, d2 = solve_partitioned_normal_equations(n11, n12, n22, l1, l2, eliminate="points")
    np.testing.assert_allclose(np.concatenate([d1, d2]), full, rtol=1e-6, atol=1e-9 * np.abs(full).max())


def test_weighted_observation_free_terms():
    assert ch03.weighted_observation_check({})["printed_equals_derived"]


# --- §3.7 regulation helper ---------------------------------------------------------------------------
def test_regulation_numbers_come_from_the_textbook():
    assert tl.regulation_value("3.7.6 height, category b") == 0.25
    assert tl.check_height_factor(1.0, 10000) == 0.2
    assert tl.check_height_factor(0.5, 500) == 0.2
    assert tl.check_height_factor(0.5, 2000) == 0.25
    assert tl.check_height_factor(2.5, 10000) == 0.25
    assert tl.check_height_factor(5.0, 25000) == 0.35
    assert tl.check_height_factor(10.0, 25000, stage="common") == 0.7
    with pytest.raises(InputError):
        tl.check_height_factor(0.5, 10000)                             # not covered by 3.7.6
    assert tl.free_strip_height_tolerance_um(153.0, 92.0) == pytest.approx(15 * 153 / 92)   # ≈ 24.9 µm
    with pytest.raises(InputError):
        tl.free_strip_height_tolerance_um(0, 92)


def test_evaluate_regulations_hand_made_cases():
    # 1:2000, h = 0.5 m → check heights mean ≤ 0.25·0.5 = 0.125 m, plan mean ≤ 0.3 mm·2000 = 0.6 m,
    # limit = 2 × tolerance (0.25 m, 1.2 m) in at most 5 % (open) / 10 % (forest) of the check points
    control = np.array([[0.1, 0.0, 0.05], [0.0, -0.1, -0.05]])        # mean |ΔZ| 0.05 ≤ 0.075; mean ΔXY 0.1 ≤ 0.4
    good = np.array([[0.3, 0.4, 0.10]] * 19 + [[0.0, 0.0, 0.25]])     # mean |ΔZ| 0.1075; 1 of 20 (5 %) at 2×
    rows = tl.evaluate_regulations(control, good, 2000, 0.5)
    assert [r.passed for r in rows] == [True] * 6
    assert rows[2].tolerance == pytest.approx(0.125) and rows[3].tolerance == pytest.approx(0.6)
    assert rows[2].value == pytest.approx(0.1075) and rows[3].value == pytest.approx(0.475)
    assert rows[4].value == pytest.approx(5.0)
    two_high = good.copy()
    two_high[0, 2] = 0.26                                             # 2 of 20 = 10 % at the limit: fails in open …
    rows = tl.evaluate_regulations(control, two_high, 2000, 0.5)
    assert not rows[4].passed and rows[2].value > 0.1075
    assert tl.evaluate_regulations(control, two_high, 2000, 0.5, wooded=True)[4].passed   # … passes in forest
    high_mean = good.copy()
    high_mean[:, 2] = 0.13                                            # mean 0.13 > 0.125, none at the limit
    rows = tl.evaluate_regulations(control, high_mean, 2000, 0.5)
    assert not rows[2].passed and rows[4].passed
    bad_control = control * 3                                          # mean |ΔZ| 0.15 > 0.15·0.5
    assert not tl.evaluate_regulations(bad_control, good, 2000, 0.5)[0].passed
    plan_1_500 = tl.evaluate_regulations(control, good, 500, 0.5)      # plan ≤ 0.15 m, heights ≤ 0.1 m at 1:500
    assert not plan_1_500[3].passed and not plan_1_500[2].passed
    with pytest.raises(InputError):
        tl.evaluate_regulations(control, np.zeros((0, 3)), 2000, 0.5)


# --- fig. 3.18: the fig. 3.10 block shot with a stereo camera (one Fig. 3.10 builder) --------------------------
def test_fig318_rig_system_has_fewer_unknowns_and_the_same_equations():
    from photolib.bundle import count_rig_unknowns, rig_design_matrix
    from photolib.synthetic import TIE
    blk = tl.fig_3_10_block(rig=True, sigma=0.0)
    free = blk.kind == TIE
    args = (blk.observations, blk.exposure_of_image, blk.camera_of_image, blk.exposures, blk.mounts, blk.points,
            blk.ios)
    A_rig, L_rig = rig_design_matrix(*args, free_points=free)
    A_free, L_free = rig_design_matrix(*args, free_points=free, parameterisation="free")
    assert A_rig.shape == (48, 30) and A_free.shape == (48, 36)
    assert np.allclose(L_rig, 0, atol=1e-9) and np.allclose(L_free, 0, atol=1e-9)     # noise-free truth
    assert count_rig_unknowns(2, 2, 4, "rig") == 30
    assert np.linalg.matrix_rank(A_rig) == 30
    # P2, P4 follow from P1, P3 by the same mounting elements (3.8.5)/(3.8.8)
    from photolib.bundle import rig_image_orientation
    np.testing.assert_allclose(rig_image_orientation(blk.cameras[2], blk.mounts[0], blk.order), blk.cameras[3],
                               atol=1e-9)


def test_rebuilt_blocks_print_a_short_summary(b10, b13):
    assert repr(b10).startswith("Block('fig3.10': 4 images, 8 points (4 tie, 4 control), 24 measurements")
    assert "GNSS" in repr(b13) and len(repr(b13)) < 200
