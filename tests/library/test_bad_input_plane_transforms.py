"""Bad-input catalogue for photolib.plane_transforms (Hanzl §2.5, plane transformations)."""

import numpy as np
import pytest

from catalogue import INF, NAN, Case, check_case
from photolib import plane_transforms as pt
from photolib.derivations import plane as plane_models
from photolib.errors import DegenerateGeometryError, InputError

SQ = [[0.0, 0.0], [10.0, 0.0], [10.0, 10.0], [0.0, 10.0]]
SQ2 = [[1.0, 2.0], [21.0, 2.0], [21.0, 32.0], [1.0, 32.0]]
LINE = [[0.0, 0.0], [1.0, 1.0], [2.0, 2.0], [3.0, 3.0]]
AFF = pt.PlaneTransform("affine", [2.0, 0.0, 1.0, 0.0, 3.0, 2.0])
PROJ = pt.PlaneTransform("projective", [1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.1, 0.0])

CASES = [
    # fit_plane_transform
    Case(pt.fit_plane_transform, (SQ, SQ2, "helmert"), raises=InputError, match="unknown", why="unknown kind"),
    Case(pt.fit_plane_transform, (SQ, SQ2, 6), raises=InputError, why="kind not a string"),
    Case(pt.fit_plane_transform, (SQ, SQ2[:3], "affine"), raises=InputError, why="different counts"),
    Case(pt.fit_plane_transform, ([[0.0, 0.0, 0.0]] * 4, SQ2, "affine"), raises=InputError, why="3-D points"),
    Case(pt.fit_plane_transform, ([[NAN, 0.0]] + SQ[1:], SQ2, "affine"), raises=InputError, why="NaN point"),
    Case(pt.fit_plane_transform, (SQ, [[INF, 0.0]] + SQ2[1:], "affine"), raises=InputError, why="inf point"),
    Case(pt.fit_plane_transform, ("abcd", SQ2, "affine"), raises=InputError, why="text points"),
    Case(pt.fit_plane_transform, (SQ[:2], SQ2[:2], "affine"), raises=DegenerateGeometryError,
         match="at least 3", why="2 points for the affine kind"),
    Case(pt.fit_plane_transform, (SQ[:3], SQ2[:3], "projective"), raises=DegenerateGeometryError,
         match="at least 4", why="3 points for the projective kind"),
    Case(pt.fit_plane_transform, (SQ, SQ2, "polynomial"), raises=DegenerateGeometryError,
         match="at least 6", why="4 points for the polynomial kind"),
    Case(pt.fit_plane_transform, (SQ[:1], SQ2[:1], "congruent"), raises=DegenerateGeometryError,
         match="at least 2", why="1 point for the congruent kind"),
    Case(pt.fit_plane_transform, (LINE, SQ2, "affine"), raises=DegenerateGeometryError, match="collinear",
         why="collinear points"),
    Case(pt.fit_plane_transform, (LINE, SQ2, "bilinear"), raises=DegenerateGeometryError, match="collinear",
         why="collinear points (bilinear)"),
    Case(pt.fit_plane_transform, ([[1.0, 1.0]] * 3, SQ2[:3], "similarity"), raises=DegenerateGeometryError,
         match="coincide", why="coincident points"),
    Case(pt.fit_plane_transform, (SQ, SQ2, "affine"), kwargs={"weights": [1.0, 1.0, -1.0, 1.0]},
         raises=InputError, why="negative weight"),
    Case(pt.fit_plane_transform, (SQ, SQ2, "affine"), kwargs={"weights": [1.0, 1.0]}, raises=InputError,
         why="wrong number of weights"),
    Case(pt.fit_plane_transform, (LINE, np.array(LINE) * 2.0 + 1.0, "similarity"), raises=None,
         why="collinear points suffice for a similarity", check=lambda t: np.allclose(t.parameters, [2, 0, 1, 1])),
    Case(pt.fit_plane_transform, (SQ, SQ2, "Collinear"), raises=None, why="alias, any case",
         check=lambda t: t.kind == "projective" and np.allclose(t.apply(SQ), SQ2)),
    # PlaneTransform
    Case(pt.PlaneTransform, ("affine", [1.0, 2.0]), raises=InputError, match="6 parameters",
         why="wrong number of parameters"),
    Case(pt.PlaneTransform, ("affine", [1.0, 0.0, 0.0, 0.0, NAN, 0.0]), raises=InputError, why="NaN parameter"),
    Case(pt.PlaneTransform, ("affine", "abcdef"), raises=InputError, why="text parameters"),
    Case(pt.PlaneTransform, ("rubber-sheet", [1.0, 2.0]), raises=InputError, why="unknown kind"),
    Case(pt.PlaneTransform, ("congruent", [0.0, 1.0, 2.0]), raises=None, why="plain record",
         check=lambda t: np.allclose(t.matrix, [[1, 0, 1], [0, 1, 2], [0, 0, 1]])),
    Case(AFF.apply, ([[1.0, 2.0, 3.0]],), raises=InputError, why="3-D points to apply"),
    Case(AFF.apply, ([[NAN, 2.0]],), raises=InputError, why="NaN point to apply"),
    Case(AFF.apply, ([],), raises=InputError, why="no points"),
    Case(PROJ.apply, ([[-10.0, 0.0]],), raises=DegenerateGeometryError, match="vanishing line",
         why="point on the vanishing line"),
    # AffineDecomposition
    Case(pt.AffineDecomposition, (0.0, 1.0, 0.0, 0.0), raises=InputError, match="positive", why="q_x = 0"),
    Case(pt.AffineDecomposition, (1.0, 1.0, NAN, 0.0), raises=InputError, why="NaN angle"),
    Case(pt.AffineDecomposition, (1.0, 1.0, [0.0, 1.0], 0.0), raises=InputError, why="array angle"),
    # affine_decomposition
    Case(pt.affine_decomposition, ([[1.0, 0.0], [0.0, 0.0]],), raises=DegenerateGeometryError, match="zero",
         why="zero column"),
    Case(pt.affine_decomposition, (np.zeros((2, 2)),), raises=DegenerateGeometryError, why="zero matrix"),
    Case(pt.affine_decomposition, (np.eye(3),), raises=InputError, why="3×3 matrix"),
    Case(pt.affine_decomposition, ([[1.0, INF], [0.0, 1.0]],), raises=InputError, why="inf entry"),
    Case(pt.affine_decomposition, (PROJ,), raises=InputError, match="projective", why="projective transform"),
    Case(pt.affine_decomposition, ([[-1.0, 0.0], [0.0, 1.0]],), raises=None, why="a reflection (δα = π)",
         check=lambda d: np.isclose(abs(d.delta_alpha), np.pi) and np.isclose(d.q_x, 1.0)),
    # affine_from_decomposition
    Case(pt.affine_from_decomposition, (-1.0, 1.0, 0.0, 0.0), raises=InputError, why="negative scale"),
    Case(pt.affine_from_decomposition, (1.0, 1.0, 0.0, NAN), raises=InputError, why="NaN δα"),
    Case(pt.affine_from_decomposition, (1.0, 1.0, 0.0, 0.0, "a"), raises=InputError, why="text shift"),
    # congruent_model
    Case(plane_models.congruent_model, (), raises=None, why="no input", check=lambda m: len(m.parameters) == 3),
]


@pytest.mark.parametrize("case", CASES, ids=lambda c: c.id)
def test_bad_input(case):
    check_case(case)
