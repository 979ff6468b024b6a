"""Ensembles from Python on the core's ensemble: sampled parameters per member, runs with
the tool's semantics, observables at each run's end, exact merges of shards."""

from __future__ import annotations

import numbers
from typing import Dict, List, NamedTuple, Optional, Sequence, Tuple

import numpy as np

from . import _checks, _native, _tables
from ._solution import column

DEFAULT_QUANTILES = (0.05, 0.25, 0.5, 0.75, 0.95)


class Distribution(NamedTuple):
    """A sampled parameter's distribution: ``uniform(low, high)`` or ``normal(mean, sd)``."""

    kind: str
    a: float
    b: float


def uniform(low, high) -> Distribution:
    """Uniform on [low, high)."""
    low = _checks.number("uniform low", low)
    high = _checks.number("uniform high", high)
    if not low < high:
        raise ValueError(f"uniform({low}, {high}): low must be below high")
    return Distribution("uniform", low, high)


def normal(mean, sd) -> Distribution:
    """Normal with this mean and standard deviation."""
    mean = _checks.number("normal mean", mean)
    sd = _checks.number("normal sd", sd)
    if sd < 0.0:
        raise ValueError(f"normal({mean}, {sd}): the standard deviation must be ≥ 0")
    return Distribution("normal", mean, sd)


class Failure(NamedTuple):
    """A member that failed: its index, its sampled parameters and the tool's message."""

    index: int
    parameters: Dict[str, float]
    message: str


def _seed(seed) -> int:
    if isinstance(seed, bool) or not isinstance(seed, numbers.Integral):
        raise TypeError(f"seed must be an integer, not {type(seed).__name__}")
    if not 0 <= int(seed) < 2**64:
        raise ValueError(f"seed must be in 0 .. 2**64 - 1, not {seed}")
    return int(seed)


def _count(argument: str, value, *, minimum: int = 0) -> int:
    if isinstance(value, bool) or not isinstance(value, numbers.Integral):
        raise TypeError(f"{argument} must be an integer, not {type(value).__name__}")
    if not minimum <= int(value) < 2**64:
        raise ValueError(f"{argument} must be at least {minimum}, not {value}")
    return int(value)


def _threads(threads) -> Optional[int]:
    return None if threads is None else _count("threads", threads, minimum=1)


class Ensemble:
    """Many runs of one model, member ``i``'s sampled parameters drawn from its own random
    stream (ChaCha8 keyed by ``seed``, stream ``i``) in the order ``sample`` lists them.

    Each member runs as ``model.run`` would with ``set`` and its sampled values, and
    reports ``observables`` at the end of its run (``"t"`` or any quantity ``record``
    takes, e.g. ``"y"``, ``"y'"``, ``"m"``, ``"H"``; ``"MU=mu"`` is named ``MU``, as
    ``record`` names it). ``inputs`` and ``tables`` are
    ``Model.run``'s: laws, data files or arrays, the same for every member. Results are
    bit-identical for any thread count, any split into shards and any merge order. An
    ensemble pickles (its specification, with the arrays of ``tables``/``inputs`` and their
    paths made absolute), so it can be sent to Dask workers; a path must be readable there.
    """

    def __init__(
        self,
        model,
        seed,
        *,
        sample,
        observables,
        until=None,
        set=None,
        init=None,
        from_=0.0,
        stop_when=None,
        method="dormand-prince",
        tol=None,
        step=None,
        inputs=None,
        tables=None,
    ):
        if not isinstance(sample, dict):
            raise TypeError(
                "sample must be a dict of parameter names to varmass.uniform(...) or "
                f"varmass.normal(...), not {type(sample).__name__}"
            )
        for key, distribution in sample.items():
            _checks.name("sample", key)
            if not isinstance(distribution, Distribution):
                raise TypeError(
                    f"sample[{key!r}] must be varmass.uniform(...) or varmass.normal(...), "
                    f"not {type(distribution).__name__}"
                )
        fixed = _checks.values("set", set)
        _checks.no_duplicates("set", fixed)
        both = sorted({k for k, _ in fixed} & {k for k in sample})
        if both:
            raise ValueError(f"set and sample both give {', '.join(both)}: give each once")
        self.model = model
        self.seed = _seed(seed)
        self.sample: Dict[str, Distribution] = dict(sample)
        self.observables: List[str] = _checks.names("observables", observables)
        self._fixed = fixed
        # The run's keywords, those of inputs and tables as another process reads them
        # (paths made absolute, arrays kept): each process makes their options, writing
        # arrays to its own files.
        options = _checks.run_keywords(locals())
        options["inputs"] = _tables.portable(inputs, laws=True)
        options["tables"] = _tables.portable(tables)
        self._options = options
        self._native = None
        self._build()

    def _build(self):
        options = _checks.run_options(self._options, self.model._facts["motors"])
        self._native = _native.NativeEnsemble(
            self.seed,
            self.model._native(),
            self.model._file,
            self.model._with,
            self._fixed,
            [(k, d.kind, d.a, d.b) for k, d in self.sample.items()],
            options,
            self.observables,
        )

    def __getstate__(self):
        state = dict(self.__dict__)
        state["_native"] = None
        return state

    def __setstate__(self, state):
        self.__dict__.update(state)
        self._build()

    def run(self, n, threads=None) -> "EnsembleResult":
        """Runs members 0 .. n-1 (on all cores, or ``threads`` threads); the GIL is
        released while they run."""
        n = _count("n", n)
        return self._result(self._native.run(0, n, _threads(threads)))

    def run_shard(self, i, n_shards, total, threads=None) -> "EnsembleResult":
        """Runs shard ``i`` of ``n_shards`` of an ensemble of ``total`` members (the
        members ``i*total//n_shards`` up to ``(i+1)*total//n_shards``)."""
        start, end = _native.NativeEnsemble.shard_members(
            _count("i", i), _count("n_shards", n_shards, minimum=1), _count("total", total)
        )
        return self._result(self._native.run(start, end, _threads(threads)))

    def member(self, index):
        """Member ``index`` alone: its sampled parameters (dict) and its observables (dict),
        as in any run of the ensemble; a member that fails raises its RunError."""
        params, values = self._native.member(_count("index", index))
        return dict(zip(self.sample, params)), dict(zip(self._native.columns, values))

    def _result(self, native) -> "EnsembleResult":
        return EnsembleResult(native, list(self.sample))

    def __repr__(self) -> str:
        return (
            f"<varmass.Ensemble of {self.model.name}: seed {self.seed}, "
            f"sample {list(self.sample)}, observables {self.observables}>"
        )



class EnsembleResult:
    """Observables and failures of some members of an ensemble (the core's ``Partial``).

    ``result["apex"]`` or ``result.values("apex")``: the completed members' values in
    member-index order (NumPy); ``result.completed``: their indices; ``result.failures``:
    each failed member's index, sampled parameters and message; ``result.summary(name)``:
    count, mean, standard deviation, extremes, quantiles and a confidence interval of the
    mean. ``a.merge(b)`` joins results of disjoint members exactly (any order gives the
    same bits); ``==`` compares them bit for bit. Results pickle (JSON that keeps every
    value's bits), so they come back from Dask workers unchanged.
    """

    def __init__(self, native, sampled: Sequence[str]):
        self._native = native
        self._sampled = list(sampled)

    @property
    def seed(self) -> int:
        return self._native.seed

    @property
    def observables(self) -> List[str]:
        return list(self._native.observables)

    @property
    def member_count(self) -> int:
        """Members run, completed or failed."""
        return self._native.member_count

    @property
    def covered(self) -> List[Tuple[int, int]]:
        """The members run, as sorted ranges (start, end)."""
        return list(self._native.covered)

    @property
    def completed(self) -> np.ndarray:
        return np.frombuffer(self._native.completed(), dtype="<u8")

    def values(self, name: str) -> np.ndarray:
        if name not in self.observables:
            raise KeyError(f"{name!r} is not an observable; they are {self.observables}")
        return column(self._native.values(self.observables.index(name)))

    __getitem__ = values

    @property
    def failures(self) -> List[Failure]:
        return [
            Failure(index, dict(zip(self._sampled, params)), message)
            for index, params, message in self._native.failures()
        ]

    def summary(self, name: str, quantiles=DEFAULT_QUANTILES, confidence=0.95) -> dict:
        """The core's statistics of observable ``name``, from its values in index order."""
        if name not in self.observables:
            raise KeyError(f"{name!r} is not an observable; they are {self.observables}")
        qs = [_checks.number("quantiles", q) for q in quantiles]
        return dict(self._native.summary(name, qs, _checks.number("confidence", confidence)))

    def merge(self, other: "EnsembleResult") -> "EnsembleResult":
        """The result of the members of both (exact; refuses shared members or another
        seed with a ValueError)."""
        if not isinstance(other, EnsembleResult):
            raise TypeError(f"merge takes an EnsembleResult, not {type(other).__name__}")
        return EnsembleResult(self._native.merge(other._native), self._sampled)

    def to_json(self) -> str:
        return self._native.to_json()

    @classmethod
    def from_json(cls, text: str, sampled: Sequence[str] = ()) -> "EnsembleResult":
        return cls(_native.NativePartial.from_json(text), sampled)

    def __reduce__(self):
        return (EnsembleResult.from_json, (self.to_json(), self._sampled))

    def __eq__(self, other) -> bool:
        return isinstance(other, EnsembleResult) and self._native == other._native

    __hash__ = None  # compared by content (==), so not hashable

    def to_pandas(self):
        """A DataFrame indexed by member, one column per observable (needs pandas)."""
        import pandas as pd

        frame = pd.DataFrame({n: self.values(n) for n in self.observables})
        frame.index = pd.Index(self.completed, name="member")
        return frame

    def __repr__(self) -> str:
        return (
            f"<varmass.EnsembleResult: {self.member_count} members "
            f"({len(self._native.failures())} failed), seed {self.seed}, "
            f"observables {self.observables}>"
        )
