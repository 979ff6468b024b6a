"""varmass from Python: variable-mass models derived, checked, shown and run, and
ensembles of runs on all cores or on a Dask cluster.

>>> import varmass
>>> sled = varmass.Model.from_file("models/sled.vms", with_=["impact"])   # doctest: +SKIP
>>> sol = sled.run(set={"m0": 10, "c": 2, "g": 9.81, "theta": 0.5236, "f_d": 0.1},
...                init={"x": 0}, until=100, stop_when="x = 50")           # doctest: +SKIP
>>> sol.t[-1], sol["x'"][-1]                                              # doctest: +SKIP

A run has the ``varmass run`` command line tool's semantics and messages: it is the same
code (the run-time interpreter and the core's steppers), reached without a process or CSV.
"""

from ._checks import METHODS
from ._ensemble import Distribution, Ensemble, EnsembleResult, Failure, normal, uniform
from ._errors import Diagnostic, ModelError, ModelWarning, RunError, VarmassError
from ._fit import FitResult, Prediction
from ._model import Check, Model
from ._scene import PhaseChange, Scene, run_scene
from ._solution import Solution

__all__ = [
    "METHODS",
    "Check",
    "Diagnostic",
    "Distribution",
    "Ensemble",
    "EnsembleResult",
    "Failure",
    "FitResult",
    "Model",
    "ModelError",
    "ModelWarning",
    "PhaseChange",
    "Prediction",
    "RunError",
    "Scene",
    "Solution",
    "VarmassError",
    "normal",
    "run_scene",
    "uniform",
]
