"""A run's result: NumPy columns by name, the end, the stepper's work."""

from __future__ import annotations

from typing import Dict, List, Optional

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

    def __init__(self, raw: dict, stop_when: Optional[List[str]], changes=()):
        self.t: np.ndarray
        self._columns: Dict[str, np.ndarray]
        self.t, self._columns = table(raw)
        self.names: List[str] = raw["names"]
        self.end_time: float = raw["end_time"]
        self.end_state: List[float] = raw["end_state"]
        # A run gives the index of its condition; a scene the condition itself.
        stopped_by = raw["stopped_by"]
        if stop_when is not None and stopped_by is not None:
            stopped_by = stop_when[stopped_by]
        self.stopped_by: Optional[str] = stopped_by
        self.changes: list = list(changes)
        self.statistics: Dict[str, object] = raw["statistics"]
        self.summary: str = raw["summary"]

    def __getitem__(self, name: str) -> np.ndarray:
        if name == "t":
            return self.t
        try:
            return self._columns[name]
        except KeyError:
            raise KeyError(
                f"{name!r} was not recorded; recorded: t, {', '.join(self.names)} "
                "(ask for more with record=[...])"
            ) from None

    def __contains__(self, name: object) -> bool:
        return name == "t" or name in self._columns

    def __len__(self) -> int:
        return len(self.t)

    def keys(self) -> List[str]:
        return ["t", *self.names]

    @property
    def end(self) -> Dict[str, float]:
        """The recorded quantities at the end of the run."""
        return {n: float(c[-1]) for n, c in self._columns.items()}

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

    def __repr__(self) -> str:
        how = f"stop_when {self.stopped_by!r}" if self.stopped_by else "until"
        return (
            f"<Solution: {len(self)} points of t, {', '.join(self.names)}; "
            f"ended at t = {self.end_time} ({how}); "
            f"{self.statistics['accepted_steps']} steps>"
        )
