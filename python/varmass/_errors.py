"""The exceptions of varmass: a model that does not derive, and a run that fails.

Their text is exactly the command line tool's message; the fields are read from it.
"""

from __future__ import annotations

import re
from typing import Dict, List, NamedTuple, Optional

__all__ = ["VarmassError", "ModelError", "ModelWarning", "RunError", "Diagnostic"]


class Diagnostic(NamedTuple):
    """One problem in a model: its message and where it is (1-based line and column)."""

    message: str
    file: str
    line: int
    column: int


class VarmassError(Exception):
    """The base of varmass's own exceptions."""


class ModelWarning(UserWarning):
    """A model that derives but probably does not say what its author meant: without
    ``units``, a parameter one edit away from another name of the model (``muu`` beside
    ``mu``) is most likely a typo that became a new parameter. The text is ``varmass
    check``'s warning."""


_POSITION = re.compile(r"^\s*--> (.*):(\d+):(\d+)$")


class ModelError(VarmassError):
    """The model does not derive, or one of its ``check`` statements fails.

    ``str(error)`` is every diagnostic as ``varmass check`` prints it (message, ``-->
    file:line:column``, the line and a caret). ``file``, ``line``, ``column`` and
    ``message`` are those of the first diagnostic; ``diagnostics`` lists them all.
    """

    def __init__(self, rendered: str):
        super().__init__(rendered)
        self.diagnostics: List[Diagnostic] = _diagnostics(rendered)
        first = self.diagnostics[0] if self.diagnostics else None
        self.message: str = first.message if first else rendered
        self.file: Optional[str] = first.file if first else None
        self.line: Optional[int] = first.line if first else None
        self.column: Optional[int] = first.column if first else None


def _diagnostics(rendered: str) -> List[Diagnostic]:
    found = []
    message = None
    for text in rendered.splitlines():
        if text.startswith("error: "):
            message = text[len("error: "):]
            continue
        position = _POSITION.match(text)
        if position and message is not None:
            found.append(
                Diagnostic(message, position[1], int(position[2]), int(position[3]))
            )
            message = None
    return found


_FAILED_AT = re.compile(r"^the run failed at t = (\S+): (.*)$")
_STATE_LINE = re.compile(r"^  (\S+) = (\S+)$")


class RunError(VarmassError):
    """A run failed (a mass that is no longer positive, a step size that underflows, …).

    ``str(error)`` is the tool's message. ``time`` is when it failed, ``reason`` why, and
    ``state`` the state there by name (coordinates, velocities, momenta, state masses).
    ``points`` holds what the run recorded up to the failure, one NumPy array per recorded
    name and ``t`` (``None`` when it failed before its first step). ``fit`` is the
    :class:`varmass.FitResult` of a fit whose prediction failed (``fit(..., predict=...)``:
    the fit stands, as ``varmass fit --predict`` prints its report before the error), else
    ``None``.
    """

    def __init__(self, message: str):
        super().__init__(message)
        self.time: Optional[float] = None
        self.reason: str = message
        self.state: Dict[str, float] = {}
        self.points = None
        self.fit = None
        lines = message.splitlines()
        failed = _FAILED_AT.match(lines[0]) if lines else None
        if failed:
            self.time = float(failed[1])
            self.reason = failed[2]
        for text in lines[1:]:
            line = _STATE_LINE.match(text)
            if line:
                self.state[line[1]] = float(line[2])
