"""Data for a run's tables and inputs given from Python: a path as the tool takes it, or
NumPy arrays written once to a CSV file the tool reads.

The command line tool reads a table's data from a file (``--table F=FILE``,
``--input u=FILE.csv``; docs/tables.md#runtime-tables). Arrays from Python take the same
path: each pair is written as a two-column CSV (a header, then ``argument,value`` a line,
every number in Python's shortest round-trip form, which Rust's parser reads back to the
same bits), so a table given by arrays runs exactly as the same numbers in a file. The file
is named by a digest of the data: the same arrays give the same file (written once, and a
run with them reuses the model derived for them), other arrays another. The files live in a
temporary directory of this process, removed when it exits; an ensemble sent to other
processes (Dask) carries the arrays and writes them there.
"""

from __future__ import annotations

import atexit
import hashlib
import os
import shutil
import tempfile
from typing import Iterable, List, Mapping, Optional, Tuple

import numpy as np

#: This process's directory of data files (pid, path), made at the first use.
_directory: Optional[Tuple[int, str]] = None


def _files() -> str:
    """The directory of this process's data files; a forked child makes its own."""
    global _directory
    if _directory is None or _directory[0] != os.getpid():
        path = tempfile.mkdtemp(prefix="varmass-tables-")
        atexit.register(shutil.rmtree, path, True)
        _directory = (os.getpid(), path)
    return _directory[1]


def arrays(argument: str, given) -> Tuple[np.ndarray, np.ndarray]:
    """``given`` = (arguments, values) as two float64 arrays, checked: one dimension, the
    same length, at least two points, finite, the arguments increasing (what the tool's
    reader refuses, refused here naming ``argument``)."""
    if len(given) != 2:
        raise ValueError(f"{argument} must be a path or a pair (arguments, values), not {len(given)} items")
    try:
        x, y = (np.asarray(a, dtype=np.float64) for a in given)
    except (TypeError, ValueError) as e:
        raise TypeError(f"{argument}: the arguments and values must be numbers ({e})") from None
    if x.ndim != 1 or y.ndim != 1:
        raise ValueError(f"{argument}: the arguments and values must be 1-D, not {x.ndim}-D and {y.ndim}-D")
    if len(x) != len(y):
        raise ValueError(f"{argument}: {len(x)} arguments but {len(y)} values")
    if len(x) < 2:
        raise ValueError(f"{argument}: a table needs at least two points, not {len(x)}")
    if not (np.all(np.isfinite(x)) and np.all(np.isfinite(y))):
        raise ValueError(f"{argument}: the arguments and values must be finite")
    steps = np.diff(x)
    if not np.all(steps > 0.0):
        k = int(np.argmin(steps > 0.0))
        raise ValueError(
            f"{argument}: the arguments must increase, but {float(x[k + 1])!r} follows {float(x[k])!r}"
        )
    return x, y


def csv_file(name: str, x: np.ndarray, y: np.ndarray, *, eng: bool = False) -> str:
    """The path of a file holding the points (x, y), written if not there yet: a CSV
    table, or with ``eng`` a RASP motor (a header, then ``time thrust`` a line), which the
    tool reads as it reads any ``.eng`` file — from (0 s, 0 N) unless the points list t = 0."""
    digest = hashlib.sha256(x.astype("<f8").tobytes() + y.astype("<f8").tobytes())
    # The name only helps a reader of the directory: any character but a word's is dropped.
    stem = "".join(c for c in name if c.isalnum() or c == "_") or "table"
    extension = "eng" if eng else "csv"
    path = os.path.join(_files(), f"{stem}-{digest.hexdigest()[:32]}.{extension}")
    if not os.path.exists(path):
        # A RASP header: the name, then diameter, length, delays, masses and maker, which
        # the run does not read.
        lines = [f"{stem} 0 0 0 0 0 varmass" if eng else f"argument,{name}"]
        separator = " " if eng else ","
        lines += [f"{a!r}{separator}{b!r}" for a, b in zip(x.tolist(), y.tolist())]
        # Written whole under another name, then renamed: a reader never sees half a file.
        partial = f"{path}.{os.getpid()}.partial"
        with open(partial, "w", encoding="utf-8") as f:
            f.write("\n".join(lines) + "\n")
        os.replace(partial, path)
    return path


def data(argument: str, name: str, given, *, eng: bool = False) -> str:
    """The file the tool reads for ``given``: a path (``str`` or ``os.PathLike``) as given,
    or arrays written to a CSV file (a RASP ``.eng`` file with ``eng``)."""
    if isinstance(given, (str, os.PathLike)):
        return os.fspath(given)
    if isinstance(given, (tuple, list)):
        x, y = arrays(argument, given)
        return csv_file(name, x, y, eng=eng)
    raise TypeError(
        f"{argument} must be a path (str or os.PathLike) or a pair (arguments, values) of "
        f"arrays, not {type(given).__name__}"
    )


def table_options(tables: Optional[Mapping], motors: Iterable[str] = ()) -> List[Tuple[str, str]]:
    """(name, file) pairs, as ``--table NAME=FILE`` takes them, for ``tables`` ({name: path
    or (x, y)}); the arrays of a table in ``motors`` (declared from a RASP ``.eng`` file)
    are written as one, so that they start from (0 s, 0 N) as the declared file's curve
    does."""
    if tables is None:
        return []
    if not isinstance(tables, Mapping):
        raise TypeError(
            f"tables must be a mapping of table names to files or (arguments, values), "
            f"not {type(tables).__name__}"
        )
    options = []
    for name, given in tables.items():
        if not isinstance(name, str):
            raise TypeError(f"tables names must be strings, not {type(name).__name__}")
        if "=" in name:
            # The tool would split `F=x=path` at its first `=` and read the file `x=path`.
            raise ValueError(f"tables: {name!r} is not a table name (a name has no `=`)")
        stripped = name.strip()
        options.append((name, data(f"tables[{name!r}]", stripped, given, eng=stripped in motors)))
    return options


def portable(given, *, laws: bool = False):
    """``given`` ({name: path or (x, y)}, or with ``laws`` also a DSL expression) for
    another process: each path made absolute (a worker's current directory may differ),
    arrays and laws kept (each process writes its own file); anything else as it is, for
    the checks to refuse."""
    if not isinstance(given, Mapping):
        return given
    out = {}
    for name, value in given.items():
        is_law = laws and isinstance(value, str) and not is_file(value)
        if isinstance(value, (str, os.PathLike)) and not is_law:
            value = os.path.abspath(os.fspath(value))
        out[name] = value
    return out


def is_file(value: str) -> bool:
    """Whether an ``inputs`` string names a data file rather than a law (as the tool
    decides: by the extension, cli/src/run/input_tables.rs)."""
    return value.strip().lower().endswith((".csv", ".eng"))
