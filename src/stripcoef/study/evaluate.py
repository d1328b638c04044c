"""One evaluation of a study: vehicle-file data (with some values changed) -> numbers.

A :class:`Job` holds what every evaluation shares (the nominal data, the key paths that vary,
the method sources, whether to solve the limits); :func:`evaluate_batch` evaluates rows of
values for those paths and sources. Both are picklable, so a batch runs the same in this
process, in a worker process or on a Dask worker.

Outputs are flat ``name -> float``: every SNAME coefficient of the model
(:meth:`HydroModel.coefficients`; a term the model rounds to zero is 0.0), the mass, and with
limits ``surge_speed_max`` [m/s], ``heave_speed_max`` [m/s], ``yaw_rate_max`` [rad/s],
``sway_speed_max`` [m/s], ``min_turning_radius`` [m] and ``u_max@R=<radius>`` [m/s] for each
turning radius (NaN where the manoeuvre is unreachable). With limits, the one text output
``limits_note`` says why a limit is blank (the solver's notes, or its refusal; empty when
every limit was found), so that a sweep never leaves a point blank without a reason.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, replace

import numpy as np

from stripcoef.errors import StripcoefError


@dataclass(frozen=True)
class Job:
    """What every evaluation of one study shares.

    ``data``: the vehicle file's nominal mapping; ``file``: its name (for errors);
    ``paths``: key paths whose values each row sets (inputs); ``sources``: the method sources
    whose factors each row carries after the inputs; ``limits``: solve the manoeuvre limits;
    ``radii``: turning radii for the limits [m]; ``strips``: strip count (None: the file's);
    ``mirrors``: the nominal body's mirror symmetries (``x``, ``y``, ``z``:
    :func:`stripcoef.assembly.symmetry.mirror_symmetries`), which decide the couplings the method
    source moves (None: none known, every coupling moves); ``model``: the model of ``data``
    when no path varies (``paths`` empty), every row's model before its method factors, solved
    once instead of once a row (None: each row solves its own; the estimate is deterministic,
    so the numbers are the same).
    """

    data: dict
    file: str
    paths: tuple = ()
    sources: tuple = ()
    limits: bool = True
    radii: tuple = (0.5, 1.0, 2.0, 5.0, 10.0, 20.0)
    strips: int | None = None
    mirrors: frozenset | None = None
    model: object = None


#: The text output that says why a limit of a point is blank (empty: none is).
NOTE = "limits_note"


def _limits_outputs(model, radii) -> dict:
    from stripcoef.limits.solver import solve_limits

    out = {"surge_speed_max": math.nan, "heave_speed_max": math.nan, "yaw_rate_max": math.nan,
           "sway_speed_max": math.nan, "min_turning_radius": math.nan}
    out.update({f"u_max@R={r:g}": math.nan for r in radii})
    try:
        res = solve_limits(model, radii=np.asarray(radii, dtype=float))
    except StripcoefError as exc:
        out[NOTE] = f"limits not solved: {exc}"
        return out
    for key in ("surge_speed_max", "heave_speed_max", "yaw_rate_max", "sway_speed_max"):
        v = getattr(res, key)
        out[key] = math.nan if v is None else float(v)
    if res.min_turning_radius is not None:
        out["min_turning_radius"] = float(res.min_turning_radius)
    for t in res.turning:
        out[f"u_max@R={t.radius:g}"] = float(t.u_max)
    blank = [k for k, v in out.items() if isinstance(v, float) and math.isnan(v)]
    why = f" (the solver's notes: {'; '.join(res.notes)})" if res.notes else ""
    out[NOTE] = f"blank: {', '.join(blank)}{why}" if blank else ""
    return out


def evaluate(job: Job, row) -> dict:
    """The outputs for one row of values (inputs in ``job.paths`` order, then method factors)."""
    from stripcoef.assembly import estimate
    from stripcoef.geometry.keypaths import set_value
    from stripcoef.geometry.vehicle import parse_vehicle
    from stripcoef.study.sources import couple, method_couplings, method_factors, scale_matrix
    from stripcoef.assembly.fin_munk import scaled
    from stripcoef.assembly.symmetry import allowed_couplings

    row = [float(v) for v in row]
    n_in = len(job.paths)
    data = job.data
    for path, value in zip(job.paths, row[:n_in]):
        data = set_value(data, path, value, file=job.file)
    if job.model is not None and not n_in:
        model = job.model                        # no input varies: the one nominal model
    else:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")      # the nominal run already showed them
            model = estimate(parse_vehicle(data, file=job.file), strips=job.strips)
    if job.sources:
        f = method_factors(list(job.sources), row[n_in:])
        c = method_couplings(list(job.sources), row[n_in:])
        allowed = None if job.mirrors is None else allowed_couplings(job.mirrors)
        model = replace(model, added_mass=couple(scale_matrix(model.added_mass, f["added_mass"]),
                                                 c["added_mass"], allowed),
                        linear_damping=scale_matrix(model.linear_damping, f["linear_damping"]),
                        quadratic_damping=scale_matrix(model.quadratic_damping,
                                                       f["quadratic_damping"]),
                        lift=np.asarray(model.lift, float) * f["lift"][0],
                        # the fins' Munk compensation follows M_A, not the lift factor
                        fin_munk_lift=scaled(model.fin_munk_lift, f["added_mass"]),
                        control_surfaces=tuple(replace(cs, derivative=np.asarray(
                            cs.derivative, float) * f["control"][0])
                            for cs in model.control_surfaces))
    out = {k: float(v) for k, v in model.coefficients().items()}
    out["mass"] = float(model.mass)
    if job.limits:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            out.update(_limits_outputs(model, job.radii))
    return out


def evaluate_batch(args) -> list[dict]:
    """``(job, rows)`` -> the outputs of each row, in order (the unit of parallel work)."""
    job, rows = args
    return [evaluate(job, row) for row in rows]


def table(results: list[dict]) -> tuple[list[str], np.ndarray]:
    """Column names (first-seen order) and a (rows, columns) array of the numeric outputs; a
    missing term is 0.0. Text outputs (``limits_note``) are left out: :func:`notes` reads them."""
    names: dict[str, None] = {}
    for r in results:
        for k, v in r.items():
            if not isinstance(v, str):
                names.setdefault(k, None)
    cols = list(names)
    arr = np.array([[r.get(c, 0.0) for c in cols] for r in results], dtype=float)
    return cols, arr


def notes(results: list[dict]) -> list[str] | None:
    """Each result's ``limits_note`` (None when the evaluations solved no limits)."""
    if not any(NOTE in r for r in results):
        return None
    return [r.get(NOTE, "") for r in results]
