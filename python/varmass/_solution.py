"""A run's result: NumPy columns by name, the end, the stepper's work."""

from __future__ import annotations

from typing import Dict, List, Optional, Tuple

import numpy as np


def column(raw: bytes) -> np.ndarray:
    """Little-endian f64 bytes from the extension as a (read-only) NumPy array."""
    return np.frombuffer(raw, dtype="<f8")


def table(raw: dict):
    """The times and the columns by name of a table from the extension (its ``names`` and
    ``data``: the times, then each column, as one block of bytes), each a read-only view
    of one array."""
    names = raw["names"]
    data = np.frombuffer(raw["data"], dtype="<f8").reshape(len(names) + 1, -1)
    return data[0], dict(zip(names, data[1:]))


class _Given:
    """A scene's end state, statistics and summary, made by the extension at once (a run's
    come from ``_native.Details``, made when read)."""

    def __init__(self, raw: dict):
        self._raw = raw

    def end_state(self):
        return self._raw["end_state"]

    def statistics(self):
        return self._raw["statistics"]

    def summary(self):
        return self._raw["summary"]

    def lift_off(self):
        return self._raw.get("lift_off")

    def rail_exit(self):
        return self._raw.get("rail_exit")


#: The details a solution keeps beside its columns (pickled with it).
_DETAILS = ("end_state", "statistics", "summary", "lift_off", "rail_exit")

#: Little-endian f64, made once (``np.frombuffer`` would parse ``"<f8"`` at every call).
_F8 = np.dtype("<f8")


class Solution:
    """The quantities a run recorded, one NumPy array per name, at every output time.

    ``sol.t`` are the times; ``sol["x"]`` (or any recorded name, ``sol["t"]`` too) a column;
    ``sol.names`` the recorded names. ``sol.end_time`` and ``sol.end`` (the end state by
    name) say where the run ended, ``sol.stopped_by`` which ``stop_when`` condition ended it
    (``None`` if it reached ``until``), ``sol.statistics`` the stepper's work and
    ``sol.summary`` what ``varmass run`` prints. A scene's solution
    (:class:`varmass.Scene`) has the ``phase`` column and ``sol.changes``, its changes of
    phase (:class:`varmass.PhaseChange`); a run's ``changes`` is empty.
    """

    def __init__(self, names, data: bytes, end_time, stopped_by, details, changes=(), flight=None):
        # One array of the times and every column (rows), each column a view of it.
        self._data = np.frombuffer(data, dtype=_F8).reshape(len(names) + 1, -1)
        self.t: np.ndarray = self._data[0]
        self.names: List[str] = names
        self.end_time: float = end_time
        self.stopped_by: Optional[str] = stopped_by
        self.changes: list = list(changes) if changes else []
        # A scene's flight (``[flight]``): ``varmass._flight.Flight`` or ``None``.
        self._flight = flight
        # The end state, the statistics and the summary, read when first asked for.
        self._details = details
        self._cache: Dict[str, object] = {}

    @classmethod
    def _of_run(cls, ran, stop_when: List[str]) -> "Solution":
        """The solution of ``_native.run``'s result; ``stop_when`` the conditions by
        index."""
        names, data, end_time, stopped_by, details = ran
        if stopped_by is not None:
            stopped_by = stop_when[stopped_by]
        return cls(names, data, end_time, stopped_by, details)

    @classmethod
    def _of_scene(cls, raw: dict, changes) -> "Solution":
        """The solution of ``_native.run_scene``'s result (a dict)."""
        from ._flight import Flight

        flight = Flight(raw["flight"]) if raw.get("flight") is not None else None
        return cls(
            raw["names"],
            raw["data"],
            raw["end_time"],
            raw["stopped_by"],
            _Given(raw),
            changes,
            flight,
        )

    def __reduce__(self):
        # Pickled (a Dask task's result) with its details made: the extension's are not.
        given = {name: self._detail(name) for name in _DETAILS}
        data = self._data.tobytes()
        args = (
            self.names,
            data,
            self.end_time,
            self.stopped_by,
            _Given(given),
            self.changes,
            self._flight,
        )
        return (Solution, args)

    def _detail(self, name: str):
        try:
            return self._cache[name]
        except KeyError:
            # A plain run's details (``_native.Details``) have no support or rail.
            made = getattr(self._details, name, None)
            value = self._cache[name] = made() if made is not None else None
            return value

    @property
    def end_state(self) -> List[float]:
        """The state ``[q, p, m_s]`` where the run ended."""
        return self._detail("end_state")

    @property
    def statistics(self) -> Dict[str, object]:
        """The stepper's work: accepted and rejected steps, rate and Jacobian evaluations,
        Newton iterations, whether stiffness was detected."""
        return self._detail("statistics")

    @property
    def summary(self) -> str:
        """What ``varmass run`` prints after a run."""
        return self._detail("summary")

    @property
    def lift_off(self) -> Optional[float]:
        """When a scene's body left its support or its rail's bottom (``support = "y"``,
        ``[rail]``: docs/scenes.md): the start if it lifted at once, ``None`` if it was
        still held at the end, for a scene with neither, and for a plain run."""
        return self._detail("lift_off")

    @property
    def rail_exit(self) -> Optional[Tuple[float, float]]:
        """When a scene's body left its rail (``[rail]``, docs/scenes.md#a-launch-rail) and
        its speed then (m/s), as ``(time, speed)``; ``None`` if it was still on the rail at
        the end, for a scene without a rail, and for a plain run."""
        exit = self._detail("rail_exit")
        return tuple(exit) if exit is not None else None

    def _column(self, name: str) -> np.ndarray:
        """The column ``name`` (a view), or ``None``."""
        try:
            return self._data[self.names.index(name) + 1]
        except ValueError:
            return None

    def __getitem__(self, name: str) -> np.ndarray:
        if name == "t":
            return self.t
        column = self._column(name)
        if column is None:
            raise KeyError(
                f"{name!r} was not recorded; recorded: t, {', '.join(self.names)} "
                "(ask for more with record=[...])"
            )
        return column

    def sensitivity(self, quantity: str, wrt: str) -> np.ndarray:
        """The derivative of the recorded ``quantity`` (``"t"`` too) with respect to
        ``wrt``, a name the run's ``sensitivity=`` gave (a parameter, ``"init:y'"``), at
        every output time: the column ``d(quantity)/d(wrt)``. Where a ``stop_when``
        condition ended the run, the last value is the derivative at the event, whose time
        moves with ``wrt`` (``sensitivity("t", wrt)`` there is the event time's)."""
        name = f"d({quantity})/d({wrt})"
        column = self._column(name)
        if column is None:
            asked = sorted({n.split("/d(", 1)[1][:-1] for n in self.names if n.startswith("d(") and "/d(" in n})
            raise KeyError(
                f"no sensitivity of {quantity!r} to {wrt!r}: the run recorded "
                f"{', '.join(n for n in self.names if not n.startswith('d('))} with "
                f"sensitivity to {', '.join(asked) if asked else 'nothing'} "
                "(ask with sensitivity=[...])"
            )
        return column

    def __contains__(self, name: object) -> bool:
        return name == "t" or name in self.names

    def __len__(self) -> int:
        return len(self.t)

    def keys(self) -> List[str]:
        return ["t", *self.names]

    @property
    def end(self) -> Dict[str, float]:
        """The recorded quantities at the end of the run."""
        return {n: float(c[-1]) for n, c in zip(self.names, self._data[1:])}

    def to_pandas(self):
        """A DataFrame with a column ``t`` and one per recorded name (needs pandas)."""
        try:
            import pandas as pd
        except ImportError as e:  # pragma: no cover - depends on the environment
            raise ImportError("to_pandas() needs pandas: pip install pandas") from e
        return pd.DataFrame({n: self[n] for n in self.keys()})

    def plot(self, names=None, ax=None):
        """Plots the recorded quantities (or ``names``) against t; returns the Axes."""
        try:
            import matplotlib.pyplot as plt
        except ImportError as e:  # pragma: no cover - depends on the environment
            raise ImportError("plot() needs matplotlib: pip install matplotlib") from e
        if ax is None:
            _, ax = plt.subplots()
        for n in names if names is not None else self.names:
            ax.plot(self.t, self[n], label=n)
        ax.set_xlabel("t")
        ax.legend()
        return ax

    def flight_summary(self) -> dict:
        """A scene's flight summary (its ``[flight]`` table, docs/scenes.md#flight), as a
        dict with the keys of ``varmass run SCENE.toml --summary-json``: ``apogee`` (time,
        altitude, their interpolation error bounds, the rows that bracket it), ``max_speed``,
        ``max_mach``, ``max_qbar``, ``max_acceleration`` (value, time), ``burnout``,
        ``lift_off``, ``rail_exit``, ``static_margin``, ``phases``, ``landing``, ``end``,
        ``log`` and ``roles`` (the expression of each role). ``ValueError`` without a
        flight."""
        from ._flight import no_flight

        if self._flight is None:
            raise no_flight()
        return self._flight.summary()

    def plot_flight(self, log=None, fig=None):
        """Plots the flight's panels — altitude, speed, attitude, angle of attack, static
        margin, those its ``[flight]`` has — against t with Matplotlib, and the measured
        log's altitude over the first: ``log=None`` the scene's ``log``, ``False`` none, a
        pair ``(t, altitude)``, a CSV path (columns ``Time (s)``, ``Altitude (m)``) or
        ``{"file": …, "time": …, "altitude": …}``. Returns the Figure."""
        from ._flight import no_flight, plot_flight

        if self._flight is None:
            raise no_flight()
        return plot_flight(self._flight, log=log, fig=fig)

    def __repr__(self) -> str:
        how = f"stop_when {self.stopped_by!r}" if self.stopped_by else "until"
        return (
            f"<Solution: {len(self)} points of t, {', '.join(self.names)}; "
            f"ended at t = {self.end_time} ({how}); "
            f"{self.statistics['accepted_steps']} steps>"
        )
