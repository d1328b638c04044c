"""``drag_by_cfd``: a closed body's damping by OpenFOAM, run by run, into a :class:`CfdResult`.

For each DOF: the finest mesh level at every speed (the damping fit), and the coarser level
at the first speed (the mesh-convergence estimate). Each run is its own case folder under
``case_dir`` (``surge_1m_s_L4``), kept for inspection and runnable unchanged elsewhere by its
``Allrun``.
"""

from __future__ import annotations

import os
from pathlib import Path

import numpy as np

from stripcoef.cfd.case import DOFS, ITERATIONS, CaseSpec, mrf_extent, write_case
from stripcoef.cfd.forces import STEADY_WINDOW, WINDOW, read_forces, read_y_plus, settle
from stripcoef.cfd.result import CfdResult, DofResult, RunResult, fit_damping, judge
from stripcoef.cfd.runner import openfoam_environment, run_case
from stripcoef.errors import InputError
from stripcoef.fluid import Fluid

#: Surface refinement levels (cells ``size / 2**level`` at the surface): coarse and fine.
LEVELS = (3, 4)
#: The default levels of a rotation, one finer: measured, levels 3 and 4 leave a rotation's
#: damping mesh-limited (the BlueROV2-sized box's yaw moved 28 % from level 3 to 4 and 5 %
#: from 4 to 5; the BlueROV2 Heavy's yaw 50 % from 3 to 4), while a translation's moves
#: 1-20 % from 3 to 4 (reference_tables/cfd/README.md).
ROTATION_LEVELS = (4, 5)


def frontal_area(surface, axis: int) -> float:
    """Area of the body's shadow on the plane normal to ``axis`` [m^2]: the union of its
    triangles projected onto that plane (shapely)."""
    from shapely import union_all
    from shapely.geometry import Polygon

    keep = [a for a in range(3) if a != axis]
    tri = np.asarray(surface.triangles, float)[:, :, keep]
    d1, d2 = tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]
    twice = np.abs(d1[:, 0] * d2[:, 1] - d1[:, 1] * d2[:, 0])
    ok = twice > 1e-12 * max(float(np.max(twice, initial=0.0)), 1e-300)
    shadow = union_all([Polygon(t) for t in tri[ok]])
    return float(shadow.area)


def default_rate(speed: float, length: float) -> float:
    """Rotation rate whose tip speed at half the body length is ``speed`` [rad/s]."""
    return 2.0 * speed / length


def _digits(value) -> float:
    return float(f"{float(value):.7g}")


def case_name(dof: str, speed: float, level: int) -> str:
    unit = "rad_s" if DOFS[dof][1] else "m_s"
    return f"{dof}_{speed:g}{unit}_L{level}".replace(".", "p").replace("-", "m")


def drag_by_cfd(surface, *, dofs=("surge",), speeds=(1.0,), rates=None, levels=None,
                ranks: int | None = None, case_dir="cfd-case", iterations: int = ITERATIONS,
                fluid: Fluid | None = None, write_only: bool = False, source: str = "mesh",
                on_progress=None) -> CfdResult:
    """Damping of a closed body by steady RANS in OpenFOAM.

    Parameters
    ----------
    surface : trimesh.Trimesh
        Closed body in body axes (FRD) [m], origin at the reference point (moments about it).
    dofs : sequence of str
        Any of surge, sway, heave (inflow), roll, pitch, yaw (MRF rotation).
    speeds : sequence of float
        Speeds of the translations [m/s]; two or more give d_L too.
    rates : sequence of float, optional
        Rates of the rotations [rad/s]; default :func:`default_rate` of each speed.
    levels : sequence of int, optional
        Mesh levels, coarse to fine (one level: no mesh-convergence estimate); default
        :data:`LEVELS` for a translation, :data:`ROTATION_LEVELS` for a rotation.
    ranks : int, optional
        MPI ranks (default: the cores available to this process).
    case_dir : str or Path
        Folder of the cases (created).
    iterations : int
        Most simpleFoam iterations per run.
    fluid : Fluid, optional
        Water (default sea water).
    write_only : bool
        Write the cases and stop (no OpenFOAM needed).
    on_progress : callable, optional
        ``on_progress(run_label, state, force, moment)`` while a solver runs.

    Returns
    -------
    CfdResult
    """
    fluid = fluid or Fluid()
    dofs = tuple(dofs)
    for d in dofs:
        if d not in DOFS:
            raise InputError("unknown degree of freedom", key="dofs", value=d,
                             expected="surge, sway, heave, roll, pitch or yaw")
    if levels is not None:
        levels = tuple(sorted(int(v) for v in levels))
        if not levels or levels[0] < 1 or levels[-1] > 8:
            raise InputError("invalid mesh levels", key="levels", value=list(levels),
                             expected="one or two integers from 1 to 8")
    speeds = tuple(float(s) for s in speeds)
    if not speeds or not all(np.isfinite(s) and s > 0 for s in speeds):
        raise InputError("speeds must be positive", key="speeds", value=list(speeds),
                         expected="numbers > 0 [m/s]")
    if ranks is None:
        ranks = len(os.sched_getaffinity(0)) if hasattr(os, "sched_getaffinity") \
            else (os.cpu_count() or 1)
    if ranks < 1:
        raise InputError("must be positive", key="ranks", value=ranks, expected="an integer >= 1")
    if not getattr(surface, "is_watertight", False):
        raise InputError("the body is not a closed surface", key="surface", value=source,
                         expected="a closed (watertight) mesh")
    env = None if write_only else openfoam_environment(ranks)
    # a mesh file's float32 coordinates: 7 digits (0.2 is not 0.19999999 in the case files)
    length = _digits(np.max(surface.extents))
    size = _digits(np.sort(surface.extents)[1])
    bounds = tuple(tuple(_digits(v) for v in row) for row in surface.bounds)
    case_dir = Path(case_dir)
    dof_results, written, used = [], [], set()
    for dof in dofs:
        axis, rotation = DOFS[dof]
        values = (tuple(rates) if rates else tuple(default_rate(s, length) for s in speeds)) \
            if rotation else speeds
        area = frontal_area(surface, axis)
        lv = levels or (ROTATION_LEVELS if rotation else LEVELS)
        used.update(lv)
        plan = [(v, lv[-1]) for v in values]
        if len(lv) > 1:
            plan.append((values[0], lv[0]))
        runs = []
        for value, level in plan:
            mrf_r, mrf_h = mrf_extent(surface.vertices, (0.0, 0.0, 0.0), axis, 0.25 * size) \
                if rotation else (0.0, 0.0)
            spec = CaseSpec(dof=dof, speed=value, level=level, length=length, size=size,
                            bounds=bounds, density=fluid.density,
                            viscosity=fluid.kinematic_viscosity, reference_area=area,
                            ranks=ranks, iterations=iterations, mrf_radius=mrf_r,
                            mrf_half_length=mrf_h)
            case = write_case(case_dir / case_name(dof, value, level), spec, surface)
            written.append(case.folder.name)
            if write_only:
                continue
            label = f"{dof} {value:g} {'rad/s' if rotation else 'm/s'} level {level}"
            cb = None if on_progress is None else \
                (lambda st, f, m, label=label: on_progress(label, st, f, m))
            outcome = run_case(case, env=env, on_progress=cb)
            runs.append(_judge_run(case, outcome, dof, value, level))
        if write_only:
            continue
        fine = [r for r in runs if r.level == lv[-1]]
        d_l, d_q = fit_damping([r.speed for r in fine], [r.force for r in fine])
        spread = None
        if len(lv) > 1:              # the two levels at the first speed
            _, d_q0 = fit_damping([runs[-1].speed], [runs[-1].force])
            _, d_qf = fit_damping([fine[0].speed], [fine[0].force])
            spread = abs(d_qf - d_q0) / abs(d_qf) if d_qf else float("inf")
        cd = None if rotation else d_q / (0.5 * fluid.density * area)
        dof_results.append(DofResult(dof=dof, runs=tuple(runs), d_linear=d_l, d_quadratic=d_q,
                                     mesh_spread=spread, drag_coefficient=cd,
                                     reference_area=area,
                                     converged=all(r.converged for r in runs)))
    return CfdResult(source=source, length=length, size=size, density=fluid.density,
                     viscosity=fluid.kinematic_viscosity, levels=tuple(sorted(used)), ranks=ranks,
                     case_dir=str(case_dir), dofs=tuple(dof_results), written=tuple(written))


def _judge_run(case, outcome, dof: str, value: float, level: int) -> RunResult:
    axis, rotation = DOFS[dof]
    try:
        hist = read_forces(case.folder)
    except (FileNotFoundError, ValueError):
        hist = None
    if hist is None or hist.iteration.size == 0:
        nan3 = (float("nan"),) * 3
        return RunResult(dof=dof, speed=value, level=level, cells=outcome.cells,
                         iterations=outcome.iterations, status="diverged", force=float("nan"),
                         swing=float("inf"), drift=float("inf"), force_vector=nan3, moment_vector=nan3,
                         case=case.folder.name,
                         note=outcome.solver_error or "no force written",
                         cpu_seconds=outcome.cpu_seconds,
                         wall_seconds=outcome.wall_seconds)
    series = (hist.moment if rotation else hist.force)[:, axis]
    # a run that met its residual criterion is a steady solution: its last iterates
    s = settle(series, STEADY_WINDOW if outcome.residuals_met else WINDOW)
    n = s.window
    status, note = judge(s, outcome.residuals_met, outcome.solver_error, outcome.iterations)
    if outcome.failed_checks:
        note = (note + "; " if note else "") + \
            f"checkMesh failed {outcome.failed_checks} check(s)"
    return RunResult(dof=dof, speed=value, level=level, cells=outcome.cells,
                     iterations=outcome.iterations, status=status, force=s.value,
                     swing=s.spread, drift=s.drift,
                     force_vector=tuple(float(v) for v in hist.force[-n:].mean(axis=0)),
                     moment_vector=tuple(float(v) for v in hist.moment[-n:].mean(axis=0)),
                     case=case.folder.name, note=note, cpu_seconds=outcome.cpu_seconds,
                     wall_seconds=outcome.wall_seconds, y_plus=read_y_plus(case.folder))
