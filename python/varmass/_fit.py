"""``Model.fit``'s result (docs/sensitivities.md#fitting)."""

from typing import Dict, List

import numpy as np


class FitResult:
    """A fit of a model's parameters (and start values) to data, as ``varmass fit``
    reports it.

    ``values`` and ``errors`` map each fitted name to its value and standard error,
    ``correlation`` is their correlation matrix (in ``names`` order), ``residuals`` maps
    each data quantity to its weighted residuals (model − data)/σ, ``solution`` is the
    fitted run (its quantities and their derivatives at the data's times),
    ``evaluations`` the runs made and ``converged`` whether Levenberg–Marquardt converged.
    """

    def __init__(self, names, raw, quantities, solution):
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

    def __repr__(self) -> str:
        state = "converged" if self.converged else "did NOT converge"
        fitted = ", ".join(f"{n} = {self.values[n]:.6g} ± {self.errors[n]:.2g}" for n in self.names)
        return f"<varmass.FitResult ({state}, {self.evaluations} runs): {fitted}>"
