"""The §1.8 as-printed resection adapter (photolib.book.ch01_resection): the flipped reading."""

import numpy as np

from photolib.camera import ExteriorOrientation, InteriorOrientation
from photolib.resection import space_resection

# The §1.8 example as printed (seed lines 650–667).
IO = InteriorOrientation(100.0, 0.0, 0.0)
XYZ = np.array([[1000, 1000, 10], [500, 1500, 15], [1500, 1500, 20], [500, 500, 15], [1500, 500, 20]], float)
XY = np.array([[8.763, -3.503], [-33.520, 50.212], [67.940, 42.748], [-46.273, -46.459], [56.541, -64.224]])
EO0 = ExteriorOrientation.from_degrees(1010, 1300, 900, 0, 0, 0)


def test_as_printed_flipped_reading_converges_elsewhere():
    from photolib.book.ch01_resection import as_printed_resection
    inputs = {"f_mm": 100.0, "x0_mm": 0.0, "y0_mm": 0.0,
              "approx": {"Xs": 1010.0, "Ys": 1300.0, "Zs": 900.0},
              "true_eo": {"Xs": 1000.0, "Ys": 1000.0, "Zs": 1000.0, "omega_deg": 2.0, "alpha_deg": 5.0, "kappa_deg": 7.0},
              "points": np.column_stack([np.arange(1, 6), XYZ, XY]).tolist()}
    run = as_printed_resection(inputs)
    correct = space_resection(XYZ, XY, IO, EO0).eo.vector
    assert abs(run.flipped.x[1] - correct[1]) > 0.1                   # not the least-squares solution
    assert np.all(np.abs(run.flipped.x[:3] - 1000) < 1)
