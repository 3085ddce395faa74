"""Assignments with answer keys, built on the worked examples of Chapters 1–4 (issue 13, item 4).

An assignment is a worked example of the book with new data: the generator of the example draws a
new, plausible "truth" from a seeded random generator (exterior orientations, control points,
camera data …), computes the derived inputs with the library exactly as the book describes them
(image coordinates by the collinearity equations (1.4.12) plus the noise the book states, printed
intermediate results of a chain such as the relative orientation angles of §2.12) and rounds every
computed input to the decimals the book prints for it. The sheet shows the inputs in the book's
layout; the answer key is what the example's own ``compute`` adapter — the function
``photolib verify`` runs on the book's data — returns for the sheet's inputs, so a key is
solvable by construction and depends only on (example id, seed).

* :data:`GENERATORS` / :func:`available` — the examples that have a generator.
* :func:`make_sheet`, :func:`answer_key`, :func:`write_assignment` — student sheet (Markdown and
  Jupyter notebook) and the separate key (TOML).
* :func:`grade`, :func:`read_answers` — grade a student's ``answers.toml``.

Tolerances (written into the key for every quantity, with the method):

* numbers: half a unit of the decimal the book prints for the quantity — the sheet holds the exact
  numbers the key was computed from, so a correct answer rounded to those decimals is within it;
* unless the rounding of the sheet's computed inputs (each stands for ± half a unit of its last
  printed decimal, ``textbook/README.md``) moves the quantity by more than that: then the bound is
  3σ + half a unit (σ by first-order propagation of uniform rounding errors, each rounded input
  moved by its half unit in turn), the rule of every ``input-rounding`` bound of ``textbook/``
  (:func:`photolib.book.ch02.rounding_bound`);
* where the book itself continues from rounded intermediate results (§2.13: b, m_xy, m_p), the
  bound also covers that reading: half a unit + |book's chain − exact|;
* integers and counts: exact; texts: equal (case and spaces ignored).

``photolib check --strict`` (``grade(..., strict=True)``) grades every number to half a unit instead.

Plausible data: a draw is redrawn (from the same seeded generator, so still deterministic) when
image points fall off the frame, an adjustment does not converge, a key value lies half-way
between two printed values, or the data are more than ``CONDITION_FACTOR`` = 3 times as sensitive
to the rounding of their printed inputs as the book's own example (measured as 3σ over half a
printed unit, worst asked quantity; at least ``CONDITION_FLOOR`` = 10 allowed). Without the last
rule a random §4.4 pair with nearly equal ω has e₃₃ ≈ 0, and F, E normalised by f₃₃ = e₃₃ = 1
become meaningless.
"""

from __future__ import annotations

import copy
import hashlib
import json
import math
import pprint
import tomllib
import zlib
from dataclasses import dataclass, field
from functools import lru_cache
from pathlib import Path
from typing import Callable

import numpy as np

from .. import __version__
from ..camera import ExteriorOrientation, InteriorOrientation
from ..errors import InputError, PhotolibError
from ..image_pair import photo_base
from ..single_image import project
from .ch02 import rounding_bound
from .textbook import Example, available_chapters, load_chapter
from .verify import resolve

__all__ = ["AssignmentError", "Generator", "Asked", "Sheet", "KeyEntry", "AnswerKey", "Verdict", "Grade", "AssignmentFiles",
           "GENERATORS", "available", "make_sheet", "answer_key", "write_assignment", "grade", "read_answers",
           "answers_toml", "printed_decimals"]

ASKED_STATUSES = ("reproduced", "input-rounding", "erratum", "transcription")
MAX_ATTEMPTS = 50
CONDITION_FACTOR = 3.0      # a new data set may be at most 3× as sensitive to input rounding as the book's …
CONDITION_FLOOR = 10.0      # … or 10 half units, whichever is larger


class AssignmentError(InputError):
    """A usage error of the assignment tools: unknown example, no generator, bad seed or answers."""


# --- data types --------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Asked:
    """One quantity a sheet asks for: its name in ``answers.toml``, unit and decimals to give."""

    name: str
    unit: str
    decimals: int | None
    kind: str = "number"                # "number", "integer" or "text"


@dataclass(frozen=True)
class Sheet:
    """The student sheet of an assignment (no answers in it).

    Attributes: ``example_id``, ``seed``, ``chapter``, ``section``, ``title``, ``inputs`` (the
    example's inputs in the textbook's format, exactly those the key is computed from), ``asked``
    (tuple of :class:`Asked`) and ``markdown`` (the statement).
    """

    example_id: str
    seed: int
    chapter: int
    section: str
    title: str
    inputs: dict
    asked: tuple
    markdown: str

    def notebook(self) -> dict:
        """The sheet as a Jupyter notebook (nbformat 4.5, as a dict): statement, inputs, answer cells.

        Written without :mod:`nbformat` (not a dependency of the library); the tests validate it.
        """
        names = "\n".join(f"    {json.dumps(a.name, ensure_ascii=False)}: None," for a in self.asked)
        template = (
            "# Fill in your results (None = not answered), run this cell, then grade with\n"
            f"#     photolib check {self.example_id} --seed {self.seed} answers.toml\n"
            "import json\n\n"
            f"answers = {{\n{names}\n}}\n\n"
            "with open(\"answers.toml\", \"w\", encoding=\"utf-8\") as fh:\n"
            "    for name, value in answers.items():\n"
            "        if value is not None:\n"
            "            value = value if isinstance(value, str) else float(value)\n"
            "            fh.write(f\"{json.dumps(name)} = {json.dumps(value)}\\n\")\n")
        inputs = ("# The inputs of the sheet, in the format of photolib's textbook/ data\n"
                  f"inputs = {pprint.pformat(self.inputs, width=100, sort_dicts=False)}\n")
        cells = [("markdown", self.markdown), ("code", inputs), ("markdown", "## Your solution"), ("code", ""),
                 ("markdown", "## Your answers\n\nWrite them to `answers.toml` (one `name = value` line per "
                              "quantity, decimal points), for example with the cell below."),
                 ("code", template)]
        out = []
        for n, (kind, text) in enumerate(cells, 1):
            cell = {"cell_type": kind, "id": f"cell-{n}", "metadata": {}, "source": text.splitlines(keepends=True)}
            if kind == "code":
                cell.update(execution_count=None, outputs=[])
            out.append(cell)
        return {"cells": out, "nbformat": 4, "nbformat_minor": 5,
                "metadata": {"kernelspec": {"display_name": "Python 3", "language": "python", "name": "python3"},
                             "language_info": {"name": "python"},
                             "photolib_assignment": {"example": self.example_id, "seed": self.seed}}}


@dataclass(frozen=True)
class KeyEntry:
    """One quantity of an answer key: the value (full precision), as printed, unit, tolerance and how."""

    name: str
    value: object
    printed: str
    unit: str
    decimals: int | None
    tolerance: float | None
    method: str
    kind: str = "number"
    half_unit: float | None = None       # the strict tolerance: half a unit of the printed decimal


@dataclass(frozen=True)
class AnswerKey:
    """The answer key of (example, seed): one :class:`KeyEntry` per asked quantity."""

    example_id: str
    seed: int
    chapter: int
    section: str
    title: str
    entries: tuple
    inputs_sha256: str

    @property
    def names(self) -> list:
        return [e.name for e in self.entries]

    def entry(self, name: str) -> KeyEntry:
        for e in self.entries:
            if e.name == name:
                return e
        raise KeyError(name)

    def to_toml(self) -> str:
        """The key as TOML (``[assignment]`` and one ``[[answer]]`` table per quantity)."""
        lines = [f"# Answer key: photolib assignment {self.example_id}, seed {self.seed}. Not for students.",
                 "# value: full precision; printed: as the book would print it; an answer is right when",
                 "# |answer - value| <= tolerance (method says where the tolerance comes from);",
                 "# with --strict, <= strict_tolerance (half a unit of the printed decimal).",
                 "", "[assignment]",
                 f"example = {_toml(self.example_id)}", f"seed = {self.seed}", f"chapter = {self.chapter}",
                 f"section = {_toml(self.section)}", f"title = {_toml(self.title)}",
                 f"inputs_sha256 = {_toml(self.inputs_sha256)}", f"photolib = {_toml(__version__)}"]
        for e in self.entries:
            lines += ["", "[[answer]]", f"name = {_toml(e.name)}", f"value = {_toml(e.value)}",
                      f"printed = {_toml(e.printed)}", f"unit = {_toml(e.unit)}", f"kind = {_toml(e.kind)}"]
            if e.decimals is not None:
                lines.append(f"decimals = {e.decimals}")
            if e.tolerance is not None:
                lines.append(f"tolerance = {_toml(e.tolerance)}")
            if e.half_unit is not None:
                lines.append(f"strict_tolerance = {_toml(e.half_unit)}")
            lines.append(f"method = {_toml(e.method)}")
        return "\n".join(lines) + "\n"


@dataclass(frozen=True)
class Verdict:
    """The grade of one quantity: ``status`` is "correct", "wrong" or "missing"."""

    name: str
    status: str
    answer: object
    expected: object
    printed: str
    tolerance: float | None
    unit: str

    def line(self) -> str:
        unit = f" {self.unit}" if self.unit else ""
        answer = f"{self.answer:.10g}" if isinstance(self.answer, float) else self.answer
        tol = f" ± {self.tolerance:g}" if self.tolerance is not None else ""
        if self.status == "correct":
            return f"{self.name}: correct ({answer}{unit})"
        if self.status == "missing":
            return f"{self.name}: missing (expected {self.printed}{tol}{unit})"
        return f"{self.name}: WRONG, answer {answer}{unit}, expected {self.printed}{tol}{unit}"


@dataclass(frozen=True)
class Grade:
    """The grade of an answer sheet: one :class:`Verdict` per asked quantity."""

    example_id: str
    seed: int
    verdicts: tuple

    @property
    def correct(self) -> int:
        return sum(v.status == "correct" for v in self.verdicts)

    @property
    def total(self) -> int:
        return len(self.verdicts)

    @property
    def ok(self) -> bool:
        return self.correct == self.total

    def count(self, status: str) -> int:
        return sum(v.status == status for v in self.verdicts)

    def report(self) -> str:
        head = (f"{self.example_id}, seed {self.seed}: {self.correct} of {self.total} correct "
                f"({self.count('wrong')} wrong, {self.count('missing')} missing)")
        return "\n".join([head] + [f"  {v.line()}" for v in self.verdicts])


@dataclass(frozen=True)
class AssignmentFiles:
    """Paths written by :func:`write_assignment`."""

    markdown: Path
    notebook: Path
    key: Path


# --- formatting ------------------------------------------------------------------------------------------
def _toml(value) -> str:
    if isinstance(value, bool):
        return "true" if value else "false"
    if isinstance(value, int):
        return str(value)
    if isinstance(value, float):
        return "nan" if math.isnan(value) else ("inf" if value > 0 else "-inf") if math.isinf(value) else repr(value)
    return json.dumps(str(value), ensure_ascii=False)


def _fmt(value, decimals) -> str:
    """``value`` with ``decimals`` decimals (negative: rounded to tens, hundreds …); ints as ints."""
    if isinstance(value, str):
        return value
    if decimals is None:
        return f"{value:g}"
    if decimals <= 0:
        return str(int(round(float(value), decimals)))
    text = f"{float(value):.{decimals}f}"
    return "0." + "0" * decimals if text == "-0." + "0" * decimals else text


def printed_decimals(values) -> int:
    """The most decimals among numbers as the textbook holds them (shortest form, trailing zeros lost).

    A printed column such as 8,763 / −33,520 / 67,940 reaches ``textbook/`` as 8.763, −33.52,
    67.94; the most decimals over the column, 3, is the printed precision.

    Parameters
    ----------
    values : iterable of numbers

    Returns
    -------
    int

    Raises
    ------
    AssignmentError
        No numbers.

    References
    ----------
    ``textbook/README.md`` (``decimals``: a printed number stands for ± half a unit of its last decimal).

    Examples
    --------
    >>> printed_decimals([8.763, -33.52, 67.94, 1000])
    3
    """
    values = list(np.ravel(np.asarray(values, dtype=float)))
    if not values:
        raise AssignmentError("no numbers to read the printed decimals from")
    best = 0
    for v in values:
        text = repr(float(v))
        if "e" in text:
            mantissa, _, exp = text.partition("e")
            digits = len(mantissa.partition(".")[2].rstrip("0"))
            best = max(best, digits - int(exp))
        else:
            best = max(best, len(text.partition(".")[2].rstrip("0")))
    return best


def _num(value) -> str:
    """A design value (integer-valued floats without decimals)."""
    return str(int(value)) if float(value).is_integer() else f"{value:g}"


def _md_table(header, rows, align="---:") -> str:
    out = ["| " + " | ".join(header) + " |", "|" + "|".join(align for _ in header) + "|"]
    out += ["| " + " | ".join(map(str, r)) + " |" for r in rows]
    return "\n".join(out)


def _eo_text(eo: dict) -> str:
    return (f"X_S = {_num(eo['Xs'])} m, Y_S = {_num(eo['Ys'])} m, Z_S = {_num(eo['Zs'])} m, "
            f"ω = {_num(eo['omega_deg'])}°, α = {_num(eo['alpha_deg'])}°, κ = {_num(eo['kappa_deg'])}°")


def _camera_text(inputs: dict) -> str:
    return (f"Interior orientation of the camera: f = {inputs['f_mm']:.1f} mm, x₀ = {inputs['x0_mm']:.1f} mm, "
            f"y₀ = {inputs['y0_mm']:.1f} mm.")


# --- the book's data ------------------------------------------------------------------------------------------
def _book(chapter: int, example_id: str) -> Example:
    return load_chapter(chapter).example(example_id)


def _column_decimals(chapter: int, example_id: str, key: str, columns) -> int:
    rows = np.asarray(_book(chapter, example_id).inputs[key], dtype=float)
    return printed_decimals(rows[:, list(columns)])


def _quantity_decimals(chapter: int, example_id: str, names) -> int:
    """The decimals the book prints for ``names`` (the most frequent, if the table is not uniform)."""
    qs = {q.name: q for q in _book(chapter, example_id).quantities}
    found = [qs[n].decimals for n in names]
    return max(set(found), key=found.count)


# --- generators -------------------------------------------------------------------------------------------
# Each family generator draws one complete data set (the book's input keys, plus the printed
# intermediate results of a chain) from ``rng``; every member example shows and uses a part of it.
def _gen_rotation(rng) -> dict:
    book = _book(1, "1.3-rotation-matrix").inputs
    while True:
        w, a, k = (float(v) for v in (rng.integers(-15, 16), rng.integers(-15, 16), rng.integers(-30, 31)))
        if (w, a, k) != (book["omega_deg"], book["alpha_deg"], book["kappa_deg"]):
            return {"omega_deg": w, "alpha_deg": a, "kappa_deg": k, "order": book["order"]}


def _gen_height_error(rng) -> dict:
    f = float(rng.choice([35, 50, 60, 80, 100, 120, 150]))
    x_max = float(rng.choice([20, 25, 30, 40, 45, 50, 60]))
    y_max = float(rng.choice([v for v in (15, 20, 25, 30, 40, 45, 50, 60) if v <= x_max]))
    return {"f_mm": f, "x_max_mm": x_max, "y_max_mm": y_max, "dZ_m": float(rng.integers(2, 31))}


def _eo_dict(Xs, Ys, Zs, angles) -> dict:
    return {"Xs": float(Xs), "Ys": float(Ys), "Zs": float(Zs), "omega_deg": float(angles[0]),
            "alpha_deg": float(angles[1]), "kappa_deg": float(angles[2])}


def _eo(d: dict, order: str) -> ExteriorOrientation:
    return ExteriorOrientation.from_degrees(d["Xs"], d["Ys"], d["Zs"], d["omega_deg"], d["alpha_deg"],
                                            d["kappa_deg"], order)


def _in_frame(xy, half: float = 90.0) -> bool:
    return bool(np.all(np.abs(xy) < half))


def _gen_resection(rng) -> dict:
    """§1.8/§1.9: one image over five control points (the book's layout: centre and four corners)."""
    book = _book(1, "1.8-resection").inputs
    d = _column_decimals(1, "1.8-resection", "points", (4, 5))
    order, sigma = book["order"], book["sigma_mm"]
    io = InteriorOrientation(book["f_mm"], book["x0_mm"], book["y0_mm"])
    Xs, Ys = (1000 + 10 * int(rng.integers(-30, 31)) for _ in range(2))
    Zs = 10 * int(rng.integers(90, 121))
    angles = [int(rng.integers(-5, 6)), int(rng.integers(-5, 6)), int(rng.integers(-10, 11))]
    true_eo = _eo_dict(Xs, Ys, Zs, angles)
    cx, cy = (v + 10 * int(rng.integers(-5, 6)) for v in (Xs, Ys))
    pattern = [(0, 0), (-1, 1), (1, 1), (-1, -1), (1, -1)]
    spread = 100 * int(rng.integers(4, 6))
    XYZ = np.array([[cx + sx * spread + 10 * int(rng.integers(-8, 9)), cy + sy * spread + 10 * int(rng.integers(-8, 9)),
                     int(rng.integers(0, 41))] for sx, sy in pattern], dtype=float)
    xy = project(XYZ, _eo(true_eo, order), io) + rng.normal(0.0, sigma, (len(XYZ), 2))
    points = [[n + 1, int(P[0]), int(P[1]), int(P[2]), round(float(p[0]), d), round(float(p[1]), d)]
              for n, (P, p) in enumerate(zip(XYZ, xy))]
    approx = {"Xs": float(Xs + 10 * int(rng.integers(-30, 31))), "Ys": float(Ys + 10 * int(rng.integers(-30, 31))),
              "Zs": float(Zs + 10 * int(rng.integers(-15, 16)))}
    if not _in_frame(np.asarray(points)[:, 4:6], 80.0):
        raise _Redraw("image points outside the frame")
    return {"f_mm": book["f_mm"], "x0_mm": book["x0_mm"], "y0_mm": book["y0_mm"], "order": order,
            "sigma_mm": sigma, "true_eo": true_eo, "points": points,
            "approx": {**approx, "omega_deg": 0.0, "alpha_deg": 0.0, "kappa_deg": 0.0}, "approx_centre": approx}


def _gen_subpixel(rng) -> dict:
    book = _book(1, "1.10-physical").inputs
    n = book["n"]           # n = 5: (j' + 0.5)/n has one decimal, the precision the book prints
    while True:
        out = {"i": int(rng.integers(1, 13)), "j": int(rng.integers(1, 13)), "i_sub": int(rng.integers(0, n)),
               "j_sub": int(rng.integers(0, n)), "n": n,
               "pixel_size_um": float(rng.choice([5, 6, 7, 9, 10, 12, 14, 15, 20, 25]))}
        if any(out[k] != book[k] for k in ("i", "j", "i_sub", "j_sub")):
            return out


def _gen_stereo_radius(rng) -> dict:
    book = _book(2, "2.1-stereo-radius").inputs
    while True:
        b, g = float(rng.integers(55, 73)), float(rng.choice([10, 15, 20, 25, 30]))
        if (b, g) != (book["b_mm"], book["gamma_min_arcsec"]):
            return {"b_mm": b, "gamma_min_arcsec": g, "rho_arcsec": book["rho_arcsec"]}


def _gen_dmc3(rng) -> dict:
    book = _book(2, "2.13-dmc3-accuracy").inputs
    return {"H_m": float(100 * rng.integers(8, 41)), "overlap_percent": float(rng.choice([60, 65, 70, 75, 80])),
            "f_mm": book["f_mm"], "frame_px_x": book["frame_px_x"], "frame_px_y": book["frame_px_y"],
            "pixel_um": book["pixel_um"], "m_xy_px": float(rng.choice([0.3, 0.4, 0.5, 0.6])),
            "m_p_px": float(rng.choice([0.2, 0.3, 0.4]))}


def _dmc3_compute(inputs: dict) -> dict:
    """The §2.13 adapter on the stated data: the book's rounded intermediates are derived first.

    ``photolib.book.ch02_theory:dmc3_accuracy`` also takes the book's printed intermediate values
    (b = 22.8 mm, m_xy = 2 μm, m_p = 1.2 μm); a sheet must not give them away, so they are
    computed here from the stated data (:func:`photolib.image_pair.photo_base`) and rounded to the
    decimals the book prints for them, then the adapter runs unchanged.
    """
    full = dict(inputs)
    frame = inputs["frame_px_x"] * inputs["pixel_um"] * 1e-3
    full["b_printed_mm"] = round(float(photo_base(frame, inputs["overlap_percent"])),
                                 _quantity_decimals(2, "2.13-dmc3-accuracy", ["b_mm"]))
    full["m_xy_printed_um"] = round(inputs["m_xy_px"] * inputs["pixel_um"],
                                    _quantity_decimals(2, "2.13-dmc3-accuracy", ["m_xy_um"]))
    full["m_p_printed_um"] = round(inputs["m_p_px"] * inputs["pixel_um"],
                                   _quantity_decimals(2, "2.13-dmc3-accuracy", ["m_p_um"]))
    return resolve("photolib.book.ch02_theory:dmc3_accuracy")(full)


def _zone_points(rng, x_left, x_right, y_mid, half_width, n_extra):
    """Six standard-zone points (§2.8) at the two principal points and the four overlap corners,
    then ``n_extra`` points near them, with integer heights."""
    zones = [(x_left, y_mid), (x_right, y_mid), (x_left, y_mid + half_width), (x_left, y_mid - half_width),
             (x_right, y_mid + half_width), (x_right, y_mid - half_width)]
    pts = [(x + 10 * int(rng.integers(-3, 4)), y + 10 * int(rng.integers(-3, 4))) for x, y in zones]
    for k in range(n_extra):
        x, y = zones[k % 6]
        pts.append((x + 10 * int(rng.integers(-6, 7)), y + 10 * int(rng.integers(-6, 7))))
    return pts


def _gen_pair(rng) -> dict:
    """§2.12 example: two images, 12 points; the chain's printed intermediates computed by the library."""
    book = _book(2, "2.ex-ro").inputs
    d_xy = _column_decimals(2, "2.ex-ro", "points", (4, 5, 6, 7))
    d_ro = _quantity_decimals(2, "2.ex-ro", ["alpha1_deg", "kappa1_deg", "omega2_deg", "alpha2_deg", "kappa2_deg"])
    d_model = _quantity_decimals(2, "2.ex-model-points", [f"{c}M{i}" for i in range(1, 13) for c in "XYZ"])
    order = "kaw"
    io = InteriorOrientation(book["f_mm"], book["x0_mm"], book["y0_mm"])
    Xs1, Ys1 = (1000 + 10 * int(rng.integers(-20, 21)) for _ in range(2))
    Zs1 = 10 * int(rng.integers(90, 111))
    base = 10 * int(rng.integers(45, 56))
    eo1 = _eo_dict(Xs1, Ys1, Zs1, rng.integers(-3, 4, 3))
    eo2 = _eo_dict(Xs1 + base, Ys1 + 10 * int(rng.integers(-2, 3)), Zs1 + 10 * int(rng.integers(-2, 3)),
                   rng.integers(-3, 4, 3))
    XY = _zone_points(rng, Xs1, Xs1 + base, Ys1, 500, 6)
    XYZ = np.array([[x, y, int(rng.integers(0, 21))] for x, y in XY], dtype=float)
    xy1 = project(XYZ, _eo(eo1, order), io) + rng.normal(0.0, book["sigma_mm"], (12, 2))
    xy2 = project(XYZ, _eo(eo2, order), io) + rng.normal(0.0, book["sigma_mm"], (12, 2))
    if not (_in_frame(xy1) and _in_frame(xy2)):
        raise _Redraw("image points outside the frame")
    points = [[n + 1, int(P[0]), int(P[1]), int(P[2]), *(round(float(v), d_xy) for v in (*p1, *p2))]
              for n, (P, p1, p2) in enumerate(zip(XYZ, xy1, xy2))]
    data = {k: book[k] for k in ("f_mm", "x0_mm", "y0_mm", "sigma_mm")}
    data.update(true_eo1=eo1, true_eo2=eo2, points=points, ro_approx_deg=list(book["ro_approx_deg"]),
                base_m=book["base_m"], ao_approx=dict(book["ao_approx"]))
    # the book continues from its printed RO angles and model coordinates: compute and round them
    ro = resolve("photolib.book.ch02:relative_orientation_example")(
        {k: data[k] for k in ("f_mm", "x0_mm", "y0_mm", "points", "ro_approx_deg")})
    data["ro_deg"] = [round(ro[f"{k}_deg"], d_ro) for k in ("alpha1", "kappa1", "omega2", "alpha2", "kappa2")]
    model = resolve("photolib.book.ch02:model_points_example")(
        {k: data[k] for k in ("f_mm", "x0_mm", "y0_mm", "points", "ro_deg", "base_m")})
    data["model_points"] = [[round(model[f"{c}M{i}"], d_model) for c in "XYZ"] for i in range(1, 13)]
    return data


def _gen_dlt(rng) -> dict:
    """§4.3 example: two images, ten control points at several heights (the DLT needs them off a plane)."""
    book = _book(4, "4.3-dlt").inputs
    d = _column_decimals(4, "4.3-dlt", "points", (4, 5, 6, 7))
    order = "kaw"
    io = InteriorOrientation(book["f_mm"], book["x0_mm"], book["y0_mm"])
    Xs1, Ys1 = (1000 + 10 * int(rng.integers(-20, 21)) for _ in range(2))
    Zs = 10 * int(rng.integers(90, 111))
    base = 10 * int(rng.integers(45, 56))
    eo1 = _eo_dict(Xs1, Ys1, Zs, rng.integers(-9, 10, 3))
    eo2 = _eo_dict(Xs1 + base, Ys1, Zs, rng.integers(-9, 10, 3))
    XY = _zone_points(rng, Xs1, Xs1 + base, Ys1, 500, 4)
    Z = 10 * rng.permutation(np.r_[rng.integers(-10, 0, 4), rng.integers(0, 15, 6)])
    XYZ = np.column_stack([np.asarray(XY, dtype=float), Z.astype(float)])
    xy1 = project(XYZ, _eo(eo1, order), io) + rng.normal(0.0, book["sigma_mm"], (10, 2))
    xy2 = project(XYZ, _eo(eo2, order), io) + rng.normal(0.0, book["sigma_mm"], (10, 2))
    if not (_in_frame(xy1) and _in_frame(xy2)):
        raise _Redraw("image points outside the frame")
    points = [[float(n + 1), *map(float, P), *(round(float(v), d) for v in (*p1, *p2))]
              for n, (P, p1, p2) in enumerate(zip(XYZ, xy1, xy2))]
    return {**{k: book[k] for k in ("f_mm", "x0_mm", "y0_mm", "sigma_mm")}, "true_eo1": eo1, "true_eo2": eo2,
            "points": points}


def _gen_fe(rng) -> dict:
    """§4.4 example: twelve image points of a pair (object points not printed), F and E from the first 8."""
    book = _book(4, "4.4-F").inputs
    d = _column_decimals(4, "4.4-F", "points", (1, 2, 3, 4))
    order = "kaw"
    io = InteriorOrientation(book["f_mm"], book["x0_mm"], book["y0_mm"])
    Xs1, Ys1 = (1000 + 10 * int(rng.integers(-20, 21)) for _ in range(2))
    Zs = 10 * int(rng.integers(90, 111))
    base = 10 * int(rng.integers(45, 56))
    eo1 = _eo_dict(Xs1, Ys1, Zs, rng.integers(-5, 6, 3))
    eo2 = _eo_dict(Xs1 + base, Ys1, Zs, rng.integers(-5, 6, 3))
    if abs(eo2["omega_deg"] - eo1["omega_deg"]) < 3:
        # e₃₃ ≈ sin Δω for a base along X: with f₃₃ = e₃₃ = 1 a small Δω makes F and E ill-determined
        raise _Redraw("the images' ω differ by less than the book's 3°")
    XY = _zone_points(rng, Xs1, Xs1 + base, Ys1, 550, 6)
    XYZ = np.array([[x, y, float(rng.integers(0, 201))] for x, y in XY], dtype=float)
    xy1 = project(XYZ, _eo(eo1, order), io) + rng.normal(0.0, book["sigma_mm"], (12, 2))
    xy2 = project(XYZ, _eo(eo2, order), io) + rng.normal(0.0, book["sigma_mm"], (12, 2))
    if not (_in_frame(xy1) and _in_frame(xy2)):
        raise _Redraw("image points outside the frame")
    points = [[float(n + 1), *(round(float(v), d) for v in (*p1, *p2))] for n, (p1, p2) in enumerate(zip(xy1, xy2))]
    return {**{k: book[k] for k in ("f_mm", "x0_mm", "y0_mm", "sigma_mm", "n_solve")}, "true_eo1": eo1,
            "true_eo2": eo2, "points": points}


def _gen_penta(rng) -> dict:
    book = _book(3, "3.8-penta-unknowns").inputs
    while True:
        n, ns = 50 * int(rng.integers(4, 61)), int(rng.integers(2, 7))
        if (n, ns) != (book["n_exposures"], book["n_cameras"]):
            return {"n_exposures": n, "n_cameras": ns, "n_points": book["n_points"]}


class _Redraw(Exception):
    """A draw that is not plausible (points off the frame, no convergence): draw again."""


FAMILIES: dict[str, Callable] = {
    "rotation": _gen_rotation, "height-error": _gen_height_error, "resection": _gen_resection,
    "subpixel": _gen_subpixel, "stereo-radius": _gen_stereo_radius, "dmc3": _gen_dmc3, "pair": _gen_pair,
    "penta": _gen_penta, "dlt": _gen_dlt, "fe": _gen_fe,
}


# --- sheet texts -------------------------------------------------------------------------------------------
def _points_table(points, header, decimals) -> str:
    rows = [[_fmt(v, d) if d is not None else _num(v) for v, d in zip(row, decimals)] for row in points]
    return _md_table(header, rows)


def _text_rotation(x: dict) -> str:
    return (f"Angles of the image: ω = {_num(x['omega_deg'])}°, α = {_num(x['alpha_deg'])}°, "
            f"κ = {_num(x['kappa_deg'])}°.\n\nCompute the rotation matrix A = A_κ A_α A_ω by (1.3.5), check it "
            "with AᵀA and det A, and compute the angles back from its elements by (1.3.6).\n\n"
            "Names: `a11` … `a33` the elements of A (row, column); `AtA11` … `AtA33` those of AᵀA; `det`; "
            "`omega_deg`, `alpha_deg`, `kappa_deg` the angles back.")


def _text_height_error(x: dict) -> str:
    return (f"A frame camera with f = {_num(x['f_mm'])} mm and an image format of {_num(2 * x['x_max_mm'])} × "
            f"{_num(2 * x['y_max_mm'])} mm takes a horizontal image. The height of a point at the corner of the "
            f"format (x = {_num(x['x_max_mm'])} mm, y = {_num(x['y_max_mm'])} mm) is wrong by "
            f"ΔZ = {_num(x['dZ_m'])} m.\n\nBy (1.6.1), by how much is the point displaced in plan "
            "(`dX`, `dY`) and in total (`dR`)?")


def _resection_data(x: dict) -> str:
    d = _column_decimals(1, "1.8-resection", "points", (4, 5))
    table = _points_table(x["points"], ["N", "X, m", "Y, m", "Z, m", "x, mm", "y, mm"],
                          [None, None, None, None, d, d])
    return (f"{_camera_text(x)} Exterior orientation used to simulate the image: {_eo_text(x['true_eo'])} "
            f"(angles of the κ–α–ω matrix (1.3.5)).\n\nControl points and their image coordinates:\n\n{table}\n\n"
            f"Random errors with a standard deviation of {x['sigma_mm']} mm were added to the image coordinates.")


def _text_resection(x: dict) -> str:
    a = x["approx"]
    return (_resection_data(x) + f" Approximate exterior orientation: X_S = {_num(a['Xs'])} m, "
            f"Y_S = {_num(a['Ys'])} m, Z_S = {_num(a['Zs'])} m, ω = α = κ = 0°.\n\n"
            "Solve the space resection by least squares from the collinearity equations (1.8.2)–(1.8.10): the "
            "six elements of exterior orientation, their root-mean-square errors and the correlation "
            "coefficients of the unknowns.\n\nNames: `Xs`, `Ys`, `Zs`, `omega_deg`, `alpha_deg`, `kappa_deg`; "
            "`m_Xs` … `m_kappa_deg` the RMS errors; `r_A_B` the correlation of A and B "
            "(A, B among Xs, Ys, Zs, omega, alpha, kappa).")


def _text_angles(x: dict) -> str:
    a = x["approx"]
    return (_resection_data(x) + f" Approximate projection centre: X_S = {_num(a['Xs'])} m, "
            f"Y_S = {_num(a['Ys'])} m, Z_S = {_num(a['Zs'])} m.\n\n"
            "Determine the projection centre without the angles, from the equality of the angles in image and "
            "object space (§1.9), using all pairs of points; give the RMS errors (degrees of freedom m − n as "
            "in the book) and the correlations.\n\nNames: `Xs`, `Ys`, `Zs`, `m_Xs`, `m_Ys`, `m_Zs`; `r12`, "
            "`r13`, `r23` the correlations of (Xs, Ys), (Xs, Zs), (Ys, Zs).")


def _subpixel_data(x: dict) -> str:
    return (f"A pixel a_ij with i = {x['i']}, j = {x['j']} is magnified {x['n']}× on the screen; consider its "
            f"element a′ with i′ = {x['i_sub']}, j′ = {x['j_sub']} (indices from 0).")


def _text_subpixel_corner(x: dict) -> str:
    return (_subpixel_data(x) + "\n\nGive the pixel coordinates `x_p`, `y_p` of the element's centre with the "
            "origin at the corner of the image, by (1.10.2).")


def _text_subpixel_center(x: dict) -> str:
    return (_subpixel_data(x) + "\n\nGive the pixel coordinates `x_p`, `y_p` of the element's centre with the "
            "origin at the centre of the lower-left pixel, by (1.10.5).")


def _text_physical(x: dict) -> str:
    return (_subpixel_data(x) + f" The pixel size is Δ = {_num(x['pixel_size_um'])} μm.\n\nGive the physical "
            "coordinates `x_c`, `y_c` of the element's centre (origin at the image corner), by (1.10.3).")


def _text_stereo_radius(x: dict) -> str:
    return (f"The eye base of an observer is b = {_num(x['b_mm'])} mm and the stereo acuity γ = "
            f"{_num(x['gamma_min_arcsec'])}″.\n\nBy (2.1.1), what is the radius `R_m` of unaided stereo vision "
            f"in metres? Take ρ″ = {_num(x['rho_arcsec'])}″ as the book does.")


def _text_dmc3(x: dict) -> str:
    return (f"A stereo pair of a DMC III camera: f = {_num(x['f_mm'])} mm, {x['frame_px_x']} × "
            f"{x['frame_px_y']} pixels of {x['pixel_um']} μm (the {x['frame_px_x']} pixels along the flight), "
            f"flying height H = {_num(x['H_m'])} m, forward overlap {_num(x['overlap_percent'])} %. The image "
            f"coordinates are measured with an error of {x['m_xy_px']} pixel, the x-parallaxes with "
            f"{x['m_p_px']} pixel.\n\nCompute the frame length along the flight `frame_mm`, the photo base "
            "`b_mm`, the measuring errors in μm (`m_xy_um`, `m_p_um`) and, by (2.13.3), the a-priori errors "
            "of the object coordinates `m_X`, `m_Y`, `m_Z`.")


def _pair_data(x: dict, *, model=False, ro=False, ao=False, images=True) -> str:
    d = _column_decimals(2, "2.ex-ro", "points", (4, 5, 6, 7))
    parts = [f"{_camera_text(x)} Exterior orientation used to simulate the images (κ–α–ω matrix (1.3.5)):\n\n"
             f"* image 1: {_eo_text(x['true_eo1'])}\n* image 2: {_eo_text(x['true_eo2'])}\n"]
    if images:
        table = _points_table(x["points"], ["N", "X, m", "Y, m", "Z, m", "x₁, mm", "y₁, mm", "x₂, mm", "y₂, mm"],
                              [None] * 4 + [d] * 4)
        parts.append(f"Control points and their image coordinates (random errors with a standard deviation of "
                     f"{x['sigma_mm']} mm added):\n\n{table}\n")
    else:
        table = _points_table([r[:4] for r in x["points"]], ["N", "X, m", "Y, m", "Z, m"], [None] * 4)
        parts.append(f"Control points:\n\n{table}\n")
    if "ro_approx_deg" in x:
        names = ["α′₁", "κ′₁", "ω′₂", "α′₂", "κ′₂"]
        parts.append("Approximate relative orientation (independent images, (2.7.4)): "
                     + ", ".join(f"{n} = {_num(v)}°" for n, v in zip(names, x["ro_approx_deg"])) + ".\n")
    if ro:
        d_ro = printed_decimals(_book(2, "2.ex-model-points").inputs["ro_deg"])
        names = ["α′₁", "κ′₁", "ω′₂", "α′₂", "κ′₂"]
        parts.append("Relative orientation found (degrees): "
                     + ", ".join(f"{n} = {_fmt(v, d_ro)}" for n, v in zip(names, x["ro_deg"]))
                     + f". The model is built with S₁ at the origin and the base B_X = {_num(x['base_m'])} m.\n")
    if model:
        d_m = _quantity_decimals(2, "2.ex-model-points", [f"{c}M{i}" for i in range(1, 13) for c in "XYZ"])
        rows = [[n + 1, *row] for n, row in enumerate(x["model_points"])]
        parts.append("Model coordinates of the points:\n\n"
                     + _points_table(rows, ["N", "X_M, m", "Y_M, m", "Z_M, m"], [None, d_m, d_m, d_m]) + "\n")
    if ao:
        a = x["ao_approx"]
        parts.append(f"Approximate exterior orientation of the model: X₀ = {_num(a['X0'])} m, Y₀ = {_num(a['Y0'])} m, "
                     f"Z₀ = {_num(a['Z0'])} m, ω_M = {_num(a['omega_deg'])}°, α_M = {_num(a['alpha_deg'])}°, "
                     f"κ_M = {_num(a['kappa_deg'])}°, t = {_num(a['t'])}.\n")
    return "\n".join(parts)


_RO_TASK = ("Determine the relative orientation of the pair in the system of independent images "
            "α′₁, κ′₁, ω′₂, α′₂, κ′₂ (2.7.4) by least squares with the coplanarity condition (2.8.1)")


def _text_ro(x):
    return (_pair_data(x) + f"\n{_RO_TASK}: the elements in degrees and their RMS errors.\n\n"
            "Names: `alpha1_deg`, `kappa1_deg`, `omega2_deg`, `alpha2_deg`, `kappa2_deg`; `m_…` their RMS errors.")


def _text_ro_corr(x):
    return (_pair_data(x) + f"\n{_RO_TASK}, and give the correlation coefficients of the elements.\n\n"
            "Names: `r_A_B` the correlation of A and B (among alpha1, kappa1, omega2, alpha2, kappa2).")


def _text_q(x):
    return (_pair_data(x) + f"\n{_RO_TASK}, and give the residual y-parallaxes (2.8.2) of the twelve points "
            "in mm.\n\nNames: `q1` … `q12`.")


def _text_model_points(x):
    return (_pair_data(x, ro=True) + "\nBuild the model by forward intersection (§2.9), N from the second formula "
            "of (2.4.12).\n\nNames: `XM1`, `YM1`, `ZM1` … `ZM12` (metres).")


_AO_TASK = ("Determine the exterior orientation of the model by least squares from (2.11.1)/(2.11.2), all twelve "
            "points as full control, A_M by (1.3.2)")


def _text_model_eo(x):
    return (_pair_data(x, model=True, ao=True, images=False) + f"\n{_AO_TASK}: the seven elements and their "
            "RMS errors.\n\nNames: `X0`, `Y0`, `Z0`, `omegaM_deg`, `alphaM_deg`, `kappaM_deg`, `t`; `m_…` their "
            "RMS errors.")


def _text_model_eo_corr(x):
    return (_pair_data(x, model=True, ao=True, images=False) + f"\n{_AO_TASK}, and give the correlation "
            "coefficients of the elements.\n\nNames: `r_A_B` (A, B among X0, Y0, Z0, omegaM, alphaM, kappaM, t).")


def _text_control(x):
    return (_pair_data(x, model=True, ao=True, images=False) + f"\n{_AO_TASK}. Check the accuracy at the "
            "control points: their transformed model coordinates, the differences computed − given and the "
            "RMS of the differences (divide by n, as the book).\n\nNames: `X1`, `Y1`, `Z1` … the transformed "
            "points; `dX1`, `dY1`, `dZ1` … the differences; `m_dX`, `m_dY`, `m_dZ` their RMS.")


def _text_image_eo(x):
    return (_pair_data(x, model=True, ro=True, ao=True, images=False) + f"\n{_AO_TASK}; then compute the "
            "exterior orientation of both images by (2.12.1)/(2.12.2), the angles by (1.3.6).\n\nNames: `Xs1`, "
            "`Ys1`, `Zs1`, `omega1_deg`, `alpha1_deg`, `kappa1_deg` and the same with 2.")


def _dlt_data(x):
    d = _column_decimals(4, "4.3-dlt", "points", (4, 5, 6, 7))
    table = _points_table(x["points"], ["N", "X, m", "Y, m", "Z, m", "x₁, mm", "y₁, mm", "x₂, mm", "y₂, mm"],
                          [None] * 4 + [d] * 4)
    return (f"{_camera_text(x)} Exterior orientation used to simulate the images (κ–α–ω matrix (1.3.5)):\n\n"
            f"* image 1: {_eo_text(x['true_eo1'])}\n* image 2: {_eo_text(x['true_eo2'])}\n\n"
            f"Control points and their image coordinates (random errors with a standard deviation of "
            f"{x['sigma_mm']} mm added):\n\n{table}\n\nBy the direct linear transformation, compute the "
            "coefficients L₁ … L₁₁ of each image by (4.2.1)–(4.2.3) from the ten control points")


def _text_dlt(x):
    return (_dlt_data(x) + ".\n\nNames: `L1_img1` … `L11_img1`, `L1_img2` …; L₉ and L₁₀ multiplied by 10⁵ as "
            "the book prints them (`L9e5_img1`, `L10e5_img1`).")


def _text_dlt_corr(x):
    return (_dlt_data(x) + ", and the correlation coefficients of L₁ … L₁₁ of image 2 (1.8.10).\n\n"
            "Names: `r_L1_L2` … `r_L10_L11`.")


def _text_dlt_points(x):
    return (_dlt_data(x) + "; then the object coordinates of the ten points by the DLT forward intersection "
            "(4.3.1).\n\nNames: `X1`, `Y1`, `Z1` … `Z10`.")


def _text_dlt_interior(x):
    return (_dlt_data(x) + "; then the interior orientation of each image by (4.2.4).\n\nNames: `x0_img1`, "
            "`y0_img1`, `fx_img1`, `fy_img1` and the same for `img2`.")


def _text_dlt_exterior(x):
    return (_dlt_data(x) + "; then the projection centres by (4.2.5) and the angles from the matrix (4.2.6) by "
            "(1.3.6).\n\nNames: `Xs_img1`, `Ys_img1`, `Zs_img1`, `omega_deg_img1`, `alpha_deg_img1`, "
            "`kappa_deg_img1` and the same for `img2`.")


def _text_dlt_rotation(x):
    return (_dlt_data(x) + "; then the rotation matrix of each image by (4.2.6).\n\nNames: `a11_img1` … "
            "`a33_img1`, `a11_img2` … `a33_img2`.")


def _fe_data(x):
    d = _column_decimals(4, "4.4-F", "points", (1, 2, 3, 4))
    rows = [[r[0], r[1], r[2], 1, r[3], r[4], 1] for r in x["points"]]
    table = _points_table(rows, ["N", "x₁, mm", "y₁, mm", "z₁", "x₂, mm", "y₂, mm", "z₂"],
                          [None, d, d, None, d, d, None])
    return (f"{_camera_text(x)} Exterior orientation used to simulate the images (κ–α–ω matrix (1.3.5)):\n\n"
            f"* image 1: {_eo_text(x['true_eo1'])}\n* image 2: {_eo_text(x['true_eo2'])}\n\n"
            "Homogeneous image coordinates of the stereo pair (random errors with a standard deviation of "
            f"{x['sigma_mm']} mm added):\n\n{table}\n\n")


_F_TASK = (f"Compute the fundamental matrix from the first 8 points by the singular value decomposition of the "
           "coefficients of (4.4.14), f₃₃ = 1, no rank constraint, in the layout x₂ᵀ F x₁ = 0 of the book's table")
_E_TASK = ("Compute the essential matrix from the first 8 points in the same way, from the normalised "
           "coordinates (4.4.15), e₃₃ = 1, in the layout x₂ᵀ E x₁ = 0")


def _text_F(x):
    return _fe_data(x) + f"{_F_TASK}.\n\nNames: `F11` … `F33`."


def _text_F_res(x):
    return _fe_data(x) + f"{_F_TASK}, and the residuals x₂ᵀ F x₁ of all twelve points.\n\nNames: `vF_1` … `vF_12`."


def _text_normalized(x):
    return (_fe_data(x) + "Compute the normalised image coordinates (4.4.15) of all points.\n\nNames: `x1n_1`, "
            "`y1n_1`, `x2n_1`, `y2n_1` … (point number last).")


def _text_E(x):
    return _fe_data(x) + f"{_E_TASK}.\n\nNames: `E11` … `E33`."


def _text_E_res(x):
    return _fe_data(x) + f"{_E_TASK}, and the residuals of all twelve points.\n\nNames: `vE_1` … `vE_12`."


def _text_penta(x):
    return (f"A multi-camera rig of {x['n_cameras']} cameras takes {x['n_exposures']} exposures (so "
            f"{x['n_cameras'] * x['n_exposures']} images); point coordinates are not counted.\n\nHow many unknowns "
            "has the bundle adjustment with free exterior orientation of every image, (3.8.1) (`N1`), and with "
            "the exterior orientation of the exposures plus the mounting elements of the rig, (3.8.2) (`N2`)?")


# --- the registry ---------------------------------------------------------------------------------------------
@dataclass(frozen=True)
class Generator:
    """How one worked example becomes an assignment.

    ``family`` draws the data (shared by the examples of one data set, so the same seed gives the
    same data for all of them); ``keys`` are the input keys the sheet shows and the key is
    computed from, optionally renamed (``(shown, from)``); ``text`` writes the statement;
    ``rounded`` lists the computed inputs printed rounded, ``(key, columns)`` (``columns`` None:
    every element; their decimals are read from the values); ``compute`` replaces the example's adapter (a wrapper,
    see :func:`_dmc3_compute`); ``decimals`` overrides the book's decimals of single quantities
    whose printing is irregular (one cell of a table printed with one decimal more or less than
    its column, e.g. dX₆ = 0,0248 of §2.12, a₁₃ = 0,09 of §4.3; r₁₂ of §1.9 printed to 6 decimals
    only because it was −0,000003 — the other correlations have 4); ``alternatives`` maps a
    quantity to the adapter output that repeats the book's chain with rounded intermediates;
    ``exclude`` lists quantities not asked.
    """

    example_id: str
    chapter: int
    family: str
    keys: tuple
    text: Callable
    title: str
    rounded: tuple = ()
    compute: Callable | None = None
    decimals: dict = field(default_factory=dict)
    alternatives: dict = field(default_factory=dict)
    exclude: tuple = ()


_RES_KEYS = ("f_mm", "x0_mm", "y0_mm", "order", "sigma_mm", "true_eo", "points")
_PAIR = ("f_mm", "x0_mm", "y0_mm", "sigma_mm", "true_eo1", "true_eo2", "points")
_XY8 = ("points", (4, 5, 6, 7))


def _registry() -> dict:
    ro = _PAIR + ("ro_approx_deg",)
    ao = _PAIR + ("model_points", "ao_approx")
    gens = [
        Generator("1.3-rotation-matrix", 1, "rotation", ("omega_deg", "alpha_deg", "kappa_deg", "order"),
                  _text_rotation, "Rotation matrix (1.3.5) and the angles back (1.3.6)"),
        Generator("1.6-height-error", 1, "height-error", ("f_mm", "x_max_mm", "y_max_mm", "dZ_m"),
                  _text_height_error, "Planimetric displacement caused by a height error (1.6.1)"),
        Generator("1.8-resection", 1, "resection", _RES_KEYS + ("approx",), _text_resection,
                  "Space resection from five control points (1.8.2)–(1.8.10)", rounded=(("points", (4, 5)),)),
        Generator("1.9-resection-by-angles", 1, "resection", _RES_KEYS + (("approx", "approx_centre"),),
                  _text_angles, "Projection centre from the equality of angles (§1.9)",
                  rounded=(("points", (4, 5)),), decimals={"r12": 4}),
        Generator("1.10-subpixel-corner", 1, "subpixel", ("i", "j", "i_sub", "j_sub", "n"), _text_subpixel_corner,
                  "Pixel coordinates of a magnified pixel's element, origin at the corner (1.10.2)"),
        Generator("1.10-physical", 1, "subpixel", ("i", "j", "i_sub", "j_sub", "n", "pixel_size_um"), _text_physical,
                  "Physical coordinates of the element (1.10.3)"),
        Generator("1.10-subpixel-center", 1, "subpixel", ("i", "j", "i_sub", "j_sub", "n"), _text_subpixel_center,
                  "Pixel coordinates of the element, origin at the centre of the lower-left pixel (1.10.5)"),
        Generator("2.1-stereo-radius", 2, "stereo-radius", ("b_mm", "gamma_min_arcsec", "rho_arcsec"),
                  _text_stereo_radius, "Radius of unaided stereo vision (2.1.1)"),
        Generator("2.13-dmc3-accuracy", 2, "dmc3",
                  ("H_m", "overlap_percent", "f_mm", "frame_px_x", "frame_px_y", "pixel_um", "m_xy_px", "m_p_px"),
                  _text_dmc3, "A-priori accuracy of a DMC III stereo pair (2.13.3)", compute=_dmc3_compute,
                  alternatives={"m_X": "m_X_printed_chain", "m_Y": "m_X_printed_chain", "m_Z": "m_Z_printed_chain"},
                  exclude=("m_X_printed_chain", "m_Z_printed_chain")),
        Generator("2.ex-ro", 2, "pair", ro, _text_ro, "Relative orientation of a pair (2.7.4), (2.8.1)",
                  rounded=(_XY8,)),
        Generator("2.ex-ro-correlation", 2, "pair", ro, _text_ro_corr,
                  "Correlations of the relative orientation elements", rounded=(_XY8,)),
        Generator("2.ex-q", 2, "pair", ro, _text_q, "Residual y-parallaxes after relative orientation (2.8.2)",
                  rounded=(_XY8,)),
        Generator("2.ex-model-points", 2, "pair", _PAIR + ("ro_deg", "base_m"), _text_model_points,
                  "Model coordinates by forward intersection (§2.9)", rounded=(_XY8, ("ro_deg", None))),
        Generator("2.ex-model-eo", 2, "pair", ao, _text_model_eo,
                  "Exterior orientation of the model (2.11.1), (2.11.2)", rounded=(("model_points", (0, 1, 2)),)),
        Generator("2.ex-model-eo-correlation", 2, "pair", ao, _text_model_eo_corr,
                  "Correlations of the model's exterior orientation elements",
                  rounded=(("model_points", (0, 1, 2)),)),
        Generator("2.ex-control", 2, "pair", ao, _text_control, "Accuracy check at the control points",
                  rounded=(("model_points", (0, 1, 2)),), decimals={"dX6": 3}),
        Generator("2.ex-image-eo", 2, "pair", ao + ("ro_deg", "base_m"), _text_image_eo,
                  "Exterior orientation of the two images (2.12.1), (2.12.2)",
                  rounded=(("model_points", (0, 1, 2)), ("ro_deg", None))),
        Generator("3.8-penta-unknowns", 3, "penta", ("n_exposures", "n_cameras", "n_points"), _text_penta,
                  "Unknowns of a multi-camera block (3.8.1), (3.8.2)"),
        Generator("4.3-dlt", 4, "dlt", _PAIR, _text_dlt, "DLT coefficients of two images (4.2.1)–(4.2.3)",
                  rounded=(_XY8,)),
        Generator("4.3-correlation", 4, "dlt", _PAIR, _text_dlt_corr, "Correlations of the DLT coefficients",
                  rounded=(_XY8,)),
        Generator("4.3-points", 4, "dlt", _PAIR, _text_dlt_points, "Object points by DLT intersection (4.3.1)",
                  rounded=(_XY8,)),
        Generator("4.3-interior", 4, "dlt", _PAIR, _text_dlt_interior, "Interior orientation from the DLT (4.2.4)",
                  rounded=(_XY8,)),
        Generator("4.3-exterior", 4, "dlt", _PAIR, _text_dlt_exterior,
                  "Exterior orientation from the DLT (4.2.5), (4.2.6)", rounded=(_XY8,)),
        Generator("4.3-rotation", 4, "dlt", _PAIR, _text_dlt_rotation, "Rotation matrices from the DLT (4.2.6)",
                  rounded=(_XY8,), decimals={"a13_img1": 3, "a22_img2": 3}),
    ]
    fe = _PAIR[:4] + ("n_solve",) + _PAIR[4:]
    xy5 = ("points", (1, 2, 3, 4))
    for eid, text, title in (("4.4-F", _text_F, "Fundamental matrix from eight points (4.4.14)"),
                             ("4.4-F-residuals", _text_F_res, "Epipolar residuals of the fundamental matrix"),
                             ("4.4-normalized", _text_normalized, "Normalised image coordinates (4.4.15)"),
                             ("4.4-E", _text_E, "Essential matrix from eight points"),
                             ("4.4-E-residuals", _text_E_res, "Epipolar residuals of the essential matrix")):
        gens.append(Generator(eid, 4, "fe", fe, text, title, rounded=(xy5,)))
    return {g.example_id: g for g in gens}


GENERATORS: dict = _registry()
"""Example id → :class:`Generator`: the worked examples of Chapters 1–4 that have assignments."""


def available() -> list:
    """The example ids that have an assignment generator, in book order.

    Returns
    -------
    list of str

    Raises
    ------
    None

    References
    ----------
    Chapters 1–4 of the book; the examples as recorded in ``textbook/ch01.toml`` … ``ch04.toml``.

    Examples
    --------
    >>> "1.8-resection" in available() and "4.3-dlt" in available()
    True
    """
    return list(GENERATORS)


def _generator(example_id: str) -> Generator:
    if not isinstance(example_id, str):
        raise AssignmentError(f"an example id is a text such as '1.8-resection', got {example_id!r}")
    if example_id in GENERATORS:
        return GENERATORS[example_id]
    known = [e.id for chapter in available_chapters() for e in load_chapter(chapter).examples]
    if example_id in known:
        raise AssignmentError(f"example {example_id!r} has no assignment generator yet; these have one: "
                              f"{', '.join(available())}")
    near = [g for g in GENERATORS if example_id.lower() in g.lower()]
    hint = f" (similar: {', '.join(near[:5])})" if near else ""
    raise AssignmentError(f"no worked example {example_id!r}{hint}; assignments exist for: {', '.join(available())}")


def _seed(seed) -> int:
    if isinstance(seed, bool) or not isinstance(seed, (int, np.integer)) or seed < 0:
        raise AssignmentError(f"the seed must be a non-negative integer, got {seed!r}")
    return int(seed)


# --- data of one (family, seed) ------------------------------------------------------------------------------
@lru_cache(maxsize=128)
def _family_data_json(family: str, seed: int) -> str:
    """The family's data set for ``seed`` as JSON (cached; every member checked to compute)."""
    rng = np.random.default_rng([zlib.crc32(family.encode()), seed])
    members = [g for g in GENERATORS.values() if g.family == family]
    last = None
    for _ in range(MAX_ATTEMPTS):
        try:
            data = FAMILIES[family](rng)
            for g in members:
                values = _compute(g)(_member_inputs(g, data))
                for a in _asked(g):
                    v = values[a.name]
                    if isinstance(v, float) and not math.isfinite(v):
                        raise _Redraw(f"{a.name} is not finite")
                    if isinstance(v, float) and a.decimals is not None and _at_tie(v, a.decimals):
                        raise _Redraw(f"{a.name} = {v!r} is half-way between two printed values")
            for g in members:
                if g.rounded and _worst_ratio(g, _member_inputs(g, data)) > _ratio_limit(g.example_id):
                    raise _Redraw(f"{g.example_id}: the data are much more sensitive to rounding than the book's")
            return json.dumps(data)
        except (_Redraw, PhotolibError, ArithmeticError, np.linalg.LinAlgError) as err:
            last = err
    raise AssignmentError(f"no plausible data for {family!r} with seed {seed} in {MAX_ATTEMPTS} draws ({last})")


def _at_tie(value: float, decimals: int) -> bool:
    """True if ``value`` lies half-way between two numbers printed with ``decimals`` (ambiguous rounding)."""
    scaled = abs(value) * 10.0 ** decimals
    return abs(scaled - math.floor(scaled) - 0.5) < 1e-6


def _member_inputs(g: Generator, data: dict) -> dict:
    out = {}
    for key in g.keys:
        shown, source = (key, key) if isinstance(key, str) else key
        out[shown] = copy.deepcopy(data[source])
    return out


def _compute(g: Generator) -> Callable:
    if g.compute is not None:
        return g.compute
    example = _book(g.chapter, g.example_id)
    return resolve(example.compute)


def _asked_quantities(g: Generator) -> list:
    example = _book(g.chapter, g.example_id)
    return [q for q in example.quantities if q.status in ASKED_STATUSES and q.name not in g.exclude]


def _inputs(g: Generator, seed: int) -> dict:
    return _member_inputs(g, json.loads(_family_data_json(g.family, seed)))


def _kind(q) -> str:
    return "text" if isinstance(q.value, str) else "number"


def _asked(g: Generator) -> tuple:
    return tuple(Asked(q.name, q.unit, g.decimals.get(q.name, q.decimals), _kind(q)) for q in _asked_quantities(g))


# --- sheets ---------------------------------------------------------------------------------------------------
def _asked_markdown(asked) -> str:
    groups = []
    for a in asked:
        label = ("text" if a.kind == "text" else "integer" if a.kind == "integer" else
                 f"{a.decimals} decimal{'s' if a.decimals > 1 else ''}" if a.decimals and a.decimals > 0 else
                 "whole units" if a.decimals == 0 else f"to 10^{-a.decimals}")
        head = (label, a.unit or "—")
        if groups and groups[-1][0] == head:
            groups[-1][1].append(a.name)
        else:
            groups.append((head, [a.name]))
    rows = [[give, unit, ", ".join(f"`{n}`" for n in names)] for (give, unit), names in groups]
    return _md_table(["give to", "unit", "quantities"], rows, ":---")


def make_sheet(example_id: str, seed: int) -> Sheet:
    """The student sheet of worked example ``example_id`` with the data of ``seed``.

    Parameters
    ----------
    example_id : str
        A worked example with a generator (:func:`available`), e.g. ``"1.8-resection"``.
    seed : int
        Non-negative; the same (id, seed) always gives the same sheet.

    Returns
    -------
    Sheet
        Inputs in the textbook's format, the asked quantities and the Markdown statement.

    Raises
    ------
    AssignmentError
        An unknown example, an example without a generator (the message lists those with one),
        a bad seed.

    References
    ----------
    The worked examples of Chapters 1–4 (§1.3, §1.6, §1.8–§1.10, §2.1, §2.12, §2.13, §3.8, §4.3, §4.4).

    Examples
    --------
    >>> sheet = make_sheet("1.3-rotation-matrix", 1)
    >>> [a.name for a in sheet.asked][:3]
    ['a11', 'a12', 'a13']
    >>> sheet.inputs == make_sheet("1.3-rotation-matrix", 1).inputs
    True
    """
    g = _generator(example_id)
    seed = _seed(seed)
    inputs = _inputs(g, seed)
    asked = _asked(g)
    example = _book(g.chapter, g.example_id)
    body = g.text(inputs)
    markdown = (f"# Assignment {g.example_id} (seed {seed})\n\n**{g.title}** — after the worked example of "
                f"§{example.section}, with new data.\n\n## Given\n\n{body}\n\n## Find\n\n"
                f"Give each quantity in `answers.toml` under its name (`name = value`, decimal point), to the "
                f"decimals the book prints:\n\n{_asked_markdown(asked)}\n\nGrade your answers with "
                f"`photolib check {g.example_id} --seed {seed} answers.toml`.\n")
    return Sheet(g.example_id, seed, g.chapter, example.section, g.title, inputs, asked, markdown)


# --- keys ------------------------------------------------------------------------------------------------------
def _slots(inputs: dict, g: "Generator") -> list:
    """(key, row, column, half unit) of every rounded scalar input (column None where not a table).

    The half unit is that of the decimals the book prints in the same input of the same example.
    """
    out = []
    for key, columns in g.rounded:
        value = inputs.get(key)
        if value is None:
            continue
        half = 0.5 * 10.0 ** (-_rounded_decimals(g.example_id, key, columns))
        if value and isinstance(value[0], list):
            out += [(key, r, c, half) for r in range(len(value)) for c in columns]
        else:
            out += [(key, r, None, half) for r in range(len(value))]
    return out


@lru_cache(maxsize=None)
def _rounded_decimals(example_id: str, key: str, columns) -> int:
    g = GENERATORS[example_id]
    arr = np.asarray(_book(g.chapter, example_id).inputs[key], dtype=float)
    return printed_decimals(arr[:, list(columns)] if columns is not None else arr)


def _perturbed(inputs: dict, slot) -> dict:
    key, r, c, half = slot
    out = copy.deepcopy(inputs)
    if c is None:
        out[key][r] = out[key][r] + half
    else:
        out[key][r][c] = out[key][r][c] + half
    return out


def _twin(g: Generator) -> Generator:
    """The first member of ``g``'s family with the same adapter, inputs and rounded fields (shares σ)."""
    return next(o for o in GENERATORS.values() if o.family == g.family and o.keys == g.keys
                and o.rounded == g.rounded and _compute(o) is _compute(g))


@lru_cache(maxsize=256)
def _sensitivity_of(example_id: str, inputs_json: str) -> dict:
    """σ of every float quantity of the adapter from the rounding of the computed inputs (first order).

    Each rounded input is moved by its half unit h in turn; with the change Δᵢ of a quantity,
    σ² = Σ Δᵢ²/3 (a uniform error on ± h has variance h²/3). Checked against a Monte Carlo of the
    re-rounding in ``tests/book/test_assignments.py``.
    """
    g = GENERATORS[example_id]
    inputs = json.loads(inputs_json)
    compute = _compute(g)
    base = compute(copy.deepcopy(inputs))
    names = [k for k, v in base.items() if isinstance(v, float)]
    total = dict.fromkeys(names, 0.0)
    for slot in _slots(inputs, g):
        moved = compute(_perturbed(inputs, slot))
        for k in names:
            total[k] += (moved[k] - base[k]) ** 2 / 3.0
    return {k: math.sqrt(v) for k, v in total.items()}


def _sigma(g: Generator, inputs: dict) -> dict:
    return _sensitivity_of(_twin(g).example_id, json.dumps(inputs, sort_keys=True))


def _sensitivity(example_id: str, seed: int) -> dict:
    """σ of every float quantity of the example's key for ``seed`` (see :func:`_sensitivity_of`)."""
    g = GENERATORS[example_id]
    return _sigma(g, _inputs(g, seed))


def _worst_ratio(g: Generator, inputs: dict) -> float:
    """The largest 3σ / half a printed unit over the asked numbers (how much the rounding matters)."""
    sigma = _sigma(g, inputs)
    return max((3.0 * sigma[a.name] / (0.5 * 10.0 ** -a.decimals) for a in _asked(g)
                if a.name in sigma and a.decimals is not None), default=0.0)


@lru_cache(maxsize=None)
def _ratio_limit(example_id: str) -> float:
    """A draw is plausible if its rounding matters at most ``CONDITION_FACTOR`` times as much as in the
    book's own example (in units of the printed decimals), and never less than ``CONDITION_FLOOR``."""
    g = GENERATORS[example_id]
    book = _book(g.chapter, example_id).inputs
    return max(CONDITION_FACTOR * _worst_ratio(g, book), CONDITION_FLOOR)


def _tolerance(g: Generator, name: str, value, decimals, kind, sigma: dict, values: dict):
    if kind == "text":
        return None, "text: equal (case and spaces ignored)"
    if kind == "integer":
        return 0.0, "integer: exact"
    half = 0.5 * 10.0 ** (-(decimals or 0))
    tol, method = half, f"half a unit of the printed decimal ({_fmt(half, None)})"
    s = sigma.get(name, 0.0)
    if 3.0 * s > half:
        tol = round(rounding_bound(s, decimals), decimals + 2)
        method = (f"input rounding: the sheet's computed inputs stand for ± half a unit of their last decimal; "
                  f"first-order propagation gives sigma = {s:.2g}, bound = 3 sigma + half a unit")
    alt = g.alternatives.get(name)
    if alt is not None:
        gap = abs(values[alt] - value)
        grid = 10.0 ** (-(decimals + 2))
        bound = round(math.ceil((gap + half) / grid - 1e-9) * grid, decimals + 2)
        if bound > tol:
            tol = bound
            method = (f"the book's chain with its rounded intermediates ({alt}) differs by {gap:.2g}: "
                      f"bound = that difference + half a unit")
    return tol, method


@lru_cache(maxsize=128)
def _key_cached(example_id: str, seed: int) -> AnswerKey:
    g = GENERATORS[example_id]
    inputs = _inputs(g, seed)
    values = _compute(g)(inputs)
    sigma = _sensitivity(example_id, seed) if g.rounded else {}
    example = _book(g.chapter, g.example_id)
    entries = []
    for a in _asked(g):
        value = values[a.name]
        value = value.item() if hasattr(value, "item") else value
        kind = a.kind
        if kind == "number" and isinstance(value, int) and not isinstance(value, bool):
            kind = "integer"                      # a count: the adapter returns an int
        elif kind == "number":
            value = float(value)
        tol, method = _tolerance(g, a.name, value, a.decimals, kind, sigma, values)
        half = None if kind == "text" else 0.0 if kind == "integer" else 0.5 * 10.0 ** (-(a.decimals or 0))
        entries.append(KeyEntry(a.name, value, _fmt(value, a.decimals), a.unit, a.decimals, tol, method, kind,
                                half))
    digest = hashlib.sha256(json.dumps(inputs, sort_keys=True).encode()).hexdigest()
    return AnswerKey(g.example_id, seed, g.chapter, example.section, g.title, tuple(entries), digest)


def answer_key(example_id: str, seed: int) -> AnswerKey:
    """The answer key of (``example_id``, ``seed``): the example's adapter on the sheet's inputs.

    Deterministic: regenerated from the id and the seed, so grading needs no key file.

    Parameters
    ----------
    example_id : str
        A worked example with a generator (:func:`available`).
    seed : int
        Non-negative.

    Returns
    -------
    AnswerKey
        One :class:`KeyEntry` per asked quantity: value, as printed, unit, tolerance and its method.

    Raises
    ------
    AssignmentError
        As :func:`make_sheet`.

    References
    ----------
    ``textbook/README.md`` (decimals, input-rounding bounds); the examples' adapters in
    ``photolib/book/ch01*.py`` … ``ch04*.py``.

    Examples
    --------
    >>> key = answer_key("1.6-height-error", 3)
    >>> [e.name for e in key.entries], key.entry("dR").tolerance
    (['dX', 'dY', 'dR'], 0.05)
    """
    g = _generator(example_id)
    return _key_cached(g.example_id, _seed(seed))


def write_assignment(example_id: str, seed: int, out_dir=".") -> AssignmentFiles:
    """Write ``ID-seedN.md``, ``ID-seedN.ipynb`` (the sheet) and ``ID-seedN-key.toml`` into ``out_dir``.

    Parameters
    ----------
    example_id : str
    seed : int
    out_dir : str or Path
        Created if missing.

    Returns
    -------
    AssignmentFiles
        The three paths.

    Raises
    ------
    AssignmentError
        As :func:`make_sheet`; ``out_dir`` is a file.

    References
    ----------
    Issue 13, item 4 (assignments with answer keys).

    Examples
    --------
    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     files = write_assignment("1.10-physical", 2, tmp)
    ...     files.markdown.name, files.key.name
    ('1.10-physical-seed2.md', '1.10-physical-seed2-key.toml')
    """
    sheet = make_sheet(example_id, seed)
    key = answer_key(example_id, seed)
    out = Path(out_dir)
    if out.exists() and not out.is_dir():
        raise AssignmentError(f"--out {out} is a file, not a folder")
    out.mkdir(parents=True, exist_ok=True)
    stem = f"{sheet.example_id}-seed{sheet.seed}"
    files = AssignmentFiles(out / f"{stem}.md", out / f"{stem}.ipynb", out / f"{stem}-key.toml")
    files.markdown.write_text(sheet.markdown, encoding="utf-8")
    files.notebook.write_text(json.dumps(sheet.notebook(), ensure_ascii=False, indent=1) + "\n", encoding="utf-8")
    files.key.write_text(key.to_toml(), encoding="utf-8")
    return files


# --- grading -----------------------------------------------------------------------------------------------------
def read_answers(path) -> dict:
    """Read a student's ``answers.toml``: a flat table ``name = value``.

    Parameters
    ----------
    path : str or Path

    Returns
    -------
    dict
        Quantity name → answer.

    Raises
    ------
    AssignmentError
        The file is missing, not TOML, or holds tables instead of ``name = value`` lines.

    References
    ----------
    Issue 13, item 4; TOML as read by :mod:`tomllib`.

    Examples
    --------
    >>> import tempfile, pathlib
    >>> with tempfile.TemporaryDirectory() as tmp:
    ...     p = pathlib.Path(tmp, "answers.toml")
    ...     _ = p.write_text('dX = 4\\n"dR" = 5.1\\n')
    ...     read_answers(p)
    {'dX': 4, 'dR': 5.1}
    """
    path = Path(path)
    if not path.is_file():
        raise AssignmentError(f"answers file {str(path)!r} not found")
    try:
        data = tomllib.loads(path.read_text(encoding="utf-8"))
    except (tomllib.TOMLDecodeError, UnicodeDecodeError) as err:
        raise AssignmentError(f"answers file {path.name} is not valid TOML: {err}") from None
    nested = [k for k, v in data.items() if isinstance(v, (dict, list))]
    if nested:
        raise AssignmentError(f"answers file {path.name}: expected 'name = value' lines, but {', '.join(nested)} "
                              "is a table or array")
    return data


def _number(value, name):
    if isinstance(value, bool):
        raise AssignmentError(f"answer {name!r}: expected a number, got {value!r}")
    if isinstance(value, (int, float)):
        return float(value)
    if isinstance(value, str):
        try:
            return float(value.strip().replace(",", ".").replace("−", "-").replace(" ", ""))
        except ValueError:
            pass
    raise AssignmentError(f"answer {name!r}: expected a number, got {value!r}")


def grade(example_id: str, seed: int, answers: dict, strict: bool = False) -> Grade:
    """Grade ``answers`` (quantity name → value) against the regenerated key of (``example_id``, ``seed``).

    A number is correct when |answer − value| ≤ tolerance (with the float slack of
    ``photolib verify``); a text when equal ignoring case and spaces; a quantity not in
    ``answers`` is missing.

    Parameters
    ----------
    example_id : str
    seed : int
    answers : dict
        As :func:`read_answers` returns; numbers may also be texts with a decimal comma.
    strict : bool
        Grade every number to half a unit of its printed decimal (the sheet's numbers taken as
        exact), ignoring the wider input-rounding bounds of the key.

    Returns
    -------
    Grade
        Per-quantity verdicts and the total.

    Raises
    ------
    AssignmentError
        As :func:`make_sheet`; ``answers`` not a dict, a name that the sheet does not ask (the
        message lists the names), or a value that is not a number.

    References
    ----------
    Issue 13, item 4; tolerances as in :func:`answer_key`.

    Examples
    --------
    >>> key = answer_key("1.6-height-error", 3)
    >>> right = {e.name: e.value for e in key.entries}
    >>> grade("1.6-height-error", 3, right).ok
    True
    >>> g = grade("1.6-height-error", 3, {"dX": right["dX"] + 1.0})
    >>> [v.status for v in g.verdicts]
    ['wrong', 'missing', 'missing']
    """
    key = answer_key(example_id, seed)
    if not isinstance(answers, dict):
        raise AssignmentError(f"answers must be a table of name = value, got {type(answers).__name__}")
    unknown = [n for n in answers if n not in key.names]
    if unknown:
        raise AssignmentError(f"answers name quantities that {key.example_id} does not ask: "
                              f"{', '.join(map(str, unknown))} (asked: {', '.join(key.names)})")
    verdicts = []
    for e in key.entries:
        if e.name not in answers:
            verdicts.append(Verdict(e.name, "missing", None, e.value, e.printed,
                                    e.half_unit if strict else e.tolerance, e.unit))
            continue
        given = answers[e.name]
        if e.kind == "text":
            ok = " ".join(str(given).split()).lower() == " ".join(str(e.value).split()).lower()
        else:
            number = _number(given, e.name)
            tol = e.half_unit if strict else e.tolerance
            ok = math.isfinite(number) and abs(number - e.value) <= tol * (1 + 1e-9) + 1e-12
        verdicts.append(Verdict(e.name, "correct" if ok else "wrong", given, e.value, e.printed,
                                e.half_unit if strict else e.tolerance, e.unit))
    return Grade(key.example_id, key.seed, tuple(verdicts))


def answers_toml(answers: dict) -> str:
    """``answers`` as the text of an ``answers.toml`` (one ``"name" = value`` line each).

    Parameters
    ----------
    answers : dict
        Quantity name → number or text; None values are left out.

    Returns
    -------
    str

    Raises
    ------
    AssignmentError
        A value that is neither a number nor a text.

    References
    ----------
    Issue 13, item 4.

    Examples
    --------
    >>> print(answers_toml({"dX": 4, "dR": 5.1, "dY": None}), end="")
    "dX" = 4
    "dR" = 5.1
    """
    lines = []
    for name, value in answers.items():
        if value is None:
            continue
        if hasattr(value, "item"):
            value = value.item()
        if isinstance(value, bool) or not isinstance(value, (int, float, str)):
            raise AssignmentError(f"answer {name!r}: a number or a text, got {value!r}")
        lines.append(f"{json.dumps(str(name), ensure_ascii=False)} = {_toml(value)}")
    return "\n".join(lines) + ("\n" if lines else "")
