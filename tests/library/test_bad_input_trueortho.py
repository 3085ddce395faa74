"""Bad-input catalogue for photolib.trueortho and photolib.derivations.orthophoto (§7.5, §7.6, §7.8)."""

import numpy as np
import pytest

from catalogue import INF, NAN, Case, check_case
from photolib.camera import ExteriorOrientation, InteriorOrientation
from photolib.derivations import orthophoto as d
from photolib.errors import DegenerateGeometryError, InputError
from photolib.rectify import RasterGrid
from photolib.trueortho import (LsqOrtho, TrueOrtho, index_matrix, lsq_dsm_ortho, lsq_unknown_count,
                                ortho_from_points, true_ortho_multi, visibility_mask)

G = RasterGrid(0.0, 10.0, 1.0, (10, 10))
FLAT = np.zeros((10, 10))
NAN_DSM = FLAT.copy()
NAN_DSM[3, 3] = NAN
S = (5.0, 5.0, 50.0)
PROJ = lambda X, Y, Z: (10.0 - np.asarray(Y, float), np.asarray(X, float))       # a vertical "image"
BAD_PROJ = lambda X, Y, Z: (np.zeros(3), np.zeros(3))
IMG = np.random.default_rng(0).uniform(size=(12, 12))
BOX = [[2.0, 4.0, 2.0, 4.0, 0.0, 5.0]]
PTS = np.array([[1.0, 1.0, 0.0], [2.0, 2.0, 0.0], [3.0, 3.0, 1.0]])
EO = [ExteriorOrientation(0.0, 0.0, 100.0)] * 3
IO = InteriorOrientation(50.0)
SMALL = RasterGrid(-1.0, 1.0, 1.0, (2, 2))
IMS = [np.random.default_rng(i).uniform(size=(30, 30)) for i in range(3)]
GCP = np.array([[-1.0, -1.0, 0.0], [1.0, -1.0, 3.0], [-1.0, 1.0, 1.0], [1.0, 1.0, 0.5]])
GXY = np.tile(GCP[:, :2] * 0.5, (3, 1, 1))

CASES = [
    # visibility_mask
    Case(visibility_mask, (NAN_DSM, G, S), raises=InputError, why="NaN in the DSM"),
    Case(visibility_mask, (np.zeros((9, 10)), G, S), raises=InputError, why="DSM does not match its grid"),
    Case(visibility_mask, (FLAT, "grid", S), raises=InputError, why="not a RasterGrid"),
    Case(visibility_mask, (FLAT, G, (5.0, NAN, 50.0)), raises=InputError, why="NaN centre"),
    Case(visibility_mask, (FLAT, G, (5.0, 5.0)), raises=InputError, why="centre of 2 numbers"),
    Case(visibility_mask, (FLAT + 60.0, G, S), raises=InputError, match="above", why="centre below the DSM"),
    Case(visibility_mask, (FLAT, G, S), {"method": "zbuffer"}, raises=InputError, why="unknown method"),
    Case(visibility_mask, (FLAT, G, S), {"step": 0.0}, raises=InputError, why="zero step"),
    Case(visibility_mask, (FLAT, G, S), {"step": INF}, raises=InputError, why="infinite step"),
    Case(visibility_mask, (FLAT, G, S), raises=None, check=lambda m: m.dtype == np.uint8 and m.all(),
         why="flat ground: everything visible"),
    # index_matrix
    Case(index_matrix, ((10, 10), PROJ, [[4.0, 2.0, 2.0, 4.0, 0.0, 5.0]], S), raises=InputError,
         why="X_min > X_max"),
    Case(index_matrix, ((10, 10), PROJ, [[2.0, 4.0, 2.0, 4.0, NAN, 5.0]], S), raises=InputError, why="NaN box"),
    Case(index_matrix, ((10, 10), PROJ, [[2.0, 4.0, 2.0, 4.0]], S), raises=InputError, why="box of 4 numbers"),
    Case(index_matrix, ((0, 10), PROJ, BOX, S), raises=InputError, why="empty image"),
    Case(index_matrix, ((10, 10), "proj", BOX, S), raises=InputError, why="projector not callable"),
    Case(index_matrix, ((10, 10), BAD_PROJ, BOX, S), raises=InputError, why="projector returns wrong shapes"),
    Case(index_matrix, ((10, 10), PROJ, BOX, (3.0, 3.0, 2.0)), raises=InputError, why="centre inside the building"),
    Case(index_matrix, ((10, 10), PROJ, np.zeros((0, 6)), S), raises=None, check=lambda m: not m.any(),
         why="no buildings: all ground"),
    # true_ortho_multi
    Case(true_ortho_multi, ([IMG], [PROJ, PROJ], [S], FLAT, G, G), raises=InputError, why="2 projectors, 1 image"),
    Case(true_ortho_multi, ([], [], np.zeros((0, 3)), FLAT, G, G), raises=InputError, why="no images"),
    Case(true_ortho_multi, ([IMG], [PROJ], [(NAN, 0.0, 50.0)], FLAT, G, G), raises=InputError, why="NaN centre"),
    Case(true_ortho_multi, ([IMG], [PROJ], [S], NAN_DSM, G, G), raises=InputError, why="NaN DSM"),
    Case(true_ortho_multi, ([IMG], [PROJ], [S], FLAT, G, RasterGrid(-50.0, 10.0, 1.0, (5, 5))),
         raises=InputError, match="does not cover", why="DSM does not cover the ortho grid"),
    Case(true_ortho_multi, ([IMG], [BAD_PROJ], [S], FLAT, G, G), raises=InputError, why="projector shapes"),
    Case(true_ortho_multi, ([IMG], [PROJ], [S], FLAT, G, G), {"step": -1.0}, raises=InputError,
         why="negative step"),
    Case(true_ortho_multi, ([IMG], [PROJ], [S], FLAT, G, G), raises=None,
         check=lambda t: (t.source == 0).all() and np.isfinite(t.image).all(), why="one image, flat ground"),
    # ortho_from_points
    Case(ortho_from_points, (np.zeros((0, 3)), [], G), raises=InputError, why="empty cloud"),
    Case(ortho_from_points, (PTS, [1.0, 2.0], G), raises=InputError, why="values of the wrong length"),
    Case(ortho_from_points, (PTS[:, :2], [1.0, 2.0, 3.0], G), raises=InputError, why="(n, 2) points"),
    Case(ortho_from_points, (np.where(PTS == 2.0, NAN, PTS), [1.0, 2.0, 3.0], G), raises=InputError,
         why="NaN point"),
    Case(ortho_from_points, (PTS, [1.0, INF, 3.0], G), raises=InputError, why="inf value"),
    Case(ortho_from_points, (PTS, [1.0, 2.0, 3.0], G, "median"), raises=InputError, why="unknown method"),
    Case(ortho_from_points, (PTS, [1.0, 2.0, 3.0], G), {"radius": 0.0}, raises=InputError, why="zero radius"),
    Case(ortho_from_points, (PTS, [1.0, 2.0, 3.0], G), raises=None,
         check=lambda o: np.isnan(o).sum() > 80, why="sparse cloud: holes are NaN, not zeros"),
    # lsq_unknown_count
    Case(lsq_unknown_count, (0, 3), raises=InputError, why="P = 0"),
    Case(lsq_unknown_count, (100, 2.5), raises=InputError, why="non-integer S"),
    Case(lsq_unknown_count, (True, 3), raises=InputError, why="bool P"),
    Case(lsq_unknown_count, (100, 2), raises=None, check=lambda nm: nm == (201, 200), why="the book's example"),
    # lsq_dsm_ortho
    Case(lsq_dsm_ortho, (IMS[:2], EO[:2], IO, 0.1, SMALL, np.zeros((2, 2))), raises=DegenerateGeometryError,
         match="N = 9", why="two images: N > M"),
    Case(lsq_dsm_ortho, (IMS, EO[:2], IO, 0.1, SMALL, np.zeros((2, 2))), raises=InputError,
         why="3 images, 2 orientations"),
    Case(lsq_dsm_ortho, (IMS, EO, IO, 0.1, SMALL, np.full((2, 2), NAN)), raises=InputError, why="NaN initial DSM"),
    Case(lsq_dsm_ortho, (IMS, EO, IO, 0.1, SMALL, np.zeros((3, 2))), raises=InputError, why="DSM shape"),
    Case(lsq_dsm_ortho, (IMS, EO, IO, -0.1, SMALL, np.zeros((2, 2))), raises=InputError, why="negative pixel"),
    Case(lsq_dsm_ortho, (IMS, EO, "io", 0.1, SMALL, np.zeros((2, 2))), raises=InputError, why="io not a camera"),
    Case(lsq_dsm_ortho, (IMS, EO, IO, 0.1, SMALL, np.zeros((2, 2))), {"reference": 3}, raises=InputError,
         why="reference out of range"),
    Case(lsq_dsm_ortho, (IMS, EO, IO, 0.1, RasterGrid(500.0, 600.0, 1.0, (2, 2)), np.zeros((2, 2))),
         raises=InputError, match="outside image", why="grid outside the images"),
    Case(lsq_dsm_ortho, ([np.full((30, 30), 0.5)] * 3, EO, IO, 0.1, SMALL, np.zeros((2, 2))),
         {"sigma_z0": INF}, raises=DegenerateGeometryError, why="textureless images"),
    Case(lsq_dsm_ortho, (IMS, EO, IO, 0.1, SMALL, np.zeros((2, 2))), {"sigma_f": NAN}, raises=InputError,
         why="NaN sigma"),
    # lsq_dsm_ortho with unknown EO (7.8.4)
    Case(lsq_dsm_ortho, (IMS, EO, IO, 0.1, SMALL, np.zeros((2, 2))), {"estimate_eo": True},
         raises=DegenerateGeometryError, match="datum defect of 7", why="unknown EO without GCPs"),
    Case(lsq_dsm_ortho, (IMS, EO, IO, 0.1, SMALL, np.zeros((2, 2))),
         {"estimate_eo": True, "gcp_xyz": GCP[:2], "gcp_xy": GXY[:, :2]},
         raises=DegenerateGeometryError, match="datum defect", why="two GCPs only"),
    Case(lsq_dsm_ortho, (IMS[:2], EO[:2], IO, 0.1, SMALL, np.zeros((2, 2))),
         {"estimate_eo": True, "gcp_xyz": GCP, "gcp_xy": GXY[:2]}, raises=DegenerateGeometryError,
         match="third image", why="two images with unknown EO, even with GCPs"),
    Case(lsq_dsm_ortho, (IMS, EO, IO, 0.1, SMALL, np.zeros((2, 2))), {"estimate_eo": True, "gcp_xyz": GCP},
         raises=InputError, match="neither", why="GCP ground coordinates without image measurements"),
    Case(lsq_dsm_ortho, (IMS, EO, IO, 0.1, SMALL, np.zeros((2, 2))),
         {"estimate_eo": True, "gcp_xyz": GCP, "gcp_xy": GXY[:2]}, raises=InputError,
         why="measurements for 2 of 3 images"),
    Case(lsq_dsm_ortho, (IMS, EO, IO, 0.1, SMALL, np.zeros((2, 2))),
         {"estimate_eo": True, "gcp_xyz": GCP[:, :2], "gcp_xy": GXY}, raises=InputError, why="(n, 2) GCPs"),
    Case(lsq_dsm_ortho, (IMS, EO, IO, 0.1, SMALL, np.zeros((2, 2))),
         {"estimate_eo": True, "gcp_xyz": np.where(GCP == 3.0, NAN, GCP), "gcp_xy": GXY}, raises=InputError,
         why="NaN GCP"),
    Case(lsq_dsm_ortho, (IMS, EO, IO, 0.1, SMALL, np.zeros((2, 2))),
         {"estimate_eo": True, "gcp_xyz": GCP, "gcp_xy": np.where(GXY == GXY[0, 0, 0], INF, GXY)},
         raises=InputError, why="inf measurement"),
    Case(lsq_dsm_ortho, (IMS, EO, IO, 0.1, SMALL, np.zeros((2, 2))),
         {"estimate_eo": True, "gcp_xyz": GCP, "gcp_xy": GXY, "sigma_gcp": -1.0}, raises=InputError,
         why="negative sigma_gcp"),
    # result classes
    Case(TrueOrtho, (np.zeros((1, 1)), np.zeros((1, 1), int), np.zeros((1, 1)), np.ones((1, 1, 1))), raises=None,
         check=lambda t: t.source.shape == (1, 1), why="plain container"),
    Case(LsqOrtho, (np.zeros((1, 1)), np.zeros((1, 1)), np.ones(3), None, (202, 300)), raises=None,
         check=lambda r: r.counts == (202, 300), why="plain container"),
    # derivations
    Case(d.collinearity_732, ("xyz",), raises=InputError, why="unknown rotation order"),
    Case(d.check_782_equals_732, ("abc",), raises=InputError, why="unknown rotation order"),
    Case(d.correction_coefficients, (False, "xyz"), raises=InputError, why="unknown rotation order"),
    Case(d.height_partials_function, ("zzz",), raises=InputError, why="unknown rotation order"),
    Case(d.eo_partials_function, ("zzz",), raises=InputError, why="unknown rotation order"),
    Case(d.check_784_chain_rule, ("abc",), raises=InputError, why="unknown rotation order"),
    Case(d.photometric_condition, (), raises=None, check=lambda e: e.has(d.F_sym), why="no arguments"),
    Case(d.collinearity_782, (), raises=None, check=lambda xy: len(xy) == 2, why="no arguments"),
    Case(d.height_partials, (), raises=None, check=lambda h: "dx_dZ" in h, why="no arguments"),
]


@pytest.mark.parametrize("case", CASES, ids=lambda c: c.id)
def test_bad_input(case):
    check_case(case)
