"""``varmass.Model``: a model file derived, checked, shown and run from Python."""

from __future__ import annotations

import os
import warnings
from typing import Iterable, List, Mapping, NamedTuple, Optional, Tuple

import numpy as np

from . import _checks, _native
from ._errors import ModelWarning, RunError
from ._solution import Solution, table


class Check(NamedTuple):
    """A ``check`` statement of the model and how it was decided."""

    statement: str
    verdict: str


class Model:
    """A variable-mass model in the varmass DSL, derived when made.

    ``Model(text)`` derives DSL text; ``Model.from_file(path, with_=[...])`` a model file
    with the statements tagged ``[tag]`` that ``with_`` selects. A model that does not
    derive (or fails one of its ``check``\\ s) raises :class:`varmass.ModelError` with the
    file, line and column.
    """

    def __init__(self, text: str, with_=(), *, name: str = "<model>"):
        if not isinstance(text, str):
            raise TypeError(f"text must be a string of DSL, not {type(text).__name__}")
        if not isinstance(name, str):
            raise TypeError(f"name must be a string, not {type(name).__name__}")
        self._source = text
        self._file = name
        self._with = _checks.tags(with_)
        facts, self._compiled = _native.load(self._source, self._file, self._with)
        self._facts = facts
        # Without `units`, a misspelt name becomes a new parameter: said now, as `varmass
        # check` says it, rather than found when a run asks for its value.
        for warning in facts["warnings"]:
            warnings.warn(warning, ModelWarning, stacklevel=2)
        self._text: Optional[str] = None
        self._latex: Optional[str] = None
        # The last run's arguments (`_checks.plain_key`), its options as the tool's
        # arguments and its stop_when conditions by name: a sweep over `set` checks and
        # makes them once.
        self._options = None

    @classmethod
    def from_file(cls, path, with_=()) -> "Model":
        """Reads and derives the model file ``path`` (diagnostics name it)."""
        if not isinstance(path, (str, os.PathLike)):
            raise TypeError(f"path must be a str or os.PathLike, not {type(path).__name__}")
        with open(path, encoding="utf-8") as f:
            text = f.read()
        return cls(text, with_, name=os.fspath(path))

    @property
    def name(self) -> str:
        """The file name, or ``<model>`` for text."""
        return self._file

    @property
    def with_(self) -> List[str]:
        return list(self._with)

    @property
    def coordinates(self) -> List[str]:
        return list(self._facts["coordinates"])

    @property
    def parameters(self) -> List[str]:
        """The parameters the equations read: each needs a value in ``run(set=...)``."""
        return list(self._facts["parameters"])

    @property
    def state_masses(self) -> List[str]:
        """Masses integrated as state: each needs a value in ``run(init=...)``."""
        return list(self._facts["state_masses"])

    @property
    def masses(self) -> List[str]:
        return list(self._facts["state_masses"]) + list(self._facts["mass_laws"])

    @property
    def tags(self) -> List[str]:
        """Every tag of the model file, selected or not."""
        return list(self._facts["tags"])

    def check(self) -> List[Check]:
        """Each ``check`` of the model with how it was decided (the model derived, so all
        hold; one that did not would have raised ModelError)."""
        return [Check(s, v) for s, v in self._facts["checks"]]

    @property
    def derivation(self) -> str:
        """The whole derivation as text, as ``varmass derive`` prints it."""
        if self._text is None:
            self._text = self._native().derivation(False)
        return self._text

    @property
    def latex(self) -> str:
        """The derivation as LaTeX (``align*`` environments, ``%`` headings), as
        ``varmass derive --latex`` prints it."""
        if self._latex is None:
            self._latex = self._native().derivation(True)
        return self._latex

    def _repr_latex_(self) -> str:
        """Jupyter shows the derivation: each heading as text, each block as display math."""
        parts = []
        for line in self.latex.splitlines():
            if line.startswith("%"):
                parts.append(line.lstrip("% ").strip())
            else:
                parts.append(line)
        return "\n".join(parts)

    def _native(self):
        """The model derived and compiled once (a run reuses it); derived again after
        unpickling."""
        if self._compiled is None:
            _, self._compiled = _native.load(self._source, self._file, self._with)
        return self._compiled

    def __getstate__(self):
        state = dict(self.__dict__)
        state["_options"] = None
        state["_compiled"] = None
        return state

    def __repr__(self) -> str:
        tags = f" with {self._with}" if self._with else ""
        return (
            f"<varmass.Model {self._file}{tags}: coordinates {self.coordinates}, "
            f"parameters {self.parameters}>"
        )

    def run(
        self,
        *,
        set: Optional[Mapping] = None,
        init: Optional[Mapping] = None,
        until=None,
        from_=0.0,
        stop_when=None,
        method: str = "dormand-prince",
        tol=None,
        step=None,
        record=None,
        every=None,
        sensitivity=None,
        inputs: Optional[Mapping] = None,
        tables: Optional[Mapping] = None,
    ) -> Solution:
        """Integrates the model as ``varmass run`` does, with its defaults and messages.

        ``set``: parameter values; ``init``: coordinates and state masses (velocities
        ``x'`` default to 0); ``until``: the end time (``from_`` the start);
        ``stop_when``: ``"x = 50"``, ``"y' < 0"`` (falling through), ``"m > 3"``
        (rising), or a list; ``method``: one of ``varmass.METHODS``; ``tol`` (adaptive
        methods, default 1e-9, from the method's floor, 2.2e-14 or 1e-15 for
        ``"taylor"``, to 0.1) or ``step`` (fixed step); ``record``: the quantities to
        record (default coordinates, velocities and state masses); ``every``: output
        spacing instead of every accepted step; ``sensitivity``: a parameter's name or an
        initial value's (``"init:y"``, ``"init:y'"``, ``"init:m"``), or a list of up to 6,
        whose derivatives are recorded with the run (forward sensitivities,
        docs/sensitivities.md: ``sol.sensitivity("y", "u_e")``; ``"dormand-prince"`` or
        ``"dop853"``); ``inputs``: a law for each ``input`` of
        the model, ``{"u": "g + kp*(y_ref - y) - kd*y'"}``, as ``--input`` takes it
        (docs/inputs.md), or its data as a table of its first argument: a ``.csv``/``.eng``
        file or a pair of arrays ``(arguments, values)`` (linear, an error outside);
        ``tables``: the data of the model's tables, ``{"F": "motors/x.eng"}`` (a path,
        relative to the current directory) or ``{"F": (t, F)}`` (two arrays), as
        ``--table`` takes them: required by each ``table F(t) = runtime``, and replacing
        the file of a file table; the statement's options (interpolation, ``outside``) hold
        (docs/tables.md#runtime-tables), and arrays for a table declared from a RASP
        ``.eng`` file are read as one (from (0 s, 0 N) unless they list t = 0). A mistake
        is a ``ValueError`` or ``TypeError`` naming the keyword. The GIL is released while
        it runs.
        """
        # A dict goes to the extension as it is (checked there if plain, else below, after
        # the other arguments); anything else is checked first, as always.
        plain = type(set) is dict
        parameters = set if plain else _checks.unique_values("set", set)
        given = _checks.run_keywords(locals())
        key = _checks.plain_key(*given.values())
        made = self._options
        if key is None or made is None or made[0] != key:
            options = _checks.run_options(given, self._facts["motors"])
            args = _native.options(self._file, self._with, options)
            made = self._options = (key, args, options["stop_when"])
        native = self._native()
        try:
            # The extension refuses (None) a dict it cannot take as it is.
            raw = _native.run(native, parameters, made[1])
            if raw is None:  # a dict that is not plain
                raw = _native.run(native, _checks.unique_values("set", set), made[1])
        except RunError as error:
            error.points = _partial_points(error)
            raise
        return Solution._of_run(raw, made[2])

    def fit(
        self,
        data: Mapping,
        fit,
        *,
        sigma: Optional[Mapping] = None,
        set: Optional[Mapping] = None,
        init: Optional[Mapping] = None,
        from_=0.0,
        until=None,
        method: str = "dop853",
        tol=None,
        predict: Optional[str] = None,
        predict_until=None,
    ):
        """Fits parameters (and start values) of the model to measured data by weighted
        least squares, as ``varmass fit`` does (docs/sensitivities.md#fitting).

        ``data``: a mapping of model quantities to ``(times, values)`` arrays
        (``{"y": (t, altitude)}``); ``fit``: a name, a list of names (a parameter, or a
        start value ``"init:y'"``) or a mapping of names to ``(lo, hi)`` bounds (``None``
        for none); ``sigma``: each quantity's standard deviation (without it the errors
        are scaled by the residuals' spread; several quantities need theirs); ``set``:
        the parameter values, the fitted ones' start among them; ``init``, ``from_``,
        ``method`` (``"dop853"`` or ``"dormand-prince"``) and ``tol`` as :meth:`run`;
        ``until`` defaults to the data's last time. Returns a :class:`FitResult`.

        ``predict``: a condition (``"z' < 0"``, the apogee; ``"m < 40"``) the fitted model
        then runs on to, as ``varmass fit --predict`` does, before ``predict_until`` (by
        default ``from_`` plus ten times the data's span, at least 10): the result's
        ``prediction`` (a :class:`varmass.Prediction`) holds the event's time and each data
        quantity there, each with its standard error √(gᵀΣg). A prediction that fails (the
        condition not reached, a failed run) raises :class:`varmass.RunError` whose ``fit``
        is the fit's result, as the command line prints the fit before the error.
        """
        series = _series(data, sigma)
        unknowns = _unknowns(fit)
        request = _checks.prediction(predict, predict_until, _checks.number("from_", from_))
        last = max(s[1][-1] for s in series)
        options = _checks.run_options(
            {
                "init": init,
                "from_": from_,
                "until": last if until is None else until,
                "method": method,
                "tol": tol,
            },
            self._facts["motors"],
        )
        args = _native.options(self._file, self._with, options)
        pairs = _checks.unique_values("set", set)
        raw = _native.fit(self._native(), pairs, args, series, unknowns, request)
        return _fit_result(unknowns, raw, series, request)


    def ensemble(self, seed: int, **options):
        """An ensemble of runs of this model (see :class:`varmass.Ensemble`, which takes
        ``options``)."""
        from ._ensemble import Ensemble

        return Ensemble(self, seed, **options)


def _partial_points(error):
    """The points a failed run recorded before its failure, by name (``t`` first), or
    ``None`` when it failed before its first step."""
    partial = getattr(error, "_partial", None)
    if partial is None:
        return None
    t, columns = table(partial)
    return {"t": t, **columns}


def _series(data, sigma) -> list:
    """``data`` (a mapping of quantities to ``(times, values)``) and ``sigma`` (their
    standard deviations) as the native fit takes them: (quantity, times, values, σ or
    ``None``), each checked."""
    if not isinstance(data, Mapping) or not data:
        raise TypeError("data must be a non-empty mapping of quantities to (times, values)")
    weights = dict(_checks.values("sigma", sigma))
    series = []
    for quantity, pair in data.items():
        quantity = _checks.name("data", quantity)
        try:
            times, measured = pair
        except (TypeError, ValueError):
            raise TypeError(f"data[{quantity!r}] must be a pair (times, values)") from None
        times = np.asarray(times, dtype=float).ravel()
        measured = np.asarray(measured, dtype=float).ravel()
        if times.shape != measured.shape or times.size == 0:
            raise ValueError(f"data[{quantity!r}]: times and values must be equally long, not empty")
        if not (np.all(np.isfinite(times)) and np.all(np.isfinite(measured))):
            raise ValueError(f"data[{quantity!r}]: times and values must be finite")
        if np.any(np.diff(times) <= 0):
            raise ValueError(f"data[{quantity!r}]: the times must increase")
        series.append((quantity, times.tolist(), measured.tolist(), weights.pop(quantity, None)))
    if weights:
        raise ValueError(f"sigma: {', '.join(weights)} is no quantity of data")
    return series


def _fit_result(unknowns, raw, series, request=None):
    """The :class:`FitResult` of the native fit's result ``raw``, with the prediction
    ``request`` asked (condition, until); a failed prediction raises :class:`RunError`
    carrying the result."""
    from ._fit import FitResult, Prediction
    from ._solution import _Given

    names, block = raw[6], raw[7]
    times = np.frombuffer(block, dtype="<f8").reshape(len(names) + 1, -1)[0]
    details = _Given({"end_state": None, "statistics": None, "summary": None})
    solution = Solution(names, block, float(times[-1]), None, details)
    predicted, failure = raw[8]
    prediction = None if predicted is None else Prediction(predicted)
    result = FitResult(
        [u[0] for u in unknowns], raw[:6], [s[0] for s in series], solution, prediction
    )
    if failure is not None:
        # As `varmass fit --predict`: the fit stands (its report first), then the error.
        error = RunError(f"predict `{request[0]}`: {failure}")
        error.fit = result
        raise error
    return result


def _unknowns(fit) -> list:
    """``fit`` as (name, lo, hi) triples: a name, a list of names, or a mapping of names to
    ``(lo, hi)`` bounds or ``None``."""
    inf = float("inf")
    if isinstance(fit, str):
        return [(_checks.name("fit", fit), -inf, inf)]
    if isinstance(fit, Mapping):
        out = []
        for key, bounds in fit.items():
            if bounds is None:
                out.append((_checks.name("fit", key), -inf, inf))
                continue
            try:
                lo, hi = bounds
            except (TypeError, ValueError):
                raise TypeError(f"fit[{key!r}] must be (lo, hi) or None") from None
            lo = -inf if lo is None else float(lo)
            hi = inf if hi is None else float(hi)
            if not lo < hi:
                raise ValueError(f"fit[{key!r}]: lo must be below hi")
            out.append((_checks.name("fit", key), lo, hi))
        return out
    if isinstance(fit, Iterable):
        return [(_checks.name("fit", name), -inf, inf) for name in fit]
    raise TypeError(f"fit must be a name, a list of names or a mapping, not {type(fit).__name__}")
