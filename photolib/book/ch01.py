"""Chapter 1 examples: inputs from ``textbook/ch01.toml`` → library calls → named quantities."""

from __future__ import annotations

import numpy as np

from .. import rotation, single_image


def rotation_example(inputs: dict) -> dict:
    """§1.3: A by (1.3.5) for the printed angles, AᵀA, det A and the angles back by (1.3.6)."""
    w, a, k = np.radians([inputs["omega_deg"], inputs["alpha_deg"], inputs["kappa_deg"]])
    A = rotation.rotation_matrix(w, a, k, inputs["order"])
    out = {f"a{i + 1}{j + 1}": float(A[i, j]) for i in range(3) for j in range(3)}
    AtA = A.T @ A
    out.update({f"AtA{i + 1}{j + 1}": float(AtA[i, j]) for i in range(3) for j in range(3)})
    out["det"] = float(np.linalg.det(A))
    back = np.degrees(rotation.rotation_angles(A, inputs["order"]))
    out.update(omega_deg=float(back[0]), alpha_deg=float(back[1]), kappa_deg=float(back[2]))
    return out


def height_error_example(inputs: dict) -> dict:
    """§1.6: planimetric displacement (1.6.1) at the format corner for a height error ΔZ."""
    dX, dY, dR = single_image.planimetric_error_from_height_error(
        inputs["x_max_mm"], inputs["y_max_mm"], inputs["f_mm"], inputs["dZ_m"])
    return {"dX": float(dX), "dY": float(dY), "dR": float(dR)}
