"""``varmass.Scene``: a scene file (``varmass run SCENE.toml``, docs/scenes.md) run from
Python — a model flown through phases, its parameters, state masses and tags changed at
events, the state carried by separation or capture."""

from __future__ import annotations

import os
import warnings
from typing import Mapping, NamedTuple, Optional

from . import _checks, _native
from ._errors import RunError
from ._model import _fit_result, _partial_points, _series, _unknowns
from ._solution import Solution


class PhaseChange(NamedTuple):
    """A change of phase: the phase entered (counted from 1, as the ``phase`` column), its
    time, how the state was carried (``"separation"`` or ``"capture"``), the kinetic
    energy the change removed (½ q̇ᵀ (M_before − M_after) q̇ at a separation; the kinetic
    energy lost in the plastic impact at a capture), and the values the phase set there by
    expressions of the change's time (``set = { drogue_t_open = "t + 1.5" }`` gives
    ``{"drogue_t_open": t + 1.5}``; empty when it set none)."""

    phase: int
    time: float
    rule: str
    kinetic_energy_removed: float
    set: dict = {}


class Scene:
    """A scene file, run by the command line tool's own code (its checks, messages and
    numbers are those of ``varmass run SCENE.toml``).

    ``Scene.from_file("models/two_stage_rocket.toml").run()`` returns a
    :class:`varmass.Solution` whose first column is ``phase`` (1, 2, …; a change appears
    twice, before and after, at the same time) and whose ``changes`` lists each
    :class:`PhaseChange`. A mistake in the file is a ``ValueError`` (or a
    :class:`varmass.ModelError` for its model) before any step; a run that fails raises
    :class:`varmass.RunError` with the points computed up to the failure.
    """

    def __init__(self, path):
        if not isinstance(path, (str, os.PathLike)):
            raise TypeError(f"path must be a str or os.PathLike, not {type(path).__name__}")
        self._path = os.fspath(path)
        if not os.path.isfile(self._path):
            raise FileNotFoundError(f"no scene file {self._path!r}")
        # The models its runs derive, kept for the next run (made again after unpickling).
        self._native = _native.NativeScene()

    @classmethod
    def from_file(cls, path) -> "Scene":
        """The scene file at ``path`` (read, checked and run by :meth:`run`)."""
        return cls(path)

    @property
    def path(self) -> str:
        return self._path

    def run(self, sensitivity=()) -> Solution:
        """Reads, checks and runs the scene (the GIL is released while it computes). The
        model is derived at the first run and kept for the next ones while its file is
        unchanged; the scene file itself is read again at each run.

        ``sensitivity``: names (a parameter, a start value ``"init:y'"``) whose derivative
        columns the run records beside the scene's (``solution.sensitivity("y", "g")``),
        through a support, a rail and changes on a coordinate, a velocity or a state mass
        reaching a value, or at a time (docs/sensitivities.md#scenes)."""
        names = _checks.names("sensitivity", sensitivity)
        try:
            raw = _native.run_scene(self._scene(), self._path, names)
        except RunError as error:
            error.points = _partial_points(error)
            raise
        changes = [
            PhaseChange(phase, time, rule, removed, dict(values))
            for (phase, time, rule, removed, values) in raw["changes"]
        ]
        return Solution._of_scene(raw, changes)

    def fit(
        self,
        data: Mapping,
        fit,
        *,
        sigma: Optional[Mapping] = None,
        predict: Optional[str] = None,
        predict_until=None,
    ):
        """Fits parameters (and start values) of the scene to measured data, as ``varmass
        fit SCENE.toml`` does (docs/sensitivities.md#fitting-a-scene): ``data``, ``fit`` and
        ``sigma`` as :meth:`varmass.Model.fit`; the start values are the scene's own (its
        ``[set]``, else the model's defaults, and its ``[init]``), and its settings are the
        file's. ``"data:offset"`` among ``fit`` fits the log's clock offset, as a model's
        fit does. Data outside the scene's span (shifted by the offset's bound nearest 0)
        are left out with a warning. Returns a :class:`varmass.FitResult`.

        ``predict`` runs the fitted scene on to a condition in place of its own
        ``stop_when`` and ``until``, as ``varmass fit SCENE.toml --predict`` does (it ends
        the last phase only; ``predict_until`` defaults to the scene's start plus ten times
        the data's span): the result's ``prediction``, or a :class:`varmass.RunError`
        carrying the fit as :meth:`varmass.Model.fit` says."""
        series = _series(data, sigma)
        unknowns = _unknowns(fit)
        request = _checks.prediction(predict, predict_until, None)
        raw, left_out = _native.fit_scene(self._path, series, unknowns, request)
        if left_out:
            warnings.warn(
                f"{left_out} data outside the scene's span were left out of the fit",
                stacklevel=2,
            )
        return _fit_result(unknowns, raw, series, request)

    def _scene(self):
        if self._native is None:
            self._native = _native.NativeScene()
        return self._native

    def __getstate__(self):
        return {**self.__dict__, "_native": None}

    def __repr__(self) -> str:
        return f"<varmass.Scene {self._path}>"


def run_scene(path) -> Solution:
    """``Scene.from_file(path).run()``."""
    return Scene.from_file(path).run()
