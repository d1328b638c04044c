r"""Where each coefficient's uncertainty comes from: the method, and the vehicle file's inputs.

Two kinds of source, each a :class:`Source` with the text that justifies it:

- **method**: strip theory's error against references, measured per shape class
  (``data/method_uncertainty.csv``). It scales a whole matrix DOF by DOF with factors
  :math:`f_i` applied as a congruence,

  .. math:: M'_{ij} = M_{ij}\sqrt{f_i f_j},

  which keeps M_A symmetric and positive definite; :math:`f_i = e^{\sigma z}` (lognormal: every row of
  the table; the measured errors are multiplicative, up to factors of 100 for the rotations of
  bluff bodies, and every term must keep its sign) or :math:`1 + \sigma z` (normal), :math:`z \sim N(0,1)`,
  one factor per matrix and DOF group (translations share one, rotations another: the
  errors of one method on one body are correlated across its DOFs).
- **input**: a value declared uncertain in the vehicle file (``{value, sd}`` normal,
  ``{value, tol}`` uniform; :mod:`stripcoef.geometry.keypaths`).
"""

from __future__ import annotations

import csv
from dataclasses import dataclass
from functools import lru_cache
from importlib import resources

import numpy as np

from stripcoef.errors import InputError
from stripcoef.geometry.keypaths import UncertainValue

MATRICES = ("added_mass", "linear_damping", "quadratic_damping")
GROUPS = {"translation": (0, 1, 2), "rotation": (3, 4, 5)}


@dataclass(frozen=True)
class Source:
    """One independent source of uncertainty (one dimension of the sampling).

    ``kind``: ``"method"`` or ``"input"``; ``name``: ``added_mass.rotation`` or a key path;
    ``distribution``: normal, lognormal or uniform; ``spread``: sigma (relative for method
    normal, of ln for lognormal, absolute for inputs) or the uniform half-width;
    ``nominal``: the input's nominal value (1.0 for method factors).
    """

    kind: str
    name: str
    distribution: str
    spread: float
    nominal: float
    reason: str

    def draw(self, u: np.ndarray) -> np.ndarray:
        """Values from uniform draws ``u`` in (0, 1) by the inverse CDF."""
        from scipy.stats import norm

        u = np.clip(np.asarray(u, dtype=float), 1e-12, 1.0 - 1e-12)
        if self.distribution == "uniform":
            return self.nominal + self.spread * (2.0 * u - 1.0)
        z = norm.ppf(u)
        if self.distribution == "lognormal":
            return self.nominal * np.exp(self.spread * z)
        if self.kind == "method":
            return self.nominal * (1.0 + self.spread * z)
        return self.nominal + self.spread * z

    def to_dict(self) -> dict:
        return {"kind": self.kind, "name": self.name, "distribution": self.distribution,
                "spread": self.spread, "nominal": self.nominal, "reason": self.reason}


@lru_cache(maxsize=None)
def _method_table() -> tuple:
    text = resources.files("stripcoef.data").joinpath("method_uncertainty.csv").read_text()
    rows = csv.DictReader(line for line in text.splitlines() if not line.startswith("#"))
    return tuple(dict(r) for r in rows)


def shape_class(vehicle) -> str:
    """``revolution``, ``finned``, ``bluff`` or ``open_frame``, from the vehicle's geometry
    (:func:`stripcoef.study.shapes.shape_class`: the documented rule)."""
    from stripcoef.study.shapes import shape_class as by_geometry

    return by_geometry(vehicle)


def method_sources(vehicle) -> list[Source]:
    """The method rows of ``vehicle``'s shape class, one Source per matrix and DOF group."""
    cls = shape_class(vehicle)
    out = []
    for row in _method_table():
        if row["class"] != cls or row["dofs"] not in GROUPS:
            continue            # couplings are measured and listed, not sampled
        out.append(Source("method", f"{row['matrix']}.{row['dofs']}", row["distribution"],
                          float(row["sd"]), 1.0, f"{cls}: {row['source']}"))
    return out


def input_sources(declared: list[UncertainValue]) -> list[Source]:
    """One Source per value the vehicle file declares uncertain."""
    return [Source("input", u.path, u.kind, u.spread, u.value,
                   f"declared in the vehicle file ({'sd' if u.kind == 'normal' else 'tol'} "
                   f"{u.spread:g})") for u in declared]


def method_factors(sources: list[Source], values) -> dict:
    """{matrix: (6,) DOF factors} from the method sources' sampled values."""
    factors = {m: np.ones(6) for m in MATRICES}
    for s, v in zip(sources, values):
        if s.kind != "method":
            continue
        matrix, group = s.name.split(".")
        if matrix not in factors or group not in GROUPS:
            raise InputError("unknown method source", key=s.name,
                             expected=f"MATRIX.GROUP with MATRIX in {MATRICES}")
        factors[matrix][list(GROUPS[group])] = v
    return factors


def scale_matrix(matrix, factors) -> np.ndarray:
    r""":math:`M'_{ij} = M_{ij}\sqrt{f_i f_j}` (a congruence: symmetry and definiteness kept)."""
    f = np.sqrt(np.clip(np.asarray(factors, dtype=float), 0.0, None))
    return np.asarray(matrix, dtype=float) * np.outer(f, f)
