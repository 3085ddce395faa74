"""The scene renderer of photolib.synthetic: scene truth and z-buffered frame rendering (Chapters 5–6)."""

import numpy as np
import pytest

from photolib.camera import ExteriorOrientation, InteriorOrientation
from photolib.single_image import image_to_ground, project
from photolib.synthetic import (Rendering, TerrainScene, image_to_pixel, pixel_to_image, render_image,
                                terrain_scene)


@pytest.fixture(scope="module")
def scene():
    return terrain_scene(extent=80.0, spacing=0.5, n_buildings=3, n_trees=3, seed=3)


def test_scene_is_seeded(scene):
    again = terrain_scene(extent=80.0, spacing=0.5, n_buildings=3, n_trees=3, seed=3)
    other = terrain_scene(extent=80.0, spacing=0.5, n_buildings=3, n_trees=3, seed=4)
    np.testing.assert_array_equal(scene.surface, again.surface)
    np.testing.assert_array_equal(scene.albedo, again.albedo)
    assert not np.array_equal(scene.surface, other.surface)


def test_scene_layers(scene):
    assert isinstance(scene, TerrainScene)
    assert scene.surface.shape == (161, 161) and scene.spacing == 0.5
    assert np.all(scene.surface >= scene.ground - 1e-12)
    assert np.all(scene.surface[~scene.buildings & ~scene.trees] - scene.ground[~scene.buildings & ~scene.trees] <= 0.3 + 1e-12)
    assert len(scene.footprints) == 3 and scene.trees.any()
    assert not np.any(scene.buildings & scene.trees)
    assert 0.0 <= scene.albedo.min() and scene.albedo.max() <= 1.0 and scene.albedo.std() > 0.1
    for bx0, bx1, by0, by1 in scene.footprints:        # flat roof 6–20 m above the highest ground under it
        m = (scene.X >= bx0) & (scene.X <= bx1) & (scene.Y >= by0) & (scene.Y <= by1)
        roof = scene.surface[m]
        assert np.ptp(roof) == 0.0
        assert 6.0 <= roof[0] - scene.ground[m].max() <= 20.0
    f = scene.footprints                                # no two buildings overlap
    for a in range(len(f)):
        for b in range(a + 1, len(f)):
            assert f[a, 1] < f[b, 0] or f[b, 1] < f[a, 0] or f[a, 3] < f[b, 2] or f[b, 3] < f[a, 2]


def test_interpolation_hits_the_nodes_and_planes(scene):
    np.testing.assert_allclose(scene.surface_at(scene.X, scene.Y), scene.surface, atol=1e-9)
    plane = TerrainScene(np.arange(5.0), np.arange(4.0), *(np.zeros((4, 5)),) * 2, np.zeros((4, 5), bool),
                         np.zeros((4, 5), bool), np.zeros((4, 5)), np.zeros((0, 4)))
    plane = TerrainScene(plane.x, plane.y, plane.ground, 2.0 + 0.3 * plane.X - 0.7 * plane.Y, plane.buildings,
                         plane.trees, plane.albedo, plane.footprints)
    rng = np.random.default_rng(0)
    X, Y = rng.uniform(0, 4, 50), rng.uniform(0, 3, 50)
    np.testing.assert_allclose(plane.surface_at(X, Y), 2.0 + 0.3 * X - 0.7 * Y, atol=1e-12)
    assert np.isnan(plane.surface_at(-1.0, 0.0))


def test_discontinuity_distance(scene):
    d = scene.discontinuity_distance(1.0)
    assert d.shape == scene.surface.shape and d.min() == 0.0
    assert np.all(d[scene.buildings] >= 0)


def test_pixel_conversions_round_trip():
    rng = np.random.default_rng(1)
    cr = rng.uniform(0, 99, (20, 2))
    x, y = pixel_to_image(cr[:, 0], cr[:, 1], (80, 100), 0.02)
    np.testing.assert_allclose(image_to_pixel(np.column_stack([x, y]), (80, 100), 0.02), cr, atol=1e-12)
    assert pixel_to_image(49.5, 39.5, (80, 100), 0.02) == (0.0, 0.0)   # frame centre = fiducial centre


def test_flat_scene_matches_monoplotting():
    """Vertical and tilted views of a flat textured plane: XYZ equals Chapter-1 image → ground (1.4.6)."""
    flat = terrain_scene(extent=60.0, spacing=0.5, relief=0.0, n_buildings=0, seed=0)
    io = InteriorOrientation(50.0, 0.03, -0.02)
    for eo in (ExteriorOrientation(30.0, 30.0, 400.0), ExteriorOrientation(30.0, 25.0, 400.0, 0.02, -0.03, 0.4)):
        r = render_image(flat, io, eo, (40, 50), pixel_size=0.04, supersample=1)
        assert r.visible.all()
        rr, cc = np.nonzero(r.visible)
        x, y = pixel_to_image(cc, rr, r.shape, r.pixel_size)
        ref = image_to_ground(np.column_stack([x, y]), 100.0, eo, io)
        np.testing.assert_allclose(r.XYZ[rr, cc], ref, atol=1e-8)
        np.testing.assert_allclose(r.depth[rr, cc], np.linalg.norm(ref - eo.center, axis=1), rtol=1e-12)
        np.testing.assert_allclose(r.image[rr, cc], flat.albedo_at(ref[:, 0], ref[:, 1]), atol=1e-12)


def test_render_points_lie_on_the_surface_and_reproject(scene):
    io = InteriorOrientation(35.0)
    eo = ExteriorOrientation(40.0, 40.0, 360.0, 0.0, -0.08, 0.1)   # tilted: walls and occlusions
    r = render_image(scene, io, eo, (120, 160), pixel_size=0.03)
    assert isinstance(r, Rendering) and r.visible.any()
    rr, cc = np.nonzero(r.visible)
    P = r.XYZ[rr, cc]
    np.testing.assert_allclose(P[:, 2], scene.surface_at(P[:, 0], P[:, 1]), atol=1e-8)
    np.testing.assert_allclose(image_to_pixel(project(P, eo, io), r.shape, r.pixel_size),
                               np.column_stack([cc, rr]), atol=1e-6)


def test_zbuffer_keeps_the_first_hit(scene):
    """Independent ray marching: no surface crossing between S and the point found (occlusion)."""
    io = InteriorOrientation(35.0)
    eo = ExteriorOrientation(-40.0, 40.0, 220.0, 0.0, -0.5, 0.0)    # oblique, looking along +X
    r = render_image(scene, io, eo, (60, 80), pixel_size=0.2, supersample=1)
    rr, cc = np.nonzero(r.visible)
    P = r.XYZ[rr, cc]
    S = eo.center
    t = np.linspace(0.0, 0.995, 800)[:, None, None]
    ray = S + t * (P - S)                                    # (800, n, 3)
    inside = (ray[..., 0] >= 0) & (ray[..., 0] <= 80) & (ray[..., 1] >= 0) & (ray[..., 1] <= 80)
    z = scene.surface_at(np.clip(ray[..., 0], 0, 80), np.clip(ray[..., 1], 0, 80))
    below = inside & (ray[..., 2] < z - 1e-6)
    assert not below.any()
    # the oblique view really has occlusions: building nodes' back sides project inside the frame
    # but lie farther than the depth seen there
    nodes = np.column_stack([scene.X.ravel(), scene.Y.ravel(), scene.surface.ravel()])
    cr = np.rint(r.project(nodes)).astype(int)
    ok = (cr[:, 0] >= 0) & (cr[:, 0] < 80) & (cr[:, 1] >= 0) & (cr[:, 1] < 60)
    dist = np.linalg.norm(nodes[ok] - S, axis=1)
    assert np.sum(dist > r.depth[cr[ok, 1], cr[ok, 0]] + 5.0) > 100


def test_supersampling_and_noise(scene):
    io, eo = InteriorOrientation(35.0), ExteriorOrientation(40.0, 40.0, 300.0)
    a = render_image(scene, io, eo, (50, 50), pixel_size=0.03, supersample=1)
    b = render_image(scene, io, eo, (50, 50), pixel_size=0.03, supersample=3)
    c = render_image(scene, io, eo, (50, 50), pixel_size=0.03, supersample=3, noise=0.02, seed=5)
    np.testing.assert_array_equal(a.XYZ, b.XYZ)
    assert 0 < np.abs(a.image - b.image).mean() < 0.1
    assert abs(np.std(c.image - b.image) - 0.02) < 0.003


def test_background_outside_the_scene(scene):
    io, eo = InteriorOrientation(35.0), ExteriorOrientation(0.0, 0.0, 300.0)   # over the corner
    r = render_image(scene, io, eo, (40, 40), pixel_size=0.05, background=-1.0)
    assert r.visible.any() and not r.visible.all()
    assert np.all(r.image[~r.visible] == -1.0) and np.all(np.isnan(r.depth[~r.visible]))
