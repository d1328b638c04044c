r"""How sure is the model? Monte Carlo propagation of every stated uncertainty.

The sources (:mod:`stripcoef.study.sources`): strip theory's method error per shape class,
and the values the vehicle file declares uncertain. Each of the d sources is one dimension of
a scrambled Sobol sequence (Owen scrambling, seeded: :class:`scipy.stats.qmc.Sobol`), mapped
to its distribution by the inverse CDF; every sample is evaluated by
:func:`stripcoef.study.evaluate.evaluate` (the whole pipeline: vehicle file -> model ->
limits). The result gives, for every coefficient and limit, the nominal value, the sample mean
and standard deviation and the percentiles 2.5, 5, 50, 95, 97.5 (a 95 % band is
[P2.5, P97.5]).

Quasi-Monte Carlo converges like O((log N)^d / N) instead of O(N^-1/2) for smooth outputs
(Owen 1997, "Scrambled net variance for integrals of smooth functions", Ann. Statist. 25;
Sobol' 1967); percentiles are the empirical ones (linear interpolation, numpy default).
Samples are evaluated in batches by :func:`stripcoef.study.runner.run_batches`: locally or on
a Dask cluster, with the same numbers.
"""

from __future__ import annotations

import math
import warnings
from dataclasses import dataclass, field

import numpy as np

from stripcoef.errors import InputError

PERCENTILES = (2.5, 5.0, 50.0, 95.0, 97.5)
#: Samples per batch of parallel work (a batch pickles the vehicle data once).
BATCH = 8


@dataclass(frozen=True)
class UncertaintyResult:
    """Percentiles of every output. ``names``: output names; ``samples``: (N, outputs);
    ``nominal``: the outputs of the nominal model; ``sources``: the Source list;
    ``draws``: (N, sources) sampled source values."""

    vehicle: str
    names: tuple
    samples: np.ndarray
    nominal: dict
    sources: tuple
    draws: np.ndarray
    seed: int
    shape_class: str
    notes: tuple = field(default_factory=tuple)

    def column(self, name: str) -> np.ndarray:
        return self.samples[:, self.names.index(name)]

    def summary(self) -> dict:
        """name -> {nominal, mean, sd, p2.5, p5, p50, p95, p97.5} (NaN-free samples only)."""
        out = {}
        for j, name in enumerate(self.names):
            col = self.samples[:, j]
            ok = col[np.isfinite(col)]
            entry = {"nominal": self.nominal.get(name, 0.0)}
            if ok.size:
                entry.update({"mean": float(ok.mean()),
                              "sd": float(ok.std(ddof=1)) if ok.size > 1 else 0.0})
                for p, v in zip(PERCENTILES, np.percentile(ok, PERCENTILES)):
                    entry[f"p{p:g}"] = float(v)
            entry["unreachable_fraction"] = float(1.0 - ok.size / col.size) if col.size else 0.0
            out[name] = entry
        return out

    def to_dict(self) -> dict:
        """The JSON contract of ``stripcoef uncertainty --json`` (strict JSON: null for NaN)."""
        def clean(v):
            if isinstance(v, dict):
                return {k: clean(x) for k, x in v.items()}
            if isinstance(v, float) and not math.isfinite(v):
                return None
            return v

        return clean({"vehicle": self.vehicle, "samples": int(self.samples.shape[0]),
                      "seed": self.seed, "shape_class": self.shape_class,
                      "sampling": "scrambled Sobol (scipy.stats.qmc), inverse-CDF transform",
                      "sources": [s.to_dict() for s in self.sources],
                      "outputs": self.summary(), "notes": list(self.notes)})


def _draws(sources, n: int, seed: int) -> np.ndarray:
    """(n, d) source values from a scrambled Sobol sequence."""
    from scipy.stats import qmc

    d = len(sources)
    if d == 0:
        return np.zeros((n, 0))
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")          # balance warning when n is not a power of 2
        u = qmc.Sobol(d, scramble=True, seed=seed).random(n)
    return np.column_stack([s.draw(u[:, k]) for k, s in enumerate(sources)])


def _nominal_model(vehicle, strips):
    """The nominal vehicle's model, warnings hidden (the nominal evaluation shows them): its
    reference point sets the mirror symmetries the method's couplings follow
    (:func:`stripcoef.assembly.symmetry.mirror_symmetries`), its lift whether the lift rows are
    sampled."""

    from stripcoef.assembly import estimate

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return estimate(vehicle, strips=strips)


def uncertainty(vehicle, *, samples: int = 256, seed: int = 0, limits: bool = True,
                method: bool = True, radii=(0.5, 1.0, 2.0, 5.0, 10.0, 20.0),
                strips: int | None = None, workers: int | None = None, scheduler=None,
                progress: bool | None = None) -> UncertaintyResult:
    """Monte Carlo study of a vehicle file's model and limits.

    Parameters
    ----------
    vehicle : str or Path
        A vehicle file (YAML); ``{value, sd}`` / ``{value, tol}`` values are inputs.
    samples : int
        Number of samples N (a power of two keeps the Sobol points balanced).
    seed : int
        Seed of the scrambling: the same seed gives the same numbers, here or on a cluster.
    limits : bool
        Propagate to the manoeuvre limits too (about 5x the cost of the model alone).
    method : bool
        Include strip theory's method error (data/method_uncertainty.csv).
    radii : sequence of float
        Turning radii of the u_max(R) band [m].
    workers, scheduler, progress
        Where to run (:func:`stripcoef.study.runner.run_batches`).
    """
    from stripcoef.geometry.keypaths import nominal as nominal_data
    from stripcoef.geometry.keypaths import uncertain_values
    from stripcoef.geometry.vehicle import parse_vehicle, read_vehicle_data
    from stripcoef.study.evaluate import Job, evaluate, evaluate_batch, table
    from stripcoef.study.runner import run_batches
    from stripcoef.study.sources import input_sources, method_sources, shape_class

    if int(samples) != samples or samples < 2:
        raise InputError("too few samples", key="samples", value=samples,
                         expected="an integer >= 2")
    if samples > 10 ** 6:
        raise InputError("too many samples for one machine", key="samples", value=samples,
                         expected="<= 1e6 (split the study, or run it on a cluster in parts)")
    samples = int(samples)
    file = str(vehicle)
    raw = read_vehicle_data(vehicle)
    declared = uncertain_values(raw, file=file)
    data = nominal_data(raw, file=file)
    veh = parse_vehicle(data, file=file)
    mirrors, lift, model = None, False, None
    if method:
        from stripcoef.assembly.symmetry import mirror_symmetries

        model = _nominal_model(veh, strips)
        mirrors = mirror_symmetries(veh, model.reference_point, strips)
        lift = bool(np.any(np.asarray(model.lift) != 0.0) or model.control_surfaces)
    sources = (input_sources(declared) if declared else []) + \
        (method_sources(veh, lift=lift) if method else [])
    notes = []
    if not sources:
        raise InputError("nothing is uncertain", file=file, key="samples",
                         expected="values declared as {value, sd} or {value, tol}, or the "
                                  "method uncertainty (method=True)")
    job = Job(data=data, file=file, paths=tuple(u.path for u in declared),
              sources=tuple(s for s in sources if s.kind == "method"), limits=limits,
              radii=tuple(float(r) for r in radii), strips=strips,
              mirrors=mirrors, model=None if declared else model)
    nominal_row = [u.value for u in declared] + [1.0] * len(job.sources)
    nominal_out = evaluate(job, nominal_row)
    # inputs first, then method factors: the order Job.evaluate reads a row in
    ordered = [s for s in sources if s.kind == "input"] + list(job.sources)
    draws = _draws(ordered, samples, seed)
    batches = [(job, draws[i:i + BATCH].tolist()) for i in range(0, samples, BATCH)]
    results = [r for batch in run_batches(evaluate_batch, batches, workers=workers,
                                          scheduler=scheduler, progress=progress)
               for r in batch]
    names, arr = table([nominal_out] + results)
    if declared and not method:
        notes.append("method uncertainty left out (method=False)")
    if method:
        mirrors = " and ".join(f"{a} -> -{a}" for a in sorted(job.mirrors)) or "none"
        notes.append(f"added-mass couplings: every one the body's mirror symmetries ({mirrors}) "
                     f"allow gets the coupling band, zero or not; the others stay zero")
    return UncertaintyResult(vehicle=veh.name, names=tuple(names), samples=arr[1:],
                             nominal={k: float(v) for k, v in zip(names, arr[0])},
                             sources=tuple(ordered), draws=draws, seed=int(seed),
                             shape_class=shape_class(veh), notes=tuple(notes))


def plot_band(result: UncertaintyResult, *, path=None, key: str = "path"):
    """u_max(R) with its 50 % and 95 % bands (a matplotlib Figure; written to ``path`` if
    given). Speeds [m/s] against turning radius [m]."""
    from stripcoef.study.plots import band_figure

    return band_figure(result, path=path, key=key)
