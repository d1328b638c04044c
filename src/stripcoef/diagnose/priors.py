"""The calibration's priors: how far each coefficient of the prior model may move.

The widths of the Gaussian priors of a vehicle file (:class:`PriorWidths`): how far a real
vehicle is from the model of its file, measured (:func:`vehicle_mismatch`,
``data/vehicle_mismatch.csv``), with the method table's band of its shape class as the
floor; the fixed :data:`~stripcoef.diagnose.settings.BANDS` for a model file; and the
plausible range of an added mass (:func:`added_mass_bounds`).

Depends on: study (the method table), geometry, files, errors.
"""

from __future__ import annotations

import csv
from collections.abc import Mapping
from dataclasses import dataclass
from functools import lru_cache
from importlib import resources

import numpy as np

from stripcoef.diagnose.settings import ADDED_MASS_FACTOR
from stripcoef.errors import InputError

__all__ = ["ADDED_MASS_BAND_Z", "KIND_GROUP", "TERM_MATRIX", "PriorWidths", "added_mass_bounds",
           "load_prior", "method_added_mass_sd", "method_prior_widths",
           "prior_added_mass_sd", "prior_widths", "vehicle_mismatch"]


#: Half-width of the method uncertainty band of the added mass, in standard deviations [-]:
#: :math:`\pm 3\sigma` holds 99.73 % of a normal distribution (two-sided), the band a
#: calibrated added mass is clipped to when the prior's method uncertainty is known
#: (:func:`method_added_mass_sd`; issue 19: the study's bands as the diagnosis's priors).
ADDED_MASS_BAND_Z = 3.0


def added_mass_bounds(dof: int, prior: float, sd: float | None = None) -> tuple[float, float]:
    r"""(lower, upper) plausible added mass of DOF ``dof`` [kg or kg m^2].

    :data:`ADDED_MASS_FACTOR` times the prior's value, intersected, when the 1-sigma method
    uncertainty ``sd`` of the prior's added mass is known (sd of :math:`\ln M_{ii}` [-], the
    lognormal rows of :mod:`stripcoef.study.sources`), with its 99.7 % band

    .. math:: |M_{ii}|\, e^{-z\sigma} \le M'_{ii} \le |M_{ii}|\, e^{z\sigma},
              \quad z = 3

    (``ADDED_MASS_BAND_Z``)."""
    lo, hi = ADDED_MASS_FACTOR["translational" if dof < 3 else "rotational"]
    lo, hi = lo * abs(prior), hi * abs(prior)
    if sd is not None and np.isfinite(sd) and sd > 0:
        lo = max(lo, float(np.exp(-ADDED_MASS_BAND_Z * float(sd))) * abs(prior))
        hi = min(hi, float(np.exp(ADDED_MASS_BAND_Z * float(sd))) * abs(prior))
    return lo, hi


@lru_cache(maxsize=1)
def vehicle_mismatch() -> dict:
    r"""``{kind: {term: (sd, source text)}}``: how far a real vehicle's identified
    coefficients are from those predicted from its geometry, the sd of
    :math:`\ln(c_{identified} / c_{predicted})` [-] per coefficient family (term ``M``,
    ``D_L``, ``D_Q``) and DOF group (kind ``translational``, ``rotational``), from
    ``data/vehicle_mismatch.csv`` (``python -m scripts.make_vehicle_mismatch``: VideoRay
    Pro III, Wang & Clark 2006 Table I, and ROV II, Eng et al. 2009 Tables III-IV; the root
    mean square of the log ratios of 3-9 coefficients of 2 vehicles per family)."""
    text = resources.files("stripcoef.data").joinpath("vehicle_mismatch.csv").read_text()
    out: dict = {}
    for row in csv.DictReader(line for line in text.splitlines() if not line.startswith("#")):
        out.setdefault(row["group"], {})[row["term"]] = (
            float(row["sd"]), f"vehicle mismatch ({row['basis']}, {row['n_rows']} "
                              f"coefficients of {row['n_vehicles']} vehicles): {row['source']}")
    return out


#: The method-table matrix of each calibrated term (:mod:`stripcoef.study.sources`).
TERM_MATRIX = {"M": "added_mass", "D_L": "linear_damping", "D_Q": "quadratic_damping"}
#: The method-table DOF group of each band kind.
KIND_GROUP = {"translational": "translation", "rotational": "rotation"}


@dataclass(frozen=True)
class PriorWidths:
    r"""Widths of the calibration's Gaussian priors of a vehicle file (issues 19 and 33).

    Each width is the larger of the vehicle mismatch (:func:`vehicle_mismatch`: how far real
    vehicles' identified coefficients are from their geometric predictions, measured on the
    stored papers' vehicles) and the method band below, which is only the floor: the method
    band says how far the method is from the exact answer for the file's shape, not how far
    the vehicle is from its file (cables, payload, flooded volumes, missing parts; issue 33:
    a 2-3x added mass was out of reach of the method's +-1 %).

    The method table (``data/method_uncertainty.csv``, docs/uncertainty.md) gives, per shape
    class, matrix and DOF group, the sd :math:`\sigma` of :math:`\ln c` of a coefficient c:
    measured for the added mass (the ``panels`` rows when the model's added mass is the panel
    method's), measured for the translational quadratic damping of the classes with published
    3D body drag (revolution, bluff) and assumed for the others and for every rotation, and a
    placeholder for the linear damping
    (``not_predicted``: the method does not predict it, so its prior is very wide, 250 % at
    1 sigma). The calibration is additive (a correction :math:`\delta = c - c_0` to the
    prior value :math:`c_0`), so :math:`\sigma` is converted to an absolute sd at the prior
    value by the first-order (delta-method) relation
    :math:`d\ln c = dc / c`,

    .. math:: \delta \sim N\!\left(0, (\sigma\,|c_0|)^2\right)
              \quad [\text{units of } c],

    i.e. a relative band :math:`b = \sigma` [-] in the place of :data:`BANDS` (Tarantola 2005,
    eq. 3.37 for the Gaussian prior; the lognormal's sd of ln, :mod:`stripcoef.study.sources`).
    For :math:`\sigma \gtrsim 1` the lognormal is skewed and the Gaussian only approximates
    it (a wide prior, which is what such a row says); the bounds still apply (no negative
    drag; the added mass within :func:`added_mass_bounds`, its 99.7 % band).

    ``sd_ln``: ``{kind: {term: sigma}}`` (kind ``translational``/``rotational``, term
    ``M``/``D_L``/``D_Q``) [-]; ``rows``: ``{kind: {term: "CLASS MATRIX.GROUP: source
    text"}}``, the row each width came from (CLASS ``panels`` for a panel-method added mass;
    ``vehicle mismatch ...`` where the measured mismatch is the wider);
    ``shape_class``: the vehicle's geometric class; ``method_sd_ln``: the method table's
    widths alone (the floor), same form as ``sd_ln``.
    """

    shape_class: str
    sd_ln: Mapping
    rows: Mapping
    method_sd_ln: Mapping | None = None

    @property
    def bands(self) -> dict:
        """The widths in the form of :data:`BANDS` (relative 1-sigma) [-]."""
        return {k: dict(v) for k, v in self.sd_ln.items()}

    @property
    def added_mass_sd(self) -> np.ndarray:
        """(6,) sd of ln M_ii [-] (:func:`method_added_mass_sd`'s form)."""
        return np.array([self.sd_ln["translational" if i < 3 else "rotational"]["M"]
                         for i in range(6)], float)

    def to_dict(self) -> dict:
        return {"shape_class": self.shape_class,
                "sd_ln": {k: dict(v) for k, v in self.sd_ln.items()},
                "method_sd_ln": ({k: dict(v) for k, v in self.method_sd_ln.items()}
                                 if self.method_sd_ln is not None else None),
                "rows": {k: dict(v) for k, v in self.rows.items()},
                "description": "1-sigma widths of the calibration's Gaussian priors: the "
                               "larger of the measured vehicle mismatch (real vehicles' "
                               "identified coefficients against their geometric predictions, "
                               "data/vehicle_mismatch.csv) and the method table's band (the "
                               "floor); sd of ln c, applied as sd |c0| sigma at the prior "
                               "value c0"}


def method_prior_widths(vehicle, *, panels: bool | None = None,
                        mismatch: bool = True) -> PriorWidths:
    """:class:`PriorWidths` of a parsed vehicle: the rows of
    :func:`stripcoef.study.sources.method_sources` (its shape class; the ``panels`` rows for
    the added mass of a panel-method model: ``panels``, default what
    :func:`stripcoef.study.sources.uses_panels` says for the default options) as the floor
    of the measured :func:`vehicle_mismatch` (``mismatch=False``: the method rows alone)."""
    from stripcoef.study.sources import method_sources, shape_class

    found = {}
    for src in method_sources(vehicle, panels=panels):
        matrix, group = src.name.split(".")
        found[(matrix, group)] = src
    sd_ln, rows = {}, {}
    for kind, group in KIND_GROUP.items():
        sd_ln[kind], rows[kind] = {}, {}
        for term, matrix in TERM_MATRIX.items():
            src = found.get((matrix, group))
            if src is None or src.distribution != "lognormal":
                raise InputError("no lognormal method row", key=f"{matrix}.{group}",
                                 value=None if src is None else src.distribution,
                                 expected="a lognormal row of data/method_uncertainty.csv")
            cls, _, text = src.reason.partition(": ")
            sd_ln[kind][term] = float(src.spread)
            rows[kind][term] = f"{cls} {src.name}: {text}"
    method = {k: dict(v) for k, v in sd_ln.items()}
    if mismatch:
        table = vehicle_mismatch()
        for kind in sd_ln:
            for term in sd_ln[kind]:
                sd, text = table[kind][term]
                if sd > sd_ln[kind][term]:
                    rows[kind][term] = (f"{text} (wider than the method band "
                                        f"{sd_ln[kind][term]:g}: {rows[kind][term]})")
                    sd_ln[kind][term] = sd
    return PriorWidths(shape_class(vehicle), sd_ln, rows, method)



def method_added_mass_sd(vehicle) -> np.ndarray:
    """1-sigma method uncertainty of each DOF's added mass (6,), as the sd of its logarithm
    [-], for a parsed vehicle: the ``added_mass`` rows of its class (translations share one
    value, rotations another), read as :func:`method_prior_widths` reads them."""
    return method_prior_widths(vehicle).added_mass_sd


def prior_widths(path) -> PriorWidths | None:
    """:func:`method_prior_widths` when ``path`` is a vehicle file, None for a model file
    (it does not say which method or shape it came from: the fixed :data:`BANDS` apply)."""
    if not str(path).lower().endswith((".yaml", ".yml")):
        return None
    vehicle = _read_prior(path)[1]
    return None if vehicle is None else method_prior_widths(vehicle)


def load_prior(path):
    """``(model, widths)``: the prior :class:`~stripcoef.model.HydroModel` of a vehicle or
    model file (:func:`stripcoef.modelfile.load_model`) and its :func:`prior_widths`, from
    one reading of the file."""
    from stripcoef.assembly import estimate

    model, vehicle = _read_prior(path)
    if vehicle is None:
        return model, None
    return estimate(vehicle), method_prior_widths(vehicle)


def _read_prior(path):
    """``(model, None)`` for a model file, ``(None, vehicle)`` for a vehicle file (parsed),
    the file read once."""
    from stripcoef.files import load_yaml, read_text
    from stripcoef.geometry.vehicle import load_vehicle, parse_vehicle
    from stripcoef.modelfile import load_model, model_from_dict

    name = str(path)
    if not name.lower().endswith((".yaml", ".yml")):
        return load_model(path), None
    data = load_yaml(read_text(name, kind="vehicle or model file"), file=name)
    if isinstance(data, dict) and "added_mass" in data and "rigid_body_mass" in data:
        return model_from_dict(data, file=name), None
    if not isinstance(data, dict):
        return None, load_vehicle(path)      # its one-line error: not a mapping
    return None, parse_vehicle(data, file=name)


def prior_added_mass_sd(path):
    """``(sd, shape class)`` of :func:`method_added_mass_sd` when ``path`` is a vehicle file,
    ``(None, None)`` for a model file (it does not say which method or shape it came from)."""
    widths = prior_widths(path)
    return (None, None) if widths is None else (widths.added_mass_sd, widths.shape_class)

