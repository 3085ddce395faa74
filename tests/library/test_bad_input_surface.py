"""Bad-input catalogue for the scene renderer (photolib.synthetic, Chapters 5–6), photolib.epipolar (§5.6)
and photolib.surface (§6.1–6.3): NaN, wrong shapes, mismatched sizes, Z_min ≥ Z_max, points behind
the camera, non-rectifiable pairs."""

import numpy as np
import pytest

from catalogue import INF, NAN, Case, check_case
from photolib import epipolar, surface, synthetic
from photolib.camera import ExteriorOrientation, InteriorOrientation
from photolib.rotation import rotation_matrix
from photolib.errors import DegenerateGeometryError, InputError, PointBehindCameraError

IO = InteriorOrientation(50.0)
IO_DIST = InteriorOrientation(50.0, k1=1e-5)
E1, E2 = ExteriorOrientation(20.0, 20.0, 300.0), ExteriorOrientation(24.0, 20.0, 300.0)
E_UP = ExteriorOrientation(20.0, 20.0, 300.0, np.pi, 0.0, 0.0)          # looking up into the sky
SCENE = synthetic.terrain_scene(extent=40.0, spacing=1.0, n_buildings=0, relief=2.0, seed=0)
IMG = np.random.default_rng(0).random((40, 40))
IMG_NAN = IMG.copy()
IMG_NAN[3, 4] = NAN
ROT = np.eye(3)
X2, Y2 = np.meshgrid([20.0, 21.0], [20.0, 21.0])
FLAT = np.zeros((8, 8))

CASES = [
    # --- synthetic: the renderer ---
    Case(synthetic.terrain_scene, (), {"extent": NAN}, raises=InputError, why="NaN extent"),
    Case(synthetic.terrain_scene, (), {"extent": (10.0, 20.0, 30.0)}, raises=InputError, why="three extents"),
    Case(synthetic.terrain_scene, (), {"extent": 1.0, "spacing": 1.0}, raises=InputError, why="grid below 3 × 3"),
    Case(synthetic.terrain_scene, (), {"n_buildings": -1}, raises=InputError, why="negative count"),
    Case(synthetic.terrain_scene, (), {"building_height": (20.0, 6.0)}, raises=InputError, why="low > high"),
    Case(synthetic.terrain_scene, (), {"spacing": 0.0}, raises=InputError, why="zero spacing"),
    Case(synthetic.terrain_scene, (), {"extent": 30.0, "spacing": 1.0, "n_buildings": 40, "seed": 1}, raises=None,
         why="more buildings than fit: fewer placed", check=lambda s: 0 <= len(s.footprints) < 40),
    Case(synthetic.TerrainScene, (np.arange(3.0), np.arange(3.0), np.zeros((3, 3)), np.zeros((3, 4)),
                                  np.zeros((3, 3), bool), np.zeros((3, 3), bool), np.zeros((3, 3)), np.zeros((0, 4))),
         raises=InputError, why="surface of the wrong shape"),
    Case(synthetic.TerrainScene, (np.array([0.0, 1.0, 3.0]), np.arange(3.0), *(np.zeros((3, 3)),) * 2,
                                  np.zeros((3, 3), bool), np.zeros((3, 3), bool), np.zeros((3, 3)), np.zeros((0, 4))),
         raises=InputError, why="irregular axis"),
    Case(synthetic.TerrainScene, (np.arange(3.0), np.arange(3.0), np.full((3, 3), NAN), np.zeros((3, 3)),
                                  np.zeros((3, 3), bool), np.zeros((3, 3), bool), np.zeros((3, 3)), np.zeros((0, 4))),
         raises=InputError, why="NaN ground"),
    Case(SCENE.surface_at, ([NAN], [1.0]), raises=InputError, why="NaN position"),
    Case(synthetic.render_image, ("scene", IO, E1, (10, 10)), raises=InputError, why="not a scene"),
    Case(synthetic.render_image, (SCENE, IO, "eo", (10, 10)), raises=InputError, why="not an orientation"),
    Case(synthetic.render_image, (SCENE, IO, E1, (10,)), raises=InputError, why="shape of one number"),
    Case(synthetic.render_image, (SCENE, IO, E1, (10, 10)), {"pixel_size": -0.1}, raises=InputError,
         why="negative pixel size"),
    Case(synthetic.render_image, (SCENE, IO, E1, (10, 10)), {"noise": NAN}, raises=InputError, why="NaN noise"),
    Case(synthetic.render_image, (SCENE, IO_DIST, E1, (10, 10)), raises=InputError, match="distortion",
         why="a camera with distortion"),
    Case(synthetic.render_image, (SCENE, IO, ExteriorOrientation(20.0, 20.0, 50.0), (10, 10)), raises=InputError,
         match="below the surface", why="camera under the ground"),
    Case(synthetic.render_image, (SCENE, IO, E_UP, (10, 10)), raises=PointBehindCameraError,
         why="the whole scene behind the camera"),
    Case(synthetic.render_image, (SCENE, IO, ExteriorOrientation(500.0, 500.0, 300.0), (10, 10)),
         raises=DegenerateGeometryError, why="the scene outside the frame"),
    Case(synthetic.Rendering, (np.zeros((2, 2)), np.zeros((2, 2)), np.zeros((2, 2, 3)), np.ones((2, 2), bool),
                               IO, E1, 0.01), raises=None, why="a plain record", check=lambda r: r.shape == (2, 2)),
    Case(synthetic.pixel_to_image, ([0.0, NAN], [0.0, 1.0], (4, 4), 0.01), raises=InputError, why="NaN column"),
    Case(synthetic.pixel_to_image, ([0.0, 1.0], [0.0, 1.0, 2.0], (4, 4), 0.01), raises=InputError,
         why="mismatched col/row"),
    Case(synthetic.pixel_to_image, (0.0, 0.0, (1, 4), 0.01), raises=InputError, why="a one-row frame"),
    Case(synthetic.image_to_pixel, ([[0.0, INF]], (4, 4), 0.01), raises=InputError, why="inf coordinate"),
    Case(synthetic.image_to_pixel, ([[0.0, 0.0, 0.0]], (4, 4), 0.01), raises=InputError, why="3 columns"),
    Case(synthetic.image_to_pixel, ([[0.0, 0.0]], (4, 4), 0.0), raises=InputError, why="zero pixel size"),
    # --- epipolar (§5.6) ---
    Case(epipolar.pyramid, (IMG_NAN, 2), raises=InputError, why="NaN pixels"),
    Case(epipolar.pyramid, (IMG, 5), raises=InputError, why="too many levels for the image"),
    Case(epipolar.pyramid, (IMG, -1), raises=InputError, why="negative levels"),
    Case(epipolar.pyramid, (IMG, 1, "median"), raises=InputError, why="unknown method"),
    Case(epipolar.pyramid, (np.zeros((4, 4, 4)), 1), raises=InputError, why="3-D array"),
    Case(epipolar.match_coarse_to_fine, (IMG, IMG[:, :30], (20, 20)), raises=InputError,
         why="images of different sizes"),
    Case(epipolar.match_coarse_to_fine, (IMG, IMG_NAN, (20, 20)), raises=InputError, why="NaN pixels"),
    Case(epipolar.match_coarse_to_fine, (IMG, IMG, (2, 2)), {"levels": 1}, raises=InputError,
         why="window at the border"),
    Case(epipolar.match_coarse_to_fine, (np.ones((64, 64)), np.ones((64, 64)), (32, 32)), {"levels": 1},
         raises=DegenerateGeometryError, why="textureless images"),
    Case(epipolar.match_coarse_to_fine, (IMG, IMG, (NAN, 3)), raises=InputError, why="NaN point"),
    Case(epipolar.PyramidMatch, (1.0, 2.0, 0.0, 0.0, 0.9, True), raises=None, why="a plain record",
         check=lambda m: m.trace == []),
    Case(epipolar.epipolar_ordinate, ((1.0, NAN), 0.0, ROT, ROT, 100.0), raises=InputError, why="NaN point"),
    Case(epipolar.epipolar_ordinate, ((1.0, 2.0), 0.0, np.ones((3, 3)), ROT, 100.0), raises=InputError,
         why="not a rotation"),
    Case(epipolar.epipolar_ordinate, ((1.0, 2.0), 0.0, ROT, ROT, 0.0), raises=InputError, why="f = 0"),
    Case(epipolar.epipolar_ordinate, ((0.0, 0.0), 3.0, ROT, ROT, 100.0), raises=None,
         why="principal point: the line is y = 0", check=lambda y: y == 0.0),
    Case(epipolar.epipolar_ordinate, ((0.0, 0.0), 0.0, ROT, rotation_matrix(np.pi / 2, 0.0, 0.0, "wak"), 100.0),
         raises=DegenerateGeometryError, why="epipolar line parallel to the y axis (Y'1 a32 = Z'1 a22)"),
    Case(epipolar.epipolar_line, ([[1.0, 2.0]], E1, E1, IO), raises=DegenerateGeometryError, why="no base"),
    Case(epipolar.epipolar_line, ([[1.0, NAN]], E1, E2, IO), raises=InputError, why="NaN point"),
    Case(epipolar.epipolar_line, ([[1.0, 2.0]], E1, E2, IO_DIST), raises=InputError, why="camera with distortion"),
    Case(epipolar.epipolar_line, ([[1.0, 2.0]], E1, "eo", IO), raises=InputError, why="not an orientation"),
    Case(epipolar.epipolar_intersection, ([[1.0, 2.0]], [[1.0, 2.0], [3.0, 4.0]], E1, E2,
                                          ExteriorOrientation(22.0, 24.0, 300.0), IO),
         raises=InputError, why="different point counts"),
    Case(epipolar.epipolar_intersection, ([[1.0, 2.0]], [[0.2, 2.0]], E1, E2, ExteriorOrientation(28.0, 20.0, 300.0),
                                          IO), raises=DegenerateGeometryError, why="collinear centres"),
    Case(epipolar.rectify_pair, (IMG, IMG[:30], IO, E1, E2, 0.1), raises=InputError, why="mismatched sizes"),
    Case(epipolar.rectify_pair, (IMG, IMG_NAN, IO, E1, E2, 0.1), raises=InputError, why="NaN pixels"),
    Case(epipolar.rectify_pair, (IMG, IMG, IO, E1, E1, 0.1), raises=DegenerateGeometryError, why="no base"),
    Case(epipolar.rectify_pair, (IMG, IMG, IO, E1, ExteriorOrientation(20.0, 20.0, 250.0), 0.1),
         raises=DegenerateGeometryError, why="base along the viewing direction"),
    Case(epipolar.rectify_pair, (IMG, IMG, IO, E2, E1, 0.1), raises=DegenerateGeometryError,
         why="base pointing against x: images swapped"),
    Case(epipolar.rectify_pair, (IMG, IMG, IO, E1, E2, 0.0), raises=InputError, why="zero pixel size"),
    Case(epipolar.EpipolarPair, (FLAT, FLAT, FLAT > 0, FLAT > 0, ROT, 50.0, 0.01, np.zeros(2), 0.0,
                                 np.stack([np.eye(3)] * 2), (E1, E2)), raises=None, why="a plain record",
         check=lambda p: p.interior(1).f == 50.0),
    # --- surface (§6.1–6.3) ---
    Case(surface.epipolar_segment, ([[0.0, 0.0]], E1, E2, IO, 120.0, 100.0), raises=InputError, match="below",
         why="z_min > z_max"),
    Case(surface.epipolar_segment, ([[0.0, 0.0]], E1, E2, IO, 100.0, 100.0), raises=InputError, why="z_min = z_max"),
    Case(surface.epipolar_segment, ([[0.0, 0.0]], E1, E2, IO, 100.0, 400.0), raises=PointBehindCameraError,
         why="z_max above the camera"),
    Case(surface.epipolar_segment, ([[0.0, NAN]], E1, E2, IO, 0.0, 100.0), raises=InputError, why="NaN point"),
    Case(surface.epipolar_segment, ([[0.0, 0.0]], E1, E2, IO, NAN, 100.0), raises=InputError, why="NaN z_min"),
    Case(surface.epipolar_segment, ([[0.0, 0.0]], E_UP, E2, IO, 0.0, 100.0), raises=PointBehindCameraError,
         why="ray of image 1 going up"),
    Case(surface.dsm_vertical_line, ([IMG, IMG], IO, [E1, E2], X2, Y2, 110.0, 90.0), {"pixel_size": 0.1},
         raises=InputError, why="z_min > z_max"),
    Case(surface.dsm_vertical_line, ([IMG, IMG[:, :30]], IO, [E1], X2, Y2, 90.0, 110.0), {"pixel_size": 0.1},
         raises=InputError, why="two images, one orientation"),
    Case(surface.dsm_vertical_line, ([IMG, IMG_NAN], IO, [E1, E2], X2, Y2, 90.0, 110.0), {"pixel_size": 0.1},
         raises=InputError, why="NaN pixels"),
    Case(surface.dsm_vertical_line, ([IMG, IMG], IO, [E1, E2], X2, Y2[:1], 90.0, 110.0), {"pixel_size": 0.1},
         raises=InputError, why="X, Y of different shapes"),
    Case(surface.dsm_vertical_line, ([IMG, IMG, IMG], IO, [E1, E2, E1], X2, Y2, 90.0, 110.0), {"pixel_size": 0.1},
         raises=InputError, why="three images to the pair method"),
    Case(surface.dsm_vertical_line, ([IMG, IMG], IO, [E1, E2], X2, Y2, 90.0, 110.0),
         {"pixel_size": 0.1, "steps": (0.1, 1.0)}, raises=InputError, why="steps not decreasing"),
    Case(surface.dsm_vertical_line, ([IMG, IMG], IO, [E1, E2], X2, Y2, 90.0, 350.0), {"pixel_size": 0.1},
         raises=PointBehindCameraError, why="z_max above the cameras"),
    Case(surface.dsm_vertical_line, (IMG, IO, [E1, E2], X2, Y2, 90.0, 110.0), {"pixel_size": 0.1},
         raises=InputError, why="one image instead of a list"),
    Case(surface.dsm_vertical_line, ([FLAT + 1, FLAT + 1], IO, [E1, E2], X2, Y2, 90.0, 110.0), {"pixel_size": 1.0},
         raises=None, why="textureless images: no heights, never a confident guess",
         check=lambda r: not r.valid.any() and np.all(np.isnan(r.Z))),
    Case(surface.dsm_multi_image, ([IMG], IO, [E1], X2, Y2, 90.0, 110.0), {"pixel_size": 0.1}, raises=InputError,
         why="one image"),
    Case(surface.dsm_multi_image, ([IMG, IMG], IO, [E1, E2], X2, Y2, 90.0, 110.0),
         {"pixel_size": 0.1, "pairs": [(0, 0)]}, raises=InputError, why="a pair of one image"),
    Case(surface.dsm_multi_image, ([IMG, IMG], IO, [E1, E2], X2, Y2, 90.0, 110.0),
         {"pixel_size": 0.1, "pairs": [(0, 5)]}, raises=InputError, why="index out of range"),
    Case(surface.dsm_multi_image, ([IMG, IMG], [IO], [E1, E2], X2, Y2, 90.0, 110.0), {"pixel_size": 0.1},
         raises=InputError, why="one camera for two images as a list"),
    Case(surface.DSMResult, (X2, Y2, X2, X2, X2 > 0, np.zeros((2, 2), int), [(0, 1)]), raises=None,
         why="a plain record", check=lambda r: r.valid.all()),
]


@pytest.mark.parametrize("case", CASES, ids=lambda c: c.id)
def test_bad_input(case):
    check_case(case)
