"""Figures for Chapter 10, §10.3: a flight plan over real relief.

* :func:`strip_scene` — a strip of vertical images planned on the mean plane of a DEM window
  (:func:`photolib.planning.plan_block`) and flown over the DEM (:func:`photolib.planning.strip_over_relief`);
* :func:`srtm_scene` — the same over the SRTM 3″ DEM of ``../shared/data/dem/srtm_ref.tif``
  (EPSG:4326 resampled to a local transverse Mercator frame, :func:`photolib.planning.dem_to_local`);
* :func:`synthetic_scene` — the same over :func:`photolib.synthetic.terrain_height` (no data needed);
* :func:`flight_plan_over_relief` — footprints on the DEM, GSD along the strip and the forward
  overlap of each pair with its minimum.

Every figure function returns the matplotlib Figure (closed, so that a notebook shows it once)
together with the numbers it shows, rounded.
"""

from __future__ import annotations

from dataclasses import dataclass

import matplotlib.pyplot as plt
import numpy as np

from ...planning import FlightPlan, StripOverRelief, dem_to_local, plan_block, strip_over_relief, surface_dem
from ...rectify import RasterGrid
from ...synthetic import terrain_height

# a large-format camera: f = 100 mm, 6 µm pixels, 11 000 × 17 000 (along × across the flight)
CAMERA = dict(f=100.0, pixel_size=0.006, sensor=(11000, 17000))


@dataclass
class StripScene:
    """A DEM window, the plan on its mean plane and the strip flown over the relief."""

    dem: np.ndarray
    grid: RasterGrid
    plan: FlightPlan
    strip: StripOverRelief
    label: str


def _done(fig):
    plt.close(fig)
    return fig


def strip_scene(dem, grid, *, length, gsd, forward_overlap=0.6, label="", samples=40, camera=CAMERA):
    """Plan one strip along X through the window's centre on its mean plane and fly it over the DEM."""
    x0, y0, x1, y1 = grid.extent
    mean = float(np.nanmean(dem))
    plan = plan_block(length, 1.0, gsd=gsd, forward_overlap=forward_overlap, mean_height=mean, **camera)
    cx, cy = (x0 + x1) / 2, (y0 + y1) / 2
    start = np.array([cx - length / 2 + plan.exposure_x[0], cy])
    end = np.array([cx - length / 2 + plan.exposure_x[-1], cy])
    strip = strip_over_relief(dem, grid, start, end, altitude=plan.altitude, base=plan.base, samples=samples,
                              **camera)
    return StripScene(dem, grid, plan, strip, label)


def srtm_scene(bounds=(-12000.0, -6000.0, 12000.0, 6000.0), length=18000.0, gsd=0.3, **kw):
    """The strip over SRTM (raises photolib.datasets.DataUnavailableError when the data is absent)."""
    from ...datasets import data_path
    from ...georaster import read_dem
    heights, grid, crs = read_dem(data_path("dem", "srtm_ref.tif"))
    Z, local_grid, _ = dem_to_local(heights, grid, crs, bounds=bounds)
    return strip_scene(Z, local_grid, length=length, gsd=gsd, label="SRTM 3″, srtm_ref.tif (local TM frame)", **kw)


def synthetic_scene(length=18000.0, gsd=0.3, **kw):
    """The strip over a synthetic terrain (two crossing waves, 900 m of relief)."""
    def surface(X, Y):
        return terrain_height(X, Y, mean=2000.0, relief=900.0, wavelength=14000.0)
    Z, grid = surface_dem(surface, (-12000.0, -6000.0, 12000.0, 6000.0), 90.0)
    return strip_scene(Z, grid, length=length, gsd=gsd, label="synthetic terrain_height", **kw)


def flight_plan_over_relief(scene: StripScene):
    """Footprints over the DEM, GSD along the strip, forward overlaps with the minimum marked."""
    s, plan = scene.strip, scene.plan
    fig, axes = plt.subplots(3, 1, figsize=(8.0, 9.0), gridspec_kw={"height_ratios": [2.0, 1.0, 1.0]})
    ax = axes[0]
    x0, y0, x1, y1 = scene.grid.extent
    im = ax.imshow(scene.dem, extent=(x0 / 1e3, x1 / 1e3, y0 / 1e3, y1 / 1e3), cmap="terrain", origin="upper")
    fig.colorbar(im, ax=ax, label="height, m", shrink=0.8)
    for i, fp in enumerate(s.footprints):
        closed = np.vstack([fp, fp[:1]]) / 1e3
        ax.plot(closed[:, 0], closed[:, 1], color="C3" if i % 2 else "k", lw=0.8)
    ax.plot(s.centres[:, 0] / 1e3, s.centres[:, 1] / 1e3, "k.", ms=3)
    j = s.min_pair
    for k in (j, j + 1):
        closed = np.vstack([s.footprints[k], s.footprints[k][:1]]) / 1e3
        ax.plot(closed[:, 0], closed[:, 1], color="m", lw=2.0)
    ax.set_xlabel("X, km")
    ax.set_ylabel("Y, km")
    ax.set_title(f"{scene.label}: footprints over the relief (altitude {plan.altitude:.0f} m)")
    n = np.arange(len(s.centres))
    axes[1].fill_between(n, s.gsd_min * 100, s.gsd_max * 100, alpha=0.3, label="min–max in the image")
    axes[1].plot(n, s.gsd_mean * 100, "o-", ms=3, label="mean")
    axes[1].axhline(plan.gsd * 100, color="k", ls="--", lw=0.8, label="planned (mean plane)")
    axes[1].set_ylabel("GSD, cm")
    axes[1].set_xlabel("image")
    axes[1].legend(fontsize=7)
    pairs = np.arange(len(s.forward_overlap)) + 0.5
    axes[2].plot(pairs, s.forward_overlap * 100, "o-", ms=3)
    axes[2].axhline(plan.forward_overlap * 100, color="k", ls="--", lw=0.8, label="planned")
    axes[2].plot(pairs[j], s.min_overlap * 100, "ms", label=f"minimum {s.min_overlap:.0%}")
    axes[2].set_ylabel("forward overlap, %")
    axes[2].set_xlabel("pair (between images)")
    axes[2].legend(fontsize=7)
    fig.tight_layout()
    numbers = {"altitude_m": round(plan.altitude, 1), "flying_height_m": round(plan.flying_height, 1),
               "base_m": round(plan.base, 1), "images": len(s.centres),
               "gsd_cm_range": (round(float(s.gsd_min.min()) * 100, 1), round(float(s.gsd_max.max()) * 100, 1)),
               "overlap_planned": plan.forward_overlap, "overlap_min": round(s.min_overlap, 3),
               "overlap_max": round(float(s.forward_overlap.max()), 3), "min_pair": int(j)}
    return _done(fig), numbers
