"""photolib — companion library to A.G. Chibunichev, *Фотограмметрия* (MIIGAiK, 2022).

The front door: the main entry points are available as ``photolib.<name>`` (loaded on first use,
so ``import photolib`` stays light); the modules mirror the book's chapters:

* :mod:`photolib.rotation` — rotation matrices and quaternions (§1.3)
* :mod:`photolib.camera` — interior and exterior orientation, Brown distortion (§1.2–§1.3)
* :mod:`photolib.single_image` — central projection, collinearity, horizontal and tilted images
  (§1.1, §1.4–§1.7)
* :mod:`photolib.resection` — space resection (§1.8, §1.9)
* :mod:`photolib.digital` — pixel coordinates and resampling (§1.10)
* :mod:`photolib.interior` — interior orientation from fiducial marks (§1.11)
* :mod:`photolib.scanners` — photogrammetric scanners (§1.12)
* :mod:`photolib.image_pair` — an image pair: intersection, relative and absolute orientation
  (Chapter 2)
* :mod:`photolib.gnss_centres` — stereo models from GNSS-measured projection centres
  (Dobrynin & Pimshina)
* :mod:`photolib.strip_triangulation` — strip and independent-model phototriangulation (§3.2–§3.4)
* :mod:`photolib.bundle` — bundle adjustment, self-calibration, rigs, rolling shutter (§3.5–§3.9)
* :mod:`photolib.triangulation_layouts` — counts and structure of bundle systems (§3.5, §3.7)
* :mod:`photolib.synthetic` — seeded synthetic scenes, pairs and blocks with ground truth
* :mod:`photolib.projective` — DLT, projective intersection, fundamental and essential matrices,
  homography (Chapter 4)
* :mod:`photolib.matching` — correlation and least-squares matching (§5.1–§5.4)
* :mod:`photolib.features` — gradients, interest points, descriptors (§5.5, §5.7–§5.9)
* :mod:`photolib.epipolar` — pyramids, epipolar lines, resampling to the normal case (§5.6)
* :mod:`photolib.ransac` — RANSAC for relative orientation and the fundamental matrix (§5.10)
* :mod:`photolib.targets` — automatic measurement of targets (§5.11)
* :mod:`photolib.surface` — surface models by correlation and vertical-line search (§6.1–§6.3)
* :mod:`photolib.sgm` — semi-global matching in image and object space (§6.4–§6.5)
* :mod:`photolib.dtm` — TIN, grids, contours, DSM → DTM (§6.6–§6.7)
* :mod:`photolib.mrf` — terrain from a stereo pair by a Markov random field (Baikalova et al.)
* :mod:`photolib.rpc` — the rational polynomial (RPC) sensor model of satellite images (§8.5, §8.18)
* :mod:`photolib.datasets` — where the real data is, and readers for the stereo benchmarks
* :mod:`photolib.conventions` — conversions to Western, Hanzl's and OpenCV's conventions
  (Appendix A)
* :mod:`photolib.lsq` — the one least-squares engine, (1.8.5)–(1.8.10), with the block
  reduction of §3.5
* :mod:`photolib.derivations` — sympy models and the Jacobians derived from them
* :mod:`photolib.errors` — the exceptions every function raises on bad input

The book layer — published numbers (``photolib.book.textbook``), their check
(``photolib.book.verify``, the ``photolib verify`` command), errata and figures — lives in
:mod:`photolib.book`; the library never imports it.

Examples
--------
>>> import numpy as np
>>> import photolib
>>> A = photolib.rotation_matrix(*np.radians([2.0, 5.0, 7.0]), order="kaw")
>>> [round(float(np.degrees(angle)), 6) for angle in photolib.rotation_angles(A, order="kaw")]
[2.0, 5.0, 7.0]
"""

from __future__ import annotations

import importlib

__version__ = "0.1.0"

# name -> module that defines it (the main entry points of the library)
_ENTRY_POINTS = {
    # rotations (§1.3) and cameras (§1.2)
    "rotation_matrix": "rotation",
    "rotation_angles": "rotation",
    "InteriorOrientation": "camera",
    "ExteriorOrientation": "camera",
    # single image (§1.4–§1.9)
    "project": "single_image",
    "space_resection": "resection",
    # image pair (Chapter 2)
    "forward_intersection": "image_pair",
    "intersect_rays": "image_pair",
    "relative_orientation": "image_pair",
    "absolute_orientation": "image_pair",
    "double_resection": "image_pair",
    # phototriangulation (Chapter 3)
    "bundle_adjustment": "bundle",
    # projective methods (Chapter 4)
    "dlt_resection": "projective",
    "dlt_intersection": "projective",
    "fundamental_matrix": "projective",
    "essential_matrix": "projective",
    "decompose_essential": "projective",
    "homography_dlt": "projective",
    "homography_lsq": "projective",
    # matching and interest points (Chapter 5)
    "match_point": "matching",
    "lsm_affine": "matching",
    "interest_points": "features",
    "match_descriptors": "features",
    "rectify_pair": "epipolar",
    "circle_fit": "targets",
    # surface and terrain models (Chapter 6)
    "dsm_vertical_line": "surface",
    "semi_global_matching": "sgm",
    "voxel_sgm": "sgm",
    "delaunay_tin": "dtm",
    "grid_from_tin": "dtm",
    "filter_dsm": "dtm",
    # the engine
    "gauss_newton": "lsq",
    # errors
    "PhotolibError": "errors",
    "InputError": "errors",
    "DegenerateGeometryError": "errors",
    "ConvergenceError": "errors",
    "PointBehindCameraError": "errors",
}

_MODULES = ("rotation", "camera", "single_image", "resection", "digital", "interior", "scanners",
            "image_pair", "gnss_centres", "strip_triangulation", "bundle", "triangulation_layouts",
            "synthetic", "projective", "matching", "features", "epipolar", "ransac", "targets", "surface", "sgm",
            "dtm", "mrf", "rpc", "datasets", "conventions", "lsq", "derivations", "errors")

__all__ = ["__version__", *_ENTRY_POINTS, *_MODULES]


def __getattr__(name):
    if name in _ENTRY_POINTS:
        value = getattr(importlib.import_module(f".{_ENTRY_POINTS[name]}", __name__), name)
    elif name in _MODULES:
        value = importlib.import_module(f".{name}", __name__)
    else:
        raise AttributeError(f"module 'photolib' has no attribute {name!r}")
    globals()[name] = value
    return value


def __dir__():
    return sorted(set(globals()) | set(__all__))
