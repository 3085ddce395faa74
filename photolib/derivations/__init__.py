"""Model equations in sympy and the Jacobians derived from them — the one place for derivatives.

Each photogrammetric problem is written once as sympy expressions of its unknowns
(*parameters*) and its known quantities (*data*). The library never types a partial derivative
by hand: :meth:`Model.compile` differentiates the expressions with sympy and turns residuals
and Jacobian into vectorised numpy functions (printed once into the committed module
``_generated.py``, see :mod:`photolib.derivations.model`).

The book's own printed derivatives are transcribed here too (``printed_*``), so that tests and
notebooks can compare them with the derived ones (``derived_*``) term by term and the
"as printed" modes can reproduce what the book computed with them.

Modules, by topic:

* :mod:`~photolib.derivations.symbols` — the shared sympy symbols.
* :mod:`~photolib.derivations.model` — :class:`Model`, compilation and code generation.
* :mod:`~photolib.derivations.rotation` — rotation matrices, Chapter 1, §1.3 (1.3.1)–(1.3.5).
* :mod:`~photolib.derivations.quaternion` — the quaternion matrix (1.3.7).
* :mod:`~photolib.derivations.distortion` — Brown's distortion, §1.2 (1.2.2)/(1.2.3) and (3.6.2).
* :mod:`~photolib.derivations.collinearity` — collinearity and resection, §1.8–§1.9.
* :mod:`~photolib.derivations.intersection` — forward intersection, Chapter 2, §2.4.
* :mod:`~photolib.derivations.coplanarity` — relative orientation, §2.7–§2.8.
* :mod:`~photolib.derivations.similarity` — absolute orientation of a model, §2.10–§2.11.
* :mod:`~photolib.derivations.bundle` — bundle method, self-calibration, rigs, rolling
  shutter, Chapter 3, §3.5–§3.9.
* :mod:`~photolib.derivations.projective` — the homography, §1.7 and Chapter 4, §4.1.
* :mod:`~photolib.derivations.gnss` — the GNSS-centres paper (appendix).
* :mod:`~photolib.derivations.matching` — least-squares matching, Chapter 5, §5.4.
* :mod:`~photolib.derivations.orthophoto` — the least-squares DSM and orthophoto, Chapter 7, §7.8.
* :mod:`~photolib.derivations.scanner` — pushbroom collinearity, resection and coplanarity,
  Chapter 8, §8.2–§8.8.
* :mod:`~photolib.derivations.radar` — radar positioning, stereo and InSAR, §8.9–§8.13.
* :mod:`~photolib.derivations.georef` — direct georeferencing and scanner triangulation,
  §8.14–§8.15.
* :mod:`~photolib.derivations.shapes` — point-to-sphere and point-to-cylinder distances,
  Chapter 9, §9.11.
* :mod:`~photolib.derivations.lidar` — laser scanning: the laser-line scanner, mobile mapping,
  Chapter 9, §9.1–§9.10.
* :mod:`~photolib.derivations.registration` — the rigid transform without scale (9.5.1).
* :mod:`~photolib.derivations.terrestrial` — condition equations, polar collinearity and the
  normal case of terrestrial pairs, Chapter 11, §11.6–§11.8.
* :mod:`~photolib.derivations.direct_orientation` — the boresight-misalignment calibration
  (6 parameters), Hanzl §7.3.
* :mod:`~photolib.derivations.plane` — the congruent plane transformation of Hanzl's §2.5.
* :mod:`~photolib.derivations.hanzl_foundations` — Hanzl §2: his rotation table, collinearity,
  inverse, DLT and plane projective forms, the affine decomposition and the robust-adjustment formulas.
* :mod:`~photolib.derivations.parallax` — Hanzl §3: the first-order y-parallax of relative
  orientation, the model deformation, printed vs derived formulas of §3.1–§3.2.6.
* :mod:`~photolib.derivations.hanzl_at` — Hanzl §4.4 and §5.4.1: Ebner's 12 orthogonal parameters
  with the radial and tangential ones, Brown's 18 and Murai's model.
* :mod:`~photolib.derivations.estimation` — Hanzl §7.1, §7.3: least squares, sequential least
  squares, the Kalman update and the transition matrix derived from first principles.
* :mod:`~photolib.derivations.planar_target` — Sementsov's planar-target theory (6)–(18) and the
  additional-parameter models (2)–(4), appendix to Chapter 11.
* :mod:`~photolib.derivations.mockup` — collinearity with f, x₀, y₀ unknown and the tripod-head
  centres (20) of Sementsov's mock-up calibrations, appendix to Chapter 11.

Every public name of these modules is available here: ``from photolib import derivations;
derivations.collinearity_model("kaw")``.

Examples
--------
>>> from photolib import derivations
>>> derivations.collinearity_model("kaw").jacobian().shape
(2, 6)
"""

from . import (bundle, collinearity, coplanarity, direct_orientation, distortion, estimation,
               georef, gnss, hanzl_at, hanzl_foundations, intersection, lidar, matching, mockup,
               model, orthophoto, parallax, planar_target, plane, projective, quaternion, radar,
               registration, rotation, scanner, shapes, similarity, symbols, terrestrial)
from .bundle import *  # noqa: F401,F403
from .collinearity import *  # noqa: F401,F403
from .coplanarity import *  # noqa: F401,F403
from .coplanarity import _IMAGE1_SUBS  # noqa: F401 — used by the book's tests
from .direct_orientation import *  # noqa: F401,F403
from .distortion import *  # noqa: F401,F403
from .estimation import *  # noqa: F401,F403
from .georef import *  # noqa: F401,F403
from .gnss import *  # noqa: F401,F403
from .hanzl_at import *  # noqa: F401,F403
from .hanzl_foundations import *  # noqa: F401,F403
from .intersection import *  # noqa: F401,F403
from .lidar import *  # noqa: F401,F403
from .matching import *  # noqa: F401,F403
from .mockup import *  # noqa: F401,F403
from .model import *  # noqa: F401,F403
from .orthophoto import *  # noqa: F401,F403
from .parallax import *  # noqa: F401,F403
from .planar_target import *  # noqa: F401,F403
from .plane import *  # noqa: F401,F403
from .projective import *  # noqa: F401,F403
from .quaternion import *  # noqa: F401,F403
from .radar import *  # noqa: F401,F403
from .registration import *  # noqa: F401,F403
from .rotation import *  # noqa: F401,F403
from .scanner import *  # noqa: F401,F403
from .shapes import *  # noqa: F401,F403
from .similarity import *  # noqa: F401,F403
from .symbols import *  # noqa: F401,F403
from .terrestrial import *  # noqa: F401,F403

__all__ = [name for module in (symbols, model, rotation, quaternion, distortion, collinearity, intersection,
                               coplanarity, similarity, bundle, projective, gnss, matching, orthophoto,
                               scanner, radar, georef, shapes, lidar, registration,
                               terrestrial, planar_target, mockup, plane, direct_orientation)
           for name in module.__all__]
