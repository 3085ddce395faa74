"""The Sementsov appendix (Appendix E), simulations: Table 1, Appendix A, §3.2 (Tables 2, 3, 5, 6, the slopes).

Adapters for the ``[[example]]`` entries of ``textbook/ch11_sementsov_simulation.toml`` (seed
``004_ae61db45a4af28ce.txt``, A.V. Sementsov's 2019 dissertation on calibrating non-metric cameras
on a planar target). They turn the transcribed inputs into calls of :mod:`photolib.mockup`:

* :func:`appendix_a_statistics` — Tables A.2–A.20: mean, max, min, SKO, m ∓ σ of the printed
  per-mock-up errors (Tables A.1–A.19) by :func:`photolib.mockup.error_statistics`;
* :func:`appendix_a_correlations` — Table A.21 from the same rows;
* :func:`table1_variants` — Table 1 as encoded in :data:`photolib.mockup.TABLE1_VARIANTS`, to compare
  with the transcription;
* :func:`gnss_in_pixels` — line 1035, the GNSS σ expressed in pixels;
* :func:`tripod_tables` — Tables 2 and 3 and the points of the central image;
* :func:`tripod_slopes` — the systematic (noise-free sweep) and random (covariance) errors of the
  interior orientation caused by the tripod offset, lines 1103–1116.

:func:`appendix_a_errors` and :func:`appendix_a_mu` return the transcribed rows as arrays for the
notebook and the figures; :func:`resimulate_table1` and :func:`offset_modelling` run the Monte Carlo
re-simulations the notebook shows (demonstrations, not textbook entries).
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np

from .. import mockup
from .textbook import load_chapter

__all__ = ["STATISTICS", "COMPONENTS", "VARIANT_EXAMPLES", "number", "appendix_a_statistics",
           "appendix_a_correlations", "appendix_a_errors", "appendix_a_mu", "table1_variants", "gnss_in_pixels",
           "tripod_tables", "tripod_slopes", "tripod_sweep", "describe_angles", "resimulate_table1",
           "OFFSET_VARIANTS", "offset_modelling"]

STATISTICS = ("m_minus_sigma", "max", "min", "m_plus_sigma", "mean", "sko")
"""The rows of Tables A.2–A.20 in their printed order (m − σ, max, min, m + σ, сред., СКО)."""
COMPONENTS = ("f", "x0", "y0")
VARIANT_EXAMPLES = {v: f"sementsov-appendix-a-{v}" for v in mockup.TABLE1_VARIANTS}
"""The textbook id of each variant's Appendix A tables."""


def number(text) -> float:
    """A number as printed (decimal comma, Unicode minus) as a float."""
    return float(str(text).strip().replace(",", ".").replace("−", "-"))


def _rows(inputs) -> np.ndarray:
    return np.array([[number(c) for c in row[:3]] for row in inputs["rows"]])


# ------------------------------------------------------------------------------ Appendix A
def appendix_a_statistics(inputs: dict) -> dict:
    """Tables A.2 … A.20: the statistics of one variant's printed errors σ_f, σ_x₀, σ_y₀.

    ``inputs['rows']``: the rows of the variant's error table as printed (σ_f, σ_x₀, σ_y₀, μ;
    variant 2-3 has a second row per mock-up, camera 2, without μ). Returns ``"<stat>[<comp>]"``
    for the statistics of :data:`STATISTICS` and the components f, x0, y0.
    """
    s = mockup.error_statistics(_rows(inputs))
    return {f"{stat}[{comp}]": float(getattr(s, stat)[k]) for stat in STATISTICS for k, comp in enumerate(COMPONENTS)}


@lru_cache(maxsize=None)
def _variant_inputs(variant: str) -> dict:
    return load_chapter(11).example(VARIANT_EXAMPLES[variant]).inputs


def appendix_a_errors(variant: str) -> np.ndarray:
    """The printed errors (σ_f, σ_x₀, σ_y₀) of a variant's mock-ups as an (n, 3) array (px)."""
    return _rows(_variant_inputs(variant))


def appendix_a_mu(variant: str) -> np.ndarray:
    """The printed μ of a variant's mock-ups (px), one per mock-up."""
    return np.array([number(row[3]) for row in _variant_inputs(variant)["rows"] if len(row) > 3 and row[3]])


def appendix_a_correlations(inputs: dict) -> dict:
    """Table A.21: Pearson correlations σ_f–σ_x₀, σ_f–σ_y₀, σ_x₀–σ_y₀ of every variant.

    ``inputs['variants']`` lists the variants; their rows are those transcribed for Tables
    A.1–A.19 (:data:`VARIANT_EXAMPLES`). Returns ``"r(f,x0)[<variant>]"`` etc.
    """
    out = {}
    for v in inputs["variants"]:
        pairs = mockup.error_statistics(appendix_a_errors(v)).pairs
        for (a, b), r in zip((("f", "x0"), ("f", "y0"), ("x0", "y0")), pairs):
            out[f"r({a},{b})[{v}]"] = float(r)
    return out


# ------------------------------------------------------------------------------ Table 1
def describe_angles(angles_deg) -> str:
    """The tilt angles of a variant's images written as Table 1 does: "α₁ = 30°, ω₂ = 30°"."""
    parts, many = [], len(angles_deg) > 1
    for i, a in enumerate(angles_deg, 1):
        named = [(n, v) for n, v in zip(("α", "ω", "κ"), a) if v != 0] or [("α", 0.0)]
        for n, v in named:
            parts.append(f"{n}{'₁₂₃'[i - 1] if many else ''} = {v:g}°".replace("-", "−"))
    return ", ".join(parts)


def table1_variants(inputs: dict) -> dict:
    """Table 1 as the library encodes it (:data:`photolib.mockup.TABLE1_VARIANTS`).

    Returns per variant ``methodology``, ``images``, ``cameras``, ``angles`` (as Table 1 writes
    them), ``centres`` ("S1 = S2", "S1 != S2" or "one") and ``gnss`` (the known components, or
    "none"), so that the transcription can be compared with the code.
    """
    out = {}
    for name in inputs["variants"]:
        v = mockup.TABLE1_VARIANTS[name]
        out[f"methodology[{name}]"] = v.methodology
        out[f"images[{name}]"] = len(v.angles_deg)
        out[f"cameras[{name}]"] = v.n_cameras
        out[f"angles[{name}]"] = describe_angles(v.angles_deg)
        out[f"centres[{name}]"] = "one" if len(v.centres) == 1 else ("S1 = S2" if v.n_centres == 1 else "S1 != S2")
        out[f"gnss[{name}]"] = v.gnss or "none"
    return out


def gnss_in_pixels(inputs: dict) -> dict:
    """Line 1035: the GNSS σ of the centre in pixels, σ·f/Z_S (GSD = Z_S/f, eq. (22)).

    ``inputs``: ``Z_S`` (m), ``f_px`` (px; printed in §3.2 only), ``sigma_plan``, ``sigma_height`` (m).
    """
    gsd = float(inputs["Z_S"]) / float(inputs["f_px"])
    return {"gnss_plan_px": float(inputs["sigma_plan"]) / gsd, "gnss_height_px": float(inputs["sigma_height"]) / gsd}


# ------------------------------------------------------------------------------ §3.2
def tripod_tables(inputs: dict) -> dict:
    """Tables 2 and 3 as the library encodes them, and the points of the central image.

    Returns ``alpha[i]``, ``omega[i]``, ``kappa[i]`` of the five images of
    :data:`photolib.mockup.TABLE2_ANGLES` and ``central_points``: the target points inside the
    central image of :func:`photolib.mockup.tripod_mockup` (25 cm lattice through the principal
    ray, 2 m away).
    """
    out = {}
    for i, a in enumerate(mockup.TABLE2_ANGLES, 1):
        for name, v in zip(("alpha", "omega", "kappa"), a):
            out[f"{name}[{i}]"] = float(v)
    obs = mockup.tripod_mockup(sigma=0.0, distance=float(inputs["distance_m"]), step=float(inputs["step_m"]))
    out["central_points"] = int(obs.images[0].xy.shape[0])
    return out


def tripod_sweep(axis: int, l_values, *, distance=2.0, step=0.25):
    """Noise-free errors Δf, Δx₀, Δy₀ (px) of the single-centre calibration for offsets along ``axis``.

    Each offset l (m) along camera axis ``axis`` (0 = X, 1 = Y, 2 = Z) makes the five centres of
    Table 2 differ (eq. (20)); the adjustment (:func:`photolib.mockup.calibrate_network`, unknown
    points on the plane) assumes one centre. Returns ``(l_px, errors)`` with l in pixels
    (l·f/H, GSD = H/f) and errors (k, 3).
    """
    l_values = np.asarray(l_values, dtype=float)
    errors = []
    for lv in l_values:
        l = np.zeros(3)
        l[axis] = lv
        obs = mockup.tripod_mockup(l, sigma=0.0, distance=distance, step=step)
        errors.append(mockup.calibrate_network(obs, targets="plane").io_errors(obs)[0])
    return l_values * mockup.NEX5.f / distance, np.array(errors)


def _slope(l_px, d) -> float:
    """Least-squares slope of a line through the origin (the trend of Fig. 42)."""
    return float(l_px @ d / (l_px @ l_px))


def tripod_slopes(inputs: dict) -> dict:
    """Lines 1103–1116: the trends Δ = k·l (l in pixels) and the random parts m_ξ/m_xy.

    ``inputs``: ``distance_m``, ``step_m`` and ``l_values_m`` (the 10 offsets of Table 3). The
    trends are least-squares lines through the origin over the noise-free sweep
    (:func:`tripod_sweep`) for l_X and l_Z; m_ξ/m_xy is √Q_jj of f, x₀, y₀ of the l = 0 adjustment
    with unit a-priori σ (the expected standard deviation per pixel of image noise).
    """
    dist, step = float(inputs["distance_m"]), float(inputs["step_m"])
    l_values = inputs["l_values_m"]
    out = {}
    for axis, tag in ((0, "l_X"), (2, "l_Z")):
        l_px, err = tripod_sweep(axis, l_values, distance=dist, step=step)
        for k, comp in enumerate(COMPONENTS):
            out[f"d{comp}/{tag}"] = _slope(l_px, err[:, k])
    obs = mockup.tripod_mockup(sigma=0.0, distance=dist, step=step)
    q = np.sqrt(np.diag(mockup.calibrate_network(obs, targets="plane", sigma_image=1.0).adjustment.Q)[:3])
    for comp, v in zip(COMPONENTS, q):
        out[f"m_xi_{comp}/m_xy"] = float(v)
    return out


# ------------------------------------------------------------------------------ notebook helpers
def resimulate_table1(runs=60, seed=2019, variants=None) -> dict:
    """Monte Carlo of the Table 1 variants with both GNSS treatments (:func:`photolib.mockup.simulate_variant`).

    Returns ``{(variant, mode): VariantRuns}``; the variants without GNSS are run once (mode
    "fixed"; the treatment does not apply). Seeded: the i-th variant of Table 1 uses the seed
    ``seed + i`` in both modes, so the two treatments see the same image errors and GNSS draws.
    """
    order = list(mockup.TABLE1_VARIANTS)
    variants = order if variants is None else list(variants)
    out = {}
    for v in variants:
        modes = ("fixed", "weighted") if mockup.TABLE1_VARIANTS[v].gnss else ("fixed",)
        for mode in modes:
            out[(v, mode)] = mockup.simulate_variant(v, runs, seed=seed + order.index(v), gnss_mode=mode)
    return out


OFFSET_VARIANTS = (
    "reference (l = 0), one centre",
    "offset, one centre (Table 5, var. 1)",
    "offset, model (20), plane tilt held (Tables 5/6, var. 2)",
    "offset, model (20), minimal gauge",
)
"""The calibrations compared in Tables 5 and 6 (and one more: the tripod model with the minimal gauge)."""


def offset_modelling(l=(0.005, 0.065, -0.04), sets=20, seed=46, sigma=0.5) -> dict:
    """Tables 5/6 re-simulated: errors of f, x₀, y₀ without offset, with it unmodelled and modelled by (20).

    Each set draws one mock-up of :func:`photolib.mockup.tripod_mockup` with the offset ``l`` and
    one with l = 0 (the same seed, so the same image errors) and calibrates them with unknown
    points on the plane (:func:`photolib.mockup.calibrate_network`, ``targets="plane"``):

    * the reference and Table 5's variant 1 assume one centre (datum: the plane, the centre and the
      first image's rotation);
    * the tripod model (20) with the same datum — the plane's tilt held at its true value, as the
      book's first variant started from the true plane (line 1179);
    * the tripod model with the minimal 7-parameter gauge (only the first κ held), started from
      the previous solution (the tilt is then estimated, through l).

    Returns ``{label: {"errors": (sets, 3), "l": (sets, 3)}}`` for the labels of
    :data:`OFFSET_VARIANTS` (``l`` is NaN without the model).
    """
    rng = np.random.default_rng(seed)
    out = {k: {"errors": [], "l": []} for k in OFFSET_VARIANTS}

    def keep(label, res, obs):
        out[label]["errors"].append(res.io_errors(obs)[0])
        out[label]["l"].append(res.l if res.l is not None else np.full(3, np.nan))

    for _ in range(sets):
        state = int(rng.integers(2**31))
        ref = mockup.tripod_mockup((0.0, 0.0, 0.0), sigma=sigma, seed=state)
        obs = mockup.tripod_mockup(l, sigma=sigma, seed=state)
        keep(OFFSET_VARIANTS[0], mockup.calibrate_network(ref, targets="plane"), ref)
        keep(OFFSET_VARIANTS[1], mockup.calibrate_network(obs, targets="plane"), obs)
        held = mockup.calibrate_network(obs, targets="plane", tripod=True)
        keep(OFFSET_VARIANTS[2], held, obs)
        keep(OFFSET_VARIANTS[3], mockup.calibrate_network(obs, targets="plane", tripod=True, datum="minimal",
                                                          l0=held.l, angles0=held.angles, cameras0=held.cameras), obs)
    return {k: {"errors": np.array(v["errors"]), "l": np.array(v["l"])} for k, v in out.items()}
