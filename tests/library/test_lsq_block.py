"""The band Cholesky of the reduced system (3.5.16) in photolib.lsq: ordering, solution, datum defects.

Expected values come from independent computations: numpy's dense solver on the same matrix,
the dense engine :func:`photolib.lsq.solve_normal_equations` on the unreduced normal equations
(3.5.8), and the structure of the matrices themselves (a band is checked entry by entry).
"""

import numpy as np
import pytest
from scipy import sparse

from photolib import synthetic
from photolib.bundle import bundle_correction_equations
from photolib.errors import DegenerateGeometryError
from photolib.lsq import (_band_ordering, _block_diagonal, _Factorisation, block_equations_dense,
                          solve_block_normal_equations, solve_normal_equations)


@pytest.fixture(scope="module")
def block():
    """3 strips × 6 images: wide enough that the reduced matrix is a proper band."""
    return synthetic.aerial_block(3, 6, points_per_image=15, sigma=0.005, seed=11)


def _equations(blk, image_numbers=None):
    """Correction equations at perturbed start values; images optionally renumbered."""
    cams, pts = blk.start_values(seed=4)
    o = blk.observations
    image = o.image if image_numbers is None else image_numbers[o.image]
    if image_numbers is not None:
        cams = cams[np.argsort(image_numbers)]          # camera of new number j
    return bundle_correction_equations(image, o.point, o.xy, cams, pts, blk.io, blk.order)


def _free(blk):
    free = np.ones(len(blk.points), bool)
    free[blk.control] = False
    return free


def _reduced_matrix(blk, eq):
    """The reduced matrix S of (3.5.16), assembled densely from the unreduced N (independent path)."""
    n = blk.n_images
    B, L, P = block_equations_dense(eq, n, len(blk.points), free_points=_free(blk))
    N = B.T @ (P[:, None] * B)
    i = 6 * n
    return N[:i, :i] - N[:i, i:] @ np.linalg.solve(N[i:, i:], N[i:, :i])


def _random_band_spd(n, q, width, seed):
    """A random symmetric positive definite block matrix whose blocks lie within `width` block diagonals."""
    rng = np.random.default_rng(seed)
    nb = n // q
    G = np.zeros((n, n))
    for a in range(nb):
        for b in range(max(0, a - width), a + 1):
            G[a * q:(a + 1) * q, b * q:(b + 1) * q] = rng.normal(size=(q, q))
    return G @ G.T + n * np.eye(n) * 1e-3


# --- ordering ------------------------------------------------------------------------------------
def test_band_ordering_is_a_permutation_and_the_band_holds_every_non_zero(block):
    S = _reduced_matrix(block, _equations(block))
    S[np.abs(S) < 1e-9 * np.abs(S).max()] = 0.0          # exact zeros where images share no point
    for matrix in (sparse.csr_matrix(S), sparse.csr_matrix(S).tobsr(blocksize=(6, 6))):
        order, b = _band_ordering(matrix)
        assert np.array_equal(np.sort(order), np.arange(S.shape[0]))
        Sp = S[np.ix_(order, order)]
        i, j = np.nonzero(Sp)
        assert np.abs(i - j).max() <= b
        if matrix.format == "csr":
            assert np.abs(i - j).max() == b                   # exact for scalar unknowns
        else:
            assert np.all(order.reshape(-1, 6) // 6 == order[::6, None] // 6)      # image by image


def test_band_ordering_repairs_a_scrambled_numbering(block):
    """Images numbered at random give a wide band; reverse Cuthill–McKee narrows it again."""
    n = block.n_images
    scrambled = np.random.default_rng(2).permutation(n)
    S = sparse.csr_matrix(_reduced_matrix(block, _equations(block, scrambled)))
    S.data[np.abs(S.data) < 1e-9 * np.abs(S.data).max()] = 0.0
    S.eliminate_zeros()
    given = int(np.abs(S.tocoo().row - S.tocoo().col).max())
    order, b = _band_ordering(S)
    assert b < given
    # strip-wise numbering of the generator is kept when it is the narrower one
    S0 = sparse.csr_matrix(_reduced_matrix(block, _equations(block)))
    S0.data[np.abs(S0.data) < 1e-9 * np.abs(S0.data).max()] = 0.0
    S0.eliminate_zeros()
    order0, b0 = _band_ordering(S0)
    natural = int(np.abs(S0.tocoo().row - S0.tocoo().col).max())
    assert b0 <= natural
    if b0 == natural:
        assert np.array_equal(order0, np.arange(S0.shape[0]))


# --- the factorisation ---------------------------------------------------------------------------
@pytest.mark.parametrize("seed", [0, 1])
def test_band_factorisation_solves_like_the_dense_solver(seed):
    n, q = 120, 6
    S = _random_band_spd(n, q, width=3, seed=seed)
    perm = np.random.default_rng(seed + 10).permutation(n // q)            # scramble the blocks
    p = (q * perm[:, None] + np.arange(q)).ravel()
    S = S[np.ix_(p, p)]
    rhs = np.random.default_rng(seed + 20).normal(size=(n, 3))
    expected = np.linalg.solve(S, rhs)
    for matrix in (sparse.csr_matrix(S), sparse.csr_matrix(S).tobsr(blocksize=(q, q))):
        fac = _Factorisation(matrix, rcond=1e-12)
        assert not fac.dense
        np.testing.assert_allclose(fac.solve(rhs), expected, rtol=1e-9, atol=1e-12)
        np.testing.assert_allclose(fac.solve(rhs[:, 0]), expected[:, 0], rtol=1e-9, atol=1e-12)
    np.testing.assert_allclose(_Factorisation(sparse.csr_matrix(S), 1e-12).inverse(chunk=7), np.linalg.inv(S),
                               rtol=1e-8, atol=1e-12)
    dense = _Factorisation(sparse.csr_matrix(S), 1e-12, dense_limit=n)
    assert dense.dense
    np.testing.assert_allclose(dense.solve(rhs), expected, rtol=1e-9, atol=1e-12)


def test_duplicate_entries_are_summed():
    S = _random_band_spd(30, 3, width=2, seed=5)
    C = sparse.coo_matrix(S)
    half = C.data / 2                                    # every entry given twice, as two halves
    dup = sparse.coo_matrix((np.concatenate([half, half]), (np.tile(C.row, 2), np.tile(C.col, 2))), shape=S.shape)
    rhs = np.arange(30.0)
    np.testing.assert_allclose(_Factorisation(dup, 1e-12).solve(rhs), np.linalg.solve(S, rhs), rtol=1e-9)


def test_block_step_equals_the_unreduced_dense_solution(block):
    """Band path of solve_block_normal_equations = dense (3.5.8)–(3.5.9), also after renumbering images."""
    n, k = block.n_images, len(block.points)
    free = _free(block)
    eq = _equations(block)
    B, L, P = block_equations_dense(eq, n, k, free_points=free)
    delta, _ = solve_normal_equations(B, L, P)
    sol = solve_block_normal_equations(eq, n, k, free_points=free)
    np.testing.assert_allclose(sol.delta1.ravel(), delta[:6 * n], rtol=1e-7, atol=1e-9)
    np.testing.assert_allclose(sol.delta2[free].ravel(), delta[6 * n:], rtol=1e-7, atol=1e-7)
    assert np.all(sol.delta2[~free] == 0)
    numbers = np.random.default_rng(8).permutation(n)
    shuffled = solve_block_normal_equations(_equations(block, numbers), n, k, free_points=free)
    np.testing.assert_allclose(shuffled.delta1[numbers], sol.delta1, rtol=1e-7, atol=1e-9)
    np.testing.assert_allclose(shuffled.delta2, sol.delta2, rtol=1e-7, atol=1e-8)


def test_fixed_images_and_a_point_measured_twice_in_one_image(block):
    """Columns of fixed images drop out; a repeated measurement adds a second row — as in the dense solve."""
    n, k = block.n_images, len(block.points)
    free = _free(block)
    eq = _equations(block)
    again = np.flatnonzero(free[eq.point])[:5]                            # measure five rays twice
    eq.frame, eq.point = np.concatenate([eq.frame, eq.frame[again]]), np.concatenate([eq.point, eq.point[again]])
    eq.B1, eq.B2 = np.concatenate([eq.B1, eq.B1[again]]), np.concatenate([eq.B2, eq.B2[again]])
    eq.L = np.concatenate([eq.L, eq.L[again] + 0.002])
    free_frames = np.ones(n, bool)
    free_frames[[0, 7]] = False
    B, L, P = block_equations_dense(eq, n, k, free_points=free)
    cols = np.concatenate([np.repeat(free_frames, 6), np.ones(B.shape[1] - 6 * n, bool)])
    delta, _ = solve_normal_equations(B[:, cols], L, P)
    sol = solve_block_normal_equations(eq, n, k, free_points=free, free_frames=free_frames)
    np.testing.assert_allclose(sol.delta1[free_frames].ravel(), delta[:6 * free_frames.sum()], rtol=1e-7, atol=1e-9)
    np.testing.assert_allclose(sol.delta2[free].ravel(), delta[6 * free_frames.sum():], rtol=1e-7, atol=1e-7)
    assert np.all(sol.delta1[~free_frames] == 0)


# --- datum defects -------------------------------------------------------------------------------
def test_free_network_is_a_datum_defect_in_the_band_factorisation(block):
    """No control at all: S has a 7-dimensional null space; a clear error, never a silent solution."""
    eq = _equations(block)
    with pytest.raises(DegenerateGeometryError, match="datum defect"):
        solve_block_normal_equations(eq, block.n_images, len(block.points))


def test_singular_and_nearly_singular_matrices_are_rejected():
    """S − vvᵀ/(vᵀS⁻¹v) has the null vector S⁻¹v; with (1 − ε) instead of 1 one eigenvalue is ≈ ε-small."""
    S = _random_band_spd(60, 6, width=2, seed=3)
    v = np.random.default_rng(4).normal(size=60)

    def deflated(eps):
        Z = S - (1 - eps) * np.outer(v, v) / (v @ np.linalg.solve(S, v))
        return sparse.csr_matrix((Z + Z.T) / 2)

    for dense_limit in (0, 60):                          # band and dense Cholesky
        with pytest.raises(DegenerateGeometryError, match="singular"):
            _Factorisation(deflated(0.0), rcond=1e-12, dense_limit=dense_limit)
        # ε = 1e-12: the smallest scaled pivot is ≈ 4e-10 in either numbering — a threshold decides
        with pytest.raises(DegenerateGeometryError, match="singular"):
            _Factorisation(deflated(1e-12), rcond=1e-8, dense_limit=dense_limit)
        fac = _Factorisation(deflated(1e-12), rcond=1e-11, dense_limit=dense_limit)
        assert 1e-11 < fac.min_pivot < 1e-8
    with pytest.raises(DegenerateGeometryError, match="not determined"):
        _Factorisation(sparse.csr_matrix(np.diag([1.0, 0.0, 2.0])), rcond=1e-12)


def test_block_diagonal_helper_is_block_sparse():
    blocks = np.arange(2 * 9, dtype=float).reshape(2, 3, 3)
    M = _block_diagonal(blocks)
    assert M.format == "bsr" and M.blocksize == (3, 3)
    np.testing.assert_array_equal(M.toarray()[:3, :3], blocks[0])
    np.testing.assert_array_equal(M.toarray()[3:, 3:], blocks[1])
    assert not M.toarray()[:3, 3:].any()


# --- the compiled step of small blocks ---------------------------------------------------------------
@pytest.mark.parametrize("seed", range(4))
def test_compiled_band_cholesky_equals_lapack(seed):
    """photolib._block_kernels.band_cholesky / band_solve against scipy's LAPACK dpbtrf / dpbtrs."""
    from scipy.linalg import cho_solve_banded, cholesky_banded

    from photolib import _block_kernels
    rng = np.random.default_rng(seed)
    n, kd = 40 + 7 * seed, 3 + 4 * seed
    A = np.zeros((n, n))
    for d in range(kd + 1):
        v = rng.normal(size=n - d)
        A += np.diag(v, -d) + (np.diag(v, d) if d else 0)
    A += np.eye(n) * (np.abs(A).sum(axis=1).max() + 1.0)          # diagonally dominant: positive definite
    band = np.zeros((kd + 1, n), order="F")
    for d in range(kd + 1):
        band[d, :n - d] = np.diag(A, -d)
    reference = cholesky_banded(band.copy(), lower=True)
    smallest, where = _block_kernels.band_cholesky(band)
    np.testing.assert_allclose(band, reference, rtol=1e-13, atol=1e-13)
    pivots = np.diag(np.linalg.cholesky(A)) ** 2
    assert smallest == pytest.approx(pivots.min(), rel=1e-12) and where == np.argmin(pivots)
    rhs = rng.normal(size=n)
    x = rhs.copy()
    _block_kernels.band_solve(band, x)
    np.testing.assert_allclose(x, cho_solve_banded((reference, True), rhs), rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(A @ x, rhs, rtol=1e-10, atol=1e-10)
    indefinite = band.copy()
    indefinite[0, n // 2] = -1.0
    assert _block_kernels.band_cholesky(indefinite) == (0.0, n // 2)


def test_compiled_step_equals_the_lapack_step(block):
    """The small-block compiled step (covariance=False) = the LAPACK band step (covariance=True),
    with weighted control, GNSS-like priors on the images and two fixed images."""
    n, k = block.n_images, len(block.points)
    eq = _equations(block)
    rng = np.random.default_rng(5)
    point_prior = (rng.normal(0, 0.05, (k, 3)), np.where(np.isin(np.arange(k), block.control)[:, None], 4.0, 0.0)
                   * np.ones((k, 3)))
    frame_prior = (rng.normal(0, 0.1, (n, 6)), np.tile([1e-2, 1e-2, 1e-2, 0.0, 0.0, 0.0], (n, 1)))
    free_frames = np.ones(n, bool)
    free_frames[[2, 9]] = False
    kwargs = dict(frame_prior=frame_prior, point_prior=point_prior, free_frames=free_frames)
    compiled = solve_block_normal_equations(eq, n, k, **kwargs)
    assert "linear step (compiled)" in compiled.timings
    lapack = solve_block_normal_equations(eq, n, k, covariance=True, **kwargs)
    assert "factorisation" in lapack.timings
    np.testing.assert_allclose(compiled.delta1, lapack.delta1, rtol=1e-9, atol=1e-12)
    np.testing.assert_allclose(compiled.delta2, lapack.delta2, rtol=1e-9, atol=1e-12)
    assert np.all(compiled.delta1[~free_frames] == 0)
