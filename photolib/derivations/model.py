"""The compile/codegen core of the derivations: a model in sympy, its Jacobian, numpy code.

Each photogrammetric problem of the book (Chapters 1–4, the GNSS-centres paper) is written once
as sympy expressions of its unknowns (*parameters*) and known quantities (*data*); the rows of the
coefficient matrix B of the correction equations (1.8.5) are their derivatives by the parameters.
:meth:`Model.compile` turns residuals and Jacobian into vectorised numpy functions. The numpy code
of every model the library uses is printed once from sympy into the committed module
``photolib/derivations/_generated.py`` (regenerate with ``python -m photolib.derivations._codegen``;
``tests/library/test_derivations_generated.py`` checks that it is up to date), so that a run needs
no symbolic differentiation: a model whose sympy form (hashed) is in that module uses the printed
code, any other model is lambdified on first use.
"""

from __future__ import annotations

import hashlib
from dataclasses import dataclass
from functools import lru_cache

import numpy as np
import sympy as sp

from ..errors import InputError

__all__ = ["Model", "numpy_source", "compile_fused"]


def _broadcasting(fn, count):
    """Wrap a lambdified function so every output is an array of the common broadcast shape."""
    def wrapped(*args):
        out = fn(*args)
        return np.stack(np.broadcast_arrays(*[np.asarray(o, dtype=float) for o in out]))
    wrapped.count = count
    return wrapped


@dataclass(frozen=True)
class Model:
    """Residual functions of a least-squares problem, written in sympy.

    ``residuals`` are the functions whose values at the approximation are the free terms L of
    the correction equations (1.8.5); the rows of B are their derivatives by ``parameters``.

    Parameters
    ----------
    name : str
        A name for messages and generated code, e.g. ``"collinearity-kaw"``.
    parameters : tuple of sympy.Symbol
        The unknowns, in the order of the columns of B.
    data : tuple of sympy.Symbol
        The known quantities (one value or an array per observation when compiled).
    residuals : tuple of sympy.Expr
        The functions F whose values are the free terms.

    Raises
    ------
    InputError
        If a parameter or datum is not a sympy symbol, a residual is not a sympy expression, or
        there are no parameters or residuals.

    References
    ----------
    Chibunichev (2022), §1.8, eqs. (1.8.2)–(1.8.5); the same scheme in §2.8, §2.11, §3.5.

    Examples
    --------
    >>> import sympy as sp
    >>> a, t = sp.symbols("a t")
    >>> m = Model("line", (a,), (t,), (a * t - 1,))
    >>> m.jacobian()
    Matrix([[t]])
    >>> residual_fn, jacobian_fn = m.compile()
    >>> jacobian_fn(2.0, [1.0, 3.0]).tolist()
    [[1.0, 3.0]]
    """

    name: str
    parameters: tuple
    data: tuple
    residuals: tuple

    def __post_init__(self):
        for kind in ("parameters", "data", "residuals"):
            value = getattr(self, kind)
            if not isinstance(value, (tuple, list)):
                raise InputError(f"Model {kind} must be a tuple, got {type(value).__name__}")
            object.__setattr__(self, kind, tuple(value))
        if not self.parameters or not self.residuals:
            raise InputError("a Model needs at least one parameter and one residual")
        bad = [s for s in self.parameters + self.data if not isinstance(s, sp.Symbol)]
        if bad:
            raise InputError(f"Model parameters and data must be sympy symbols, got {bad[:3]!r}")
        if len(set(self.parameters + self.data)) != len(self.parameters + self.data):
            raise InputError("a symbol appears twice among the Model parameters and data")
        if not all(isinstance(r, sp.Basic) for r in self.residuals):
            raise InputError("Model residuals must be sympy expressions")

    def jacobian(self) -> sp.Matrix:
        """∂F/∂p derived with sympy (rows: residuals, columns: parameters).

        Returns
        -------
        sympy.Matrix
            Shape (number of residuals, number of parameters).

        Raises
        ------
        InputError
            Never for a constructed model (the inputs were checked by the constructor).

        References
        ----------
        Chibunichev (2022), §1.8, eq. (1.8.3): the coefficients a₁…b₆ are these derivatives.

        Examples
        --------
        >>> import sympy as sp
        >>> a, b, t = sp.symbols("a b t")
        >>> Model("line", (a, b), (t,), (a * t + b,)).jacobian()
        Matrix([[t, 1]])
        """
        return _jacobian(self).copy()

    def compile(self):
        """(residual_fn, jacobian_fn): numpy functions of ``(*parameters, *data)``.

        ``residual_fn`` returns an array (n_residuals, ...) and ``jacobian_fn`` an array
        (n_residuals · n_parameters, ...) in row-major order; the trailing axes broadcast over
        the data (e.g. one entry per control point). The numpy code is the committed printed
        code of ``_generated.py`` when the model is one of the library's, else lambdified once.

        Returns
        -------
        tuple of callable
            ``(residual_fn, jacobian_fn)``; each has an attribute ``count`` (rows returned).

        Raises
        ------
        InputError
            Never for a constructed model.

        References
        ----------
        Chibunichev (2022), §1.8, eqs. (1.8.3)–(1.8.5).

        Examples
        --------
        >>> import sympy as sp
        >>> a, t = sp.symbols("a t")
        >>> res, jac = Model("square", (a,), (t,), (a ** 2 - t,)).compile()
        >>> res(3.0, 2.0).tolist(), jac(3.0, 2.0).tolist()
        ([7.0], [6.0])
        """
        return _compiled(self)


@lru_cache(maxsize=None)
def _jacobian(model: Model) -> sp.Matrix:
    """The Jacobian, derived once per model (callers get a copy: sympy matrices are mutable)."""
    return sp.Matrix(model.residuals).jacobian(sp.Matrix(model.parameters))


def _model_key(model: Model) -> str:
    """A hash of the model's sympy form: the key of its printed code in ``_generated.py``."""
    text = sp.srepr((model.name, model.parameters, model.data, model.residuals))
    return hashlib.sha256(text.encode()).hexdigest()


def _lambdify(args, exprs):
    return sp.lambdify(list(args), list(exprs), modules="numpy", cse=True)


def _lambdified_parts(model: dict) -> tuple:
    """(residual, Jacobian) lambdified from a model written as a dict with ``parameters``, ``data``,
    ``residual`` and ``jacobian`` (the mobile-mapping and boresight models): functions of
    ``(*parameters, *data)`` returning the entries as lists."""
    args = (*model["parameters"], *model["data"])
    return (sp.lambdify(args, list(model["residual"]), "numpy"),
            sp.lambdify(args, list(model["jacobian"]), "numpy"))


@lru_cache(maxsize=None)
def _compiled(model: Model):
    from . import _generated
    n_res, n_jac = len(model.residuals), len(model.residuals) * len(model.parameters)
    printed = _generated.MODELS.get(_model_key(model))
    if printed is not None:
        res, jac = printed
    else:
        args = list(model.parameters) + list(model.data)
        res = _lambdify(args, model.residuals)
        jac = _lambdify(args, list(model.jacobian()))
    return _broadcasting(res, n_res), _broadcasting(jac, n_jac)


def _printed_function(key: str, build):
    """The numpy function printed under ``key`` in ``_generated.py``, or lambdify ``build()``.

    ``build()`` returns ``(args, exprs, count)``; it is only called when ``key`` is missing (the
    drift test checks that the printed code equals the lambdified ``build()``).
    """
    from . import _generated
    fn = _generated.PRINTED.get(key)
    if fn is None:
        args, exprs, count = build()
        return _broadcasting(_lambdify(args, exprs), count)
    return _broadcasting(fn, _generated.PRINTED_COUNTS[key])


def numpy_source(model: Model, function_name: str = "residuals_and_jacobian") -> str:
    """Python/numpy source of one function computing residuals and Jacobian of ``model`` together.

    :meth:`Model.compile` lambdifies residuals and Jacobian separately; for large problems (a
    bundle block has 10⁵–10⁶ image observations) it pays to run sympy's common-subexpression
    elimination over *both* at once, so that x*, y*, z*, the trigonometric terms and 1/z* are
    evaluated once per observation. The sympy expressions stay the single source of truth: this
    is only printed code.

    Parameters
    ----------
    model : Model
        The model to print.
    function_name : str, optional
        Name of the generated function (a Python identifier).

    Returns
    -------
    str
        Source of a function of ``(*parameters, *data)`` (arrays that broadcast) returning
        ``(F, J)`` with shapes (n_res, n) and (n_res·n_par, n), row-major.

    Raises
    ------
    InputError
        If ``model`` is not a :class:`Model` or ``function_name`` is not an identifier.

    References
    ----------
    Chibunichev (2022), §3.5, eqs. (3.5.1)–(3.5.2) (the bundle model printed for
    ``photolib.bundle``).

    Examples
    --------
    >>> import sympy as sp
    >>> a, t = sp.symbols("a t")
    >>> print(numpy_source(Model("line", (a,), (t,), (a * t,)), "line"))  # doctest: +ELLIPSIS
    def line(a, t):
    ...
    """
    if not isinstance(model, Model):
        raise InputError(f"numpy_source needs a Model, got {type(model).__name__}")
    if not isinstance(function_name, str) or not function_name.isidentifier():
        raise InputError(f"function_name must be a Python identifier, got {function_name!r}")
    from sympy.printing.numpy import NumPyPrinter

    exprs = list(model.residuals) + list(model.jacobian())
    replacements, reduced = sp.cse(exprs, symbols=sp.numbered_symbols("_t"), optimizations="basic")
    printer = NumPyPrinter({"fully_qualified_modules": True, "inline": True})
    args = [printer.doprint(s) for s in list(model.parameters) + list(model.data)]
    lines = [f"def {function_name}({', '.join(args)}):",
             f'    """Generated by photolib.derivations.numpy_source from the sympy model {model.name!r}."""']
    lines += [f"    {printer.doprint(sym)} = {printer.doprint(expr)}" for sym, expr in replacements]
    n_res = len(model.residuals)
    lines.append(f"    _out = [{', '.join(printer.doprint(e) for e in reduced)}]")
    lines.append("    _out = numpy.broadcast_arrays(*[numpy.asarray(o, dtype=float) for o in _out])")
    lines.append(f"    return numpy.stack(_out[:{n_res}]), numpy.stack(_out[{n_res}:])")
    return "\n".join(lines) + "\n"


@lru_cache(maxsize=None)
def compile_fused(model: Model):
    """Execute :func:`numpy_source` and return the function ``(*parameters, *data) -> (F, J)``.

    Parameters
    ----------
    model : Model
        The model to compile.

    Returns
    -------
    callable
        The generated function; its attribute ``source`` holds the printed code.

    Raises
    ------
    InputError
        If ``model`` is not a :class:`Model`.

    References
    ----------
    Chibunichev (2022), §3.5, eqs. (3.5.1)–(3.5.2).

    Examples
    --------
    >>> import sympy as sp
    >>> a, t = sp.symbols("a t")
    >>> F, J = compile_fused(Model("line", (a,), (t,), (a * t,)))(2.0, 3.0)
    >>> F.tolist(), J.tolist()
    ([6.0], [3.0])
    """
    source = numpy_source(model)
    namespace = {"numpy": np}
    exec(compile(source, f"<photolib generated: {model.name}>", "exec"), namespace)
    fn = namespace["residuals_and_jacobian"]
    fn.source = source
    return fn
