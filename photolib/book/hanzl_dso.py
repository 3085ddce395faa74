"""Adapters for Hanzl §7 (direct sensor orientation), §9 (DTM data), §10 (workstations), §11 (laser
scanning) and §12 (line scanners) — seed 002, filed in ``textbook/ch06_hanzl.toml``,
``ch08_hanzl.toml`` and ``ch09_hanzl.toml`` (ids ``hanzl-…``).

Each function takes the ``inputs`` table of an entry and returns ``{quantity: value}`` (examples)
or ``{"printed_equals_derived": bool}`` (formulas). The formula checks compare Hanzl's printed
estimation formulas with the derivations of :mod:`photolib.derivations.estimation`; the numbers
are recomputed with :mod:`photolib.direct_orientation`, :mod:`photolib.lidar` and
:mod:`photolib.pushbroom`.
"""

from __future__ import annotations

import numpy as np
import sympy as sp

from .. import direct_orientation as do
from .. import lidar, pushbroom
from ..derivations import estimation as E
from ._exact import zero as _zero

__all__ = ["formula_check", "flight_distance", "earth_rate", "boresight_calibration", "footprint",
           "line_scanner_fov", "stereo_monitor_rate", "imu_bias_for_drift", "SIDEREAL_DAY"]

SIDEREAL_DAY = 86164.0905
"""Length of the sidereal day, s (IERS conventions): one turn of the Earth relative to the stars."""



def _rational_point(symbols) -> dict:
    """Seeded exact values for ``symbols``: positive ones for the weights and cofactors, so that
    every inverse exists; the same point on every run."""
    rng = np.random.default_rng(7)
    point = {}
    for symbol in sorted(symbols, key=str):
        value = sp.Rational(int(rng.integers(1, 20)), int(rng.integers(1, 7)))
        point[symbol] = value
    # a diagonally dominant Q (q11, q22 large) keeps it positive definite
    for symbol in point:
        if str(symbol) in ("q11", "q22"):
            point[symbol] += 40
    return point


def _sequential(m2: int = 1):
    d = E.sequential_blocks(m2)
    N2 = d["A2"].T * d["P2"] * d["A2"]
    K = (d["N1"] + N2).inv() * d["A2"].T * d["P2"]
    return d, N2, K


def formula_check(inputs: dict) -> dict:
    """Compare one printed formula of Hanzl §7 with its sympy derivation (``inputs["item"]``)."""
    item = inputs["item"]
    if item == "7.3.1":
        d = E.least_squares_solution()
        N = d["A"].T * d["P"] * d["A"]
        ok = _zero(N.inv() * d["A"].T * d["P"] * d["l"] - d["x"])
    elif item == "seq-1":
        d, N2, K = _sequential()
        ok = _zero(K * (d["l2"] - d["A2"] * d["x0"]) - d["dx"])
    elif item == "seq-2":
        d, N2, K = _sequential()
        ok = _zero(-(d["N1"] + N2).inv() * N2 * d["Q0"] - d["dQ"]) and _zero(-K * d["A2"] * d["Q0"] - d["dQ"])
    elif item == "gain":
        d, N2, K = _sequential(2)
        lemma = d["N1"].inv() * d["A2"].T * (d["P2"].inv() + d["A2"] * d["N1"].inv() * d["A2"].T).inv()
        ok = _zero(lemma - K)
    elif item == "identity-1406":
        d, N2, K = _sequential()
        ok = _zero((d["N1"] + N2) * d["Q0"] - sp.eye(2))          # printed: I = N·Q_x0 with N = N₁ + N₂
    elif item == "identity-1406-corrected":
        d, N2, K = _sequential()
        ok = _zero((d["N1"] + N2) * (d["Q0"] + d["dQ"]) - sp.eye(2))
    elif item == "prior-as-observation":
        # x0 + v1 = x (weight N1) and l2 + v2 = A2 x: the batch solution equals x0 + Δx of "1)"
        d, N2, K = _sequential()
        batch = (d["N1"] + N2).inv() * (d["N1"] * d["x0"] + d["A2"].T * d["P2"] * d["l2"])
        ok = _zero(batch - (d["x0"] + d["dx"]))
    elif item == "transition":
        d = E.transition_series(2)
        printed = sp.eye(2) + d["F"] * d["dt"] + d["F"] ** 2 * d["dt"] ** 2 / 2
        ok = _zero(printed - d["series"])
    elif item == "kalman-update":
        d = E.kalman_update_batch()
        K = d["Q"] * d["A"].T * (d["Ql"] + d["A"] * d["Q"] * d["A"].T).inv()
        ok = _zero(d["x"] + K * (d["l"] - d["A"] * d["x"]) - d["x_hat"]) and \
            _zero((sp.eye(2) - K * d["A"]) * d["Q"] - d["Q_hat"])
    elif item == "kalman-gain-printed":
        # with a general transition matrix T the printed gain differs from the derived one; one
        # exact rational point where they differ proves it (an identity would hold everywhere)
        d = E.kalman_update_batch()
        point = _rational_point(set().union(*(d[k].free_symbols for k in ("x", "Q", "A", "Ql", "l", "T"))))
        x, Q, A, Ql, l, T = (d[k].subs(point) for k in ("x", "Q", "A", "Ql", "l", "T"))
        K = Q * A.T * (Ql + A * Q * T.T).inv()
        ok = x + K * (l - A * x) == d["x_hat"].subs(point)
    elif item == "position":
        d = E.position_integral()
        t, t0, s, u = d["t"], d["t0"], sp.Symbol("s", real=True), sp.Symbol("u", real=True)
        double = sp.integrate(sp.integrate(d["a"].subs(t, u), (u, t0, s)), (s, t0, t))
        ok = _zero(sp.expand(d["r0"] + d["v0"] * (t - t0) + double - d["r"]))
    else:
        raise KeyError(f"no formula check {item!r}")
    return {"printed_equals_derived": bool(ok)}


def flight_distance(inputs: dict) -> dict:
    """Distance flown in the time the IMU runs alone (Hanzl §7, line 1296): v·t."""
    return {"distance": inputs["speed"] * inputs["time"]}


def imu_bias_for_drift(inputs: dict) -> dict:
    """Accelerometer bias whose double integral gives the quoted drift in ``time`` (µg)."""
    t = inputs["time"]
    out = {}
    for name, drift in (("bias for low drift", inputs["drift_low"]), ("bias for high drift", inputs["drift_high"])):
        bias = 2 * drift / t ** 2                       # ½·b·t² = drift
        acc = np.full((int(round(t * 100)), 1), bias)    # 100 Hz, gravity removed, the bias alone
        position, _ = do.integrate_imu(acc, 0.01, np.zeros(1), np.zeros(1))
        out[name] = float(bias / 9.80665 * 1e6)
        out[name.replace("bias", "drift check")] = float(position[-1, 0])
    return out


def earth_rate(inputs: dict) -> dict:
    """Rotation rate of ECEF relative to the inertial frame, 2π per sidereal day (Hanzl §7.2.1)."""
    return {"omega_E": 2 * np.pi / inputs["sidereal_day"], "printed constant": do.EARTH_RATE}


def boresight_calibration(inputs: dict) -> dict:
    """The recommended calibration block (2 strips × 7 images, 10 control points) solved for the
    basic boresight model; returns the number of unknowns and how well the truth is recovered."""
    block = do.simulate_boresight_block(seed=inputs["seed"], n_strips=inputs["strips"], n_images=inputs["images"],
                                        n_control=inputs["control"])
    result = do.calibrate_boresight(block.xy, block.image, block.points, block.gnss, block.A_imu, block.f)
    return {"parameters": result.shift.size + result.angles.size,
            "shift error": float(np.abs(result.shift - block.shift).max()),
            "angle error": float(np.degrees(np.abs(result.angles - block.angles)).max() * 3600)}


def footprint(inputs: dict) -> dict:
    """Laser footprint at height H for a full divergence given in gon (Hanzl §11.1)."""
    return {"footprint": 100 * lidar.footprint_diameter(inputs["H"], inputs["divergence_gon"] * np.pi / 200)}


def line_scanner_fov(inputs: dict) -> dict:
    """Across-track field of view of the ADS40 and STARIMAGER lines from the text's own numbers (§12)."""
    return {name: float(np.degrees(pushbroom.line_field_of_view(n, p, f)))
            for name, (n, p, f) in (("ADS40 FOV", (inputs["ads40"])), ("STARIMAGER FOV", (inputs["starimager"])))}


def stereo_monitor_rate(inputs: dict) -> dict:
    """Frame rate of a monitor that shows each eye its image ``per_eye`` times a second (§10)."""
    return {"monitor rate": 2 * inputs["per_eye"]}
