"""A scene's flight (``[flight]`` in the scene file, docs/scenes.md#flight): its summary as
``varmass run SCENE.toml`` prints it and ``--summary-json`` writes it, and its panels drawn
with Matplotlib."""

from __future__ import annotations

import csv
import json
import os
from typing import Dict, Optional, Tuple

import numpy as np

#: The panels of :func:`plot_flight`: title and the roles drawn in it (the tool's SVG has
#: the same).
PANELS = (
    ("altitude", ("altitude",)),
    ("speed", ("speed", "vertical_speed")),
    ("attitude", ("pitch", "heading")),
    ("angle of attack", ("alpha",)),
    ("static margin", ("static_margin",)),
)

#: The legend's name of the measured log's series.
LOG_SERIES = "measured log"


class Flight:
    """A scene's flight as the extension gives it: the summary (JSON text), the roles'
    values at every recorded row, and the measured log."""

    def __init__(self, raw: dict):
        self._raw = raw
        names = raw["table"]["names"]
        data = np.frombuffer(raw["table"]["data"], dtype="<f8").reshape(len(names) + 1, -1)
        self.t: np.ndarray = data[0]
        self.columns: Dict[str, np.ndarray] = dict(zip(names, data[1:]))
        log = raw.get("log")
        self.log: Optional[Tuple[np.ndarray, np.ndarray]] = (
            None if log is None else (np.asarray(log[0]), np.asarray(log[1]))
        )

    def summary(self) -> dict:
        """The summary as a dict (a fresh one at each call), the keys of the JSON."""
        return json.loads(self._raw["summary"])

    def __reduce__(self):
        return (Flight, (self._raw,))


def no_flight() -> ValueError:
    return ValueError(
        "this solution has no flight: the scene file needs a [flight] table "
        "(docs/scenes.md#flight), and a plain Model.run has none"
    )


def read_log(log, default: Optional[Tuple[np.ndarray, np.ndarray]]):
    """The (times, altitudes) of ``plot_flight``'s ``log``: ``None`` for the scene's own,
    ``False`` for none, a pair of arrays, a CSV path (columns ``Time (s)`` and ``Altitude
    (m)``) or a dict ``{"file", "time", "altitude"}`` as the scene file's ``log``."""
    if log is None:
        return default
    if log is False:
        return None
    if isinstance(log, (str, os.PathLike)):
        log = {"file": log}
    if isinstance(log, dict):
        return _csv_columns(
            log["file"], log.get("time", "Time (s)"), log.get("altitude", "Altitude (m)")
        )
    times, altitudes = log
    return np.asarray(times, dtype=float), np.asarray(altitudes, dtype=float)


def _csv_columns(path, time: str, altitude: str):
    with open(path, newline="") as f:
        rows = [r for r in csv.reader(f) if r and not r[0].lstrip().startswith("#")]
    header = [h.strip() for h in rows[0]]
    for name in (time, altitude):
        if name not in header:
            raise ValueError(f"the log {os.fspath(path)!r} has no column {name!r}; it has {header}")
    i, j = header.index(time), header.index(altitude)
    data = np.array([[float(r[i]), float(r[j])] for r in rows[1:]])
    return data[:, 0], data[:, 1]


def plot_flight(flight: Flight, log=None, fig=None):
    """Draws the flight's panels (those whose roles it has) against t, the log's altitude
    over the altitude panel; returns the Figure."""
    try:
        import matplotlib.pyplot as plt
    except ImportError as e:
        raise ImportError(
            "plot_flight() needs matplotlib: pip install 'varmass[plot]' (or matplotlib)"
        ) from e
    measured = read_log(log, flight.log)
    panels = [
        (title, [r for r in roles if r in flight.columns])
        for title, roles in PANELS
    ]
    panels = [(title, roles) for title, roles in panels if roles]
    if fig is None:
        fig = plt.figure(figsize=(9, 2.8 * len(panels)))
    axes = fig.subplots(len(panels), 1, sharex=True, squeeze=False)[:, 0]
    for ax, (title, roles) in zip(axes, panels):
        for role in roles:
            ax.plot(flight.t, flight.columns[role], label=role.replace("_", " "))
        if title == "altitude" and measured is not None:
            ax.plot(measured[0], measured[1], "--", label=LOG_SERIES)
        ax.set_title(title)
        ax.legend()
    axes[-1].set_xlabel("t")
    return fig
