"""The sympy symbols of the models (Chapters 1–4 and the GNSS-centres paper).

One symbol per quantity of the book, shared by every model so that expressions of different
models can be compared and substituted into each other: exterior orientation X_S, Y_S, Z_S,
ω, α, κ (§1.3, §1.4), object point X, Y, Z, image point x, y, interior orientation f, x₀, y₀
and the distortion coefficients k₁, k₂, k₃, p₁, p₂ (§1.2), the elements of a pair (§2.7, §2.11),
the rig and rolling-shutter elements (§3.8, §3.9), the homography h₁…h₈ (§4.1) and the
α–ω–χ angles of the GNSS-centres paper.
"""

from __future__ import annotations

import sympy as sp

__all__ = [
    "Xs", "Ys", "Zs", "omega", "alpha", "kappa", "X", "Y", "Z", "x", "y", "f", "x0", "y0",
    "EO_SYMBOLS", "k1", "k2", "k3", "p1", "p2", "IO_SYMBOLS",
    "XA", "YA", "ZA", "XB", "YB", "ZB", "xa", "ya", "xb", "yb",
    "x1", "y1", "x2", "y2", "f1", "f2", "b_y", "b_z",
    "omega1", "alpha1", "kappa1", "omega2", "alpha2", "kappa2",
    "X0", "Y0", "Z0", "omegaM", "alphaM", "kappaM", "t_M", "XM", "YM", "ZM",
    "B_X", "B_Y", "B_Z", "omega_2p", "alpha_2p", "kappa_2p", "MOUNT_SYMBOLS",
    "k_XS", "k_YS", "k_ZS", "k_omega", "k_alpha", "k_kappa", "RATE_SYMBOLS",
    "H_SYMBOLS", "x_t", "y_t", "chi", "chi1", "chi2",
]

# --- Chapter 1: one image ----------------------------------------------------------------------
Xs, Ys, Zs = sp.symbols("X_S Y_S Z_S", real=True)
omega, alpha, kappa = sp.symbols("omega alpha kappa", real=True)
X, Y, Z = sp.symbols("X Y Z", real=True)
x, y = sp.symbols("x y", real=True)
f, x0, y0 = sp.symbols("f x_0 y_0", positive=True)

EO_SYMBOLS = (Xs, Ys, Zs, omega, alpha, kappa)
"""The six elements of exterior orientation X_S, Y_S, Z_S, ω, α, κ (§1.4)."""

k1, k2, k3, p1, p2 = sp.symbols("k_1 k_2 k_3 p_1 p_2", real=True)
IO_SYMBOLS = (f, x0, y0, k1, k2, k3, p1, p2)
"""Interior orientation and Brown distortion f, x₀, y₀, k₁, k₂, k₃, p₁, p₂ (§1.2, §3.6)."""

# two control points A, B and their images a, b (§1.9)
XA, YA, ZA, XB, YB, ZB = sp.symbols("X_A Y_A Z_A X_B Y_B Z_B", real=True)
xa, ya, xb, yb = sp.symbols("x_a y_a x_b y_b", real=True)

# --- Chapter 2: a pair of images ---------------------------------------------------------------
# Image coordinates of the pair models are *reduced* to the principal point (and corrected for
# distortion), so the ray vector of image i is (x_i, y_i, −f_i).
x1, y1, x2, y2 = sp.symbols("x_1 y_1 x_2 y_2", real=True)
f1, f2 = sp.symbols("f_1 f_2", positive=True)
b_y, b_z = sp.symbols("b_y b_z", real=True)
omega1, alpha1, kappa1 = sp.symbols("omega_1 alpha_1 kappa_1", real=True)
omega2, alpha2, kappa2 = sp.symbols("omega_2 alpha_2 kappa_2", real=True)
X0, Y0, Z0 = sp.symbols("X_0 Y_0 Z_0", real=True)
omegaM, alphaM, kappaM, t_M = sp.symbols("omega_M alpha_M kappa_M t", real=True)
XM, YM, ZM = sp.symbols("X_M Y_M Z_M", real=True)

# --- Chapter 3: rigs (§3.8) and rolling shutter (§3.9); B_X… also the GNSS base ----------------
B_X, B_Y, B_Z = sp.symbols("B_X B_Y B_Z", real=True)
omega_2p, alpha_2p, kappa_2p = sp.symbols("omega_2p alpha_2p kappa_2p", real=True)
MOUNT_SYMBOLS = (B_X, B_Y, B_Z, omega_2p, alpha_2p, kappa_2p)
"""The mounting elements of a rig camera: base B and angles ω₂′, α₂′, κ₂′ (3.8.5), (3.8.8)."""
k_XS, k_YS, k_ZS, k_omega, k_alpha, k_kappa = sp.symbols("k_XS k_YS k_ZS k_omega k_alpha k_kappa", real=True)
RATE_SYMBOLS = (k_XS, k_YS, k_ZS, k_omega, k_alpha, k_kappa)
"""The rates k₁…k₆ of the rolling-shutter exterior orientation (3.9.2)."""

# --- Chapter 4: the homography -----------------------------------------------------------------
H_SYMBOLS = sp.symbols("h_1:9", real=True)
"""h₁…h₈ of the plane-to-plane projective transformation with h₃₃ = 1 (1.7.5), (4.1.7)."""
x_t, y_t = sp.symbols("x_t y_t", real=True)

# --- GNSS-centres paper: the α–ω–χ system --------------------------------------------------------
chi, chi1, chi2 = sp.symbols("chi chi_1 chi_2", real=True)
