"""``Model.fit``'s result (docs/sensitivities.md#fitting), and its prediction."""

from typing import Dict, List, Optional

import numpy as np


class Prediction:
    """The fitted run on to a condition (``fit(..., predict="z' < 0")``), as ``varmass fit
    --predict`` prints it: each value with its standard error √(gᵀΣg), Σ the fitted
    unknowns' covariance and g their derivatives at the event
    (docs/sensitivities.md#fitting).

    ``condition`` is the condition that ended the run; ``t`` and ``t_error`` the event's
    time (the model's clock) and its error; ``clock`` and ``clock_error`` its time on the
    data's clock, t + δ, and its error when ``"data:offset"`` is fitted (else ``None``);
    ``values`` and ``errors`` map each data quantity to its value and error at the event
    (``prediction.values["z"]``, ``prediction.errors["z"]``), in the data's order.
    """

    def __init__(self, raw):
        condition, time, clock, quantities = raw
        self.condition: str = condition
        self.t: float = time[0]
        self.t_error: float = time[1]
        self.clock: Optional[float] = None if clock is None else clock[0]
        self.clock_error: Optional[float] = None if clock is None else clock[1]
        self.values: Dict[str, float] = {q: v for q, v, _ in quantities}
        self.errors: Dict[str, float] = {q: e for q, _, e in quantities}

    def __repr__(self) -> str:
        shown = [f"t = {self.t:.6g} ± {self.t_error:.2g}"]
        if self.clock is not None:
            shown.append(f"clock {self.clock:.6g} ± {self.clock_error:.2g}")
        shown += [f"{q} = {v:.6g} ± {self.errors[q]:.2g}" for q, v in self.values.items()]
        return f"<varmass.Prediction where {self.condition!r}: {', '.join(shown)}>"


class FitResult:
    """A fit of a model's parameters (and start values) to data, as ``varmass fit``
    reports it.

    ``values`` and ``errors`` map each fitted name to its value and standard error,
    ``correlation`` is their correlation matrix (in ``names`` order), ``residuals`` maps
    each data quantity to its weighted residuals (model − data)/σ, ``solution`` is the
    fitted run (its quantities and their derivatives at the data's times),
    ``evaluations`` the runs made and ``converged`` whether Levenberg–Marquardt converged.
    ``prediction`` is the :class:`Prediction` that ``fit(..., predict=...)`` asked, or
    ``None`` without one.
    """

    def __init__(self, names, raw, quantities, solution, prediction=None):
        values, errors, correlation, residuals, evaluations, converged = raw
        self.names: List[str] = list(names)
        self.values: Dict[str, float] = dict(zip(names, values))
        self.errors: Dict[str, float] = dict(zip(names, errors))
        self.correlation: np.ndarray = np.array(correlation, dtype=float)
        self.residuals: Dict[str, np.ndarray] = {
            q: np.array(r, dtype=float) for q, r in zip(quantities, residuals)
        }
        self.evaluations: int = evaluations
        self.converged: bool = converged
        self.solution = solution
        self.prediction: Optional[Prediction] = prediction

    def __repr__(self) -> str:
        state = "converged" if self.converged else "did NOT converge"
        fitted = ", ".join(f"{n} = {self.values[n]:.6g} ± {self.errors[n]:.2g}" for n in self.names)
        return f"<varmass.FitResult ({state}, {self.evaluations} runs): {fitted}>"
