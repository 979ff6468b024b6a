"""Arguments from Python, checked and turned into the typed options of a run.

A wrong type is a ``TypeError`` and an unusable value a ``ValueError``, each naming the
argument; what the model decides (an unknown name, a missing initial value) is checked by
the tool itself, with its message.
"""

from __future__ import annotations

import math
import numbers
import os
from typing import Iterable, List, Mapping, Optional, Sequence, Tuple

from . import _native, _tables

# The tool's methods, in its order (`varmass_cli::args::Method::names`): one list for the
# command line, scene files and Python.
METHODS = tuple(_native.METHODS)


def number(name: str, value, *, positive: bool = False) -> float:
    """``value`` as a finite float (positive if asked)."""
    # float and int first: the ABC check of numbers.Real costs more than the rest.
    kind = type(value)
    if kind is not float and kind is not int:
        if isinstance(value, bool) or not isinstance(value, numbers.Real):
            raise TypeError(f"{name} must be a number, not {type(value).__name__}")
    value = float(value)
    if not math.isfinite(value):
        raise ValueError(f"{name} must be finite, not {value}")
    if positive and value <= 0.0:
        raise ValueError(f"{name} must be positive, not {value}")
    return value


def optional_number(name: str, value, *, positive: bool = False) -> Optional[float]:
    return None if value is None else number(name, value, positive=positive)


def name(argument: str, value) -> str:
    if not isinstance(value, str):
        raise TypeError(f"{argument} names must be strings, not {type(value).__name__}")
    stripped = value.strip()
    if not stripped:
        raise ValueError(f"{argument}: a name is empty")
    return stripped


def values(argument: str, mapping) -> List[Tuple[str, float]]:
    """A mapping of names to numbers, checked."""
    if mapping is None:
        return []
    if type(mapping) is not dict and not isinstance(mapping, Mapping):
        raise TypeError(
            f"{argument} must be a mapping of names to numbers, not {type(mapping).__name__}"
        )
    return [
        (name(argument, key), number(f"{argument}[{key!r}]", value))
        for key, value in mapping.items()
    ]


def unique_values(argument: str, mapping) -> List[Tuple[str, float]]:
    """:func:`values`, each name once (two keys may be one name once stripped)."""
    if type(mapping) is dict:
        # A dict of names to finite floats, as written (nothing to strip): its pairs, as
        # the checks below would give them, unique as a dict's keys are (a sweep's `set`
        # takes this path).
        pairs = list(mapping.items())
        for key, value in pairs:
            if type(key) is not str or type(value) is not float:
                break
            if not key or key.strip() != key or value - value != 0.0:
                break
        else:
            return pairs
    pairs = values(argument, mapping)
    no_duplicates(argument, pairs)
    return pairs


def names(argument: str, given) -> List[str]:
    """One name or a sequence of names."""
    if given is None:
        return []
    if isinstance(given, str):
        return [name(argument, given)]
    if not isinstance(given, Iterable):
        raise TypeError(
            f"{argument} must be a string or a list of strings, not {type(given).__name__}"
        )
    return [name(argument, item) for item in given]


def method(value) -> str:
    if not isinstance(value, str):
        raise TypeError(f"method must be a string, not {type(value).__name__}")
    normal = value.strip().lower().replace("_", "-")
    if normal not in METHODS:
        raise ValueError(f"method {value!r} is not one of: {', '.join(METHODS)}")
    return normal


def tags(value) -> List[str]:
    return names("with_", value)


#: The keywords of a run beside ``set``, with their defaults, written once: ``Model.run``
#: takes them all, an ensemble all but ``record`` and ``every`` (it records its observables
#: at the end of each run).
RUN_KEYWORDS = {
    "init": None,
    "until": None,
    "from_": 0.0,
    "stop_when": None,
    "method": "dormand-prince",
    "tol": None,
    "step": None,
    "record": None,
    "every": None,
    "sensitivity": None,
    "inputs": None,
    "tables": None,
}


def run_keywords(arguments: Mapping) -> dict:
    """The run keywords among ``arguments`` (a call's ``locals()``)."""
    return {key: arguments[key] for key in RUN_KEYWORDS if key in arguments}


def run_options(given: Mapping, motors: Iterable[str] = ()) -> dict:
    """The run keywords ``given`` (the others at their defaults), checked and typed, as the
    extension's ``options`` takes them (numbers as floats, names and laws as text, arrays
    of ``inputs`` and ``tables`` written to this process's data files; ``motors``: the
    tables declared from a RASP ``.eng`` file, see ``_tables.table_options``)."""
    o = {**RUN_KEYWORDS, **given}
    if o["until"] is None:
        raise TypeError("until is required: the end time of the run")
    from_, until = number("from_", o["from_"]), number("until", o["until"])
    init = values("init", o["init"])
    stop_when = names("stop_when", o["stop_when"])
    method_name = method(o["method"])
    tol = optional_number("tol", o["tol"], positive=True)
    step = optional_number("step", o["step"], positive=True)
    if tol is not None and step is not None:
        raise ValueError("tol and step exclude each other: give one")
    return {
        "from_": from_,
        "until": until,
        "init": init,
        "stop_when": stop_when,
        "method": method_name,
        "tol": tol,
        "step": step,
        "record": names("record", o["record"]),
        "every": optional_number("every", o["every"], positive=True),
        "sensitivity": names("sensitivity", o["sensitivity"]),
        "inputs": input_laws(o["inputs"]),
        "tables": _tables.table_options(o["tables"], motors),
    }


def prediction(predict, predict_until, start: Optional[float]) -> Optional[Tuple[str, Optional[float]]]:
    """A fit's ``predict`` (the condition its fitted run goes on to, ``"z' < 0"``) and
    ``predict_until`` (the time that run may reach, after the run's ``start``; ``None``
    for a scene's, which the tool checks) as the extension takes them, or ``None`` without
    ``predict``."""
    if predict is None:
        if predict_until is not None:
            raise ValueError("predict_until needs predict: the condition the run goes on to")
        return None
    if not isinstance(predict, str):
        raise TypeError(
            f"predict must be a condition (a string such as \"z' < 0\"), not {type(predict).__name__}"
        )
    condition = predict.strip()
    if not condition:
        raise ValueError("predict: the condition is empty")
    until = optional_number("predict_until", predict_until)
    if until is not None and start is not None and not until > start:
        raise ValueError(f"predict_until must be after the run's start, {start}, not {until}")
    return condition, until


def input_laws(inputs: Optional[Mapping]) -> List[Tuple[str, str]]:
    """``inputs`` ({name: DSL expression, data file or (arguments, values)}) as (name, law)
    pairs, as ``--input`` takes them: the tool parses a law, and reads a ``.csv``/``.eng``
    file as a table of the input's first argument (arrays are written to such a file)."""
    if inputs is None:
        return []
    if not isinstance(inputs, Mapping):
        raise TypeError(f"inputs must be a mapping of names to expressions, not {type(inputs).__name__}")
    pairs = []
    for name, law in inputs.items():
        if not isinstance(name, str):
            raise TypeError(f"inputs: {name!r}: names must be strings")
        if not isinstance(law, str):
            if not isinstance(law, (os.PathLike, tuple, list)):
                raise TypeError(
                    f"inputs[{name!r}] must be a law (str), a .csv/.eng file or a pair "
                    f"(arguments, values), not {type(law).__name__}"
                )
            law = _tables.data(f"inputs[{name!r}]", name.strip(), law)
        pairs.append((name, law))
    return pairs


def plain_key(*arguments) -> Optional[tuple]:
    """A key for the run options of ``arguments``, or ``None``: two calls whose keys are
    equal make the same options (``Model.run`` then skips making them again). Only plain
    types make a key — numbers of type ``float`` or ``int`` (``1 == 1.0`` makes the same
    flag; a ``bool``, equal to 1 but refused, makes none), strings, ``None``, lists and
    tuples of strings and dicts of strings to numbers or strings — so that equality means
    the same options; any other argument is checked and made anew each time."""
    key = []
    for value in arguments:
        kind = type(value)
        if value is None or kind is float or kind is int or kind is str:
            key.append(value)
        elif kind is dict:
            items = tuple(value.items())
            for k, v in items:
                if type(k) is not str or type(v) not in _PLAIN_VALUES:
                    return None
            key.append(items)
        elif kind is list or kind is tuple:
            for v in value:
                if type(v) is not str:
                    return None
            key.append(tuple(value))
        else:
            return None
    return tuple(key)


_PLAIN_VALUES = (float, int, str)


def no_duplicates(argument: str, pairs: Sequence[Tuple[str, object]]) -> None:
    seen = set()
    for key, _ in pairs:
        if key in seen:
            raise ValueError(f"{argument}: `{key}` is given twice")
        seen.add(key)
