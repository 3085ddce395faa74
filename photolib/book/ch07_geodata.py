"""Chapter 7, §7.3 (the map-projection variant of orthorectification): adapters for
``textbook/ch07_geodata.toml``.

The book states the chain without numbers: Gauss–Krüger coordinates (GSK-2011) of the DEM nodes
→ geodetic B, L → with the geodetic height H above the reference ellipsoid → geocentric
X, Y, Z, in which the exterior orientation is given; or a topocentric frame (X in the meridian
plane, Z along the ellipsoid normal, Y completing a right-handed system). The adapters check the
chain by two independent routes (pyproj's inverse projection + the closed geodetic formulas on
the GSK-2011 ellipsoid, against PROJ's own projected → geocentric pipeline) and construct the
topocentric axes to see where Y points.
"""

from __future__ import annotations

import numpy as np

GSK2011_GK_ZONE7 = "EPSG:20907"      # GSK-2011 / Gauss–Krüger zone 7 (central meridian 39° E)
GSK2011_GEOCENTRIC = "EPSG:7681"
GSK2011_GEOGRAPHIC = "EPSG:7683"


def geodetic_to_geocentric(B, L, H, a, inverse_flattening):
    """X, Y, Z from B, L (radians) and H on an ellipsoid (the formulas of higher geodesy)."""
    f = 1.0 / inverse_flattening
    e2 = f * (2.0 - f)
    N = a / np.sqrt(1.0 - e2 * np.sin(B) ** 2)
    return ((N + H) * np.cos(B) * np.cos(L), (N + H) * np.cos(B) * np.sin(L),
            (N * (1.0 - e2) + H) * np.sin(B))


def map_projection_chain(inputs: dict) -> dict:
    """GK node → B, L (pyproj) → with H → geocentric (closed formulas) vs PROJ's own pipeline."""
    import pyproj
    from .. import georaster

    rng = np.random.default_rng(int(inputs.get("seed", 1)))
    n = int(inputs.get("points", 20))
    x = 7.0e6 + rng.uniform(3.0e5, 7.0e5, n)
    y = rng.uniform(6.0e6, 6.4e6, n)           # northing ≈ 54°–58° N
    H = rng.uniform(100.0, 300.0, n)
    L, B = georaster.transform_points(x, y, GSK2011_GK_ZONE7, GSK2011_GEOGRAPHIC)
    ellipsoid = pyproj.CRS(GSK2011_GEOGRAPHIC).ellipsoid
    a, rf = float(inputs["a"]), float(inputs["inverse_flattening"])
    same_ellipsoid = abs(ellipsoid.semi_major_metre - a) < 1e-6 and abs(ellipsoid.inverse_flattening - rf) < 1e-9
    ours = np.array(geodetic_to_geocentric(np.radians(B), np.radians(L), H, a, rf))
    proj = pyproj.Transformer.from_crs(pyproj.CRS(GSK2011_GK_ZONE7).to_3d(), GSK2011_GEOCENTRIC, always_xy=True)
    theirs = np.array(proj.transform(x, y, H))
    agree = same_ellipsoid and float(np.max(np.abs(ours - theirs))) < 1e-3
    return {"chain": "GK x, y -> B, L; B, L, H -> geocentric X, Y, Z" if agree else "routes disagree"}


def topocentric_frame(inputs: dict) -> dict:
    """Build the topocentric axes at (B, L): X north in the meridian plane, Z the normal, Y = Z × X."""
    B, L = np.radians(float(inputs["B"])), np.radians(float(inputs["L"]))
    up = np.array([np.cos(B) * np.cos(L), np.cos(B) * np.sin(L), np.sin(B)])
    north = np.array([-np.sin(B) * np.cos(L), -np.sin(B) * np.sin(L), np.cos(B)])
    east = np.array([-np.sin(L), np.cos(L), 0.0])
    Y = np.cross(up, north)                    # completes X (north), Y, Z (up) to a right-handed frame
    det = float(np.linalg.det(np.column_stack([north, Y, up])))
    handed = "right-handed" if det > 0 else "left-handed"
    side = "Y west" if float(Y @ east) < -0.999999 else ("Y east" if float(Y @ east) > 0.999999 else "Y oblique")
    return {"frame": f"{handed}, {side}"}
