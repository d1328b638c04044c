"""CPU time of the library code the test suite spends most of its time in (issue 31).

- a simulation: the 240 s manoeuvre of ``benchmarks.simulate_speed`` at rtol 1e-6 (the
  right-hand side, :meth:`stripcoef.model.HydroModel.velocity_forces`), and a synthetic log
  with a current (``validation.synthetic.generate("current", 11)``, which the diagnose tests
  build by the dozen);
- the panel method: ``estimate`` of the BlueROV2 Heavy and the VideoRay Pro 3 vehicle files,
  twice each in one process (the second reads the level solves of
  ``stripcoef.hull.panels`` solved by the first);
- the thin-sheet method: ``ring_velocity`` of 256 points on a finned body of 1600 panels
  (``stripcoef.hull.finsheet``);
- the 3D panel kernels: ``influence_matrices`` of the BlueROV2 Heavy's finest panel level
  (``stripcoef.hull.panel_kernels``, the level ``estimate`` solves);
- repeated estimates of one vehicle (a study's samples, the tests' many commands on the
  shipped files): ``estimate(mares.yaml)``, the first and the mean of the next 10 in one
  process (the equivalent bodies of the 3D corrections, ``stripcoef.hull.axisymmetric``);
- the finned circle's exact roll series (``stripcoef.sections.added_mass``), 240 hull
  radii and tips, each computed afresh (its memo bypassed);
- one surface about another reference point: ``estimate(bluerov2_heavy.yaml)`` about its
  centre of gravity after the file's own estimate (about the centre of buoyancy) in the same
  process (``stripcoef.hull.panels``: the level solves are kept about the surface's own
  origin and moved to each reference point);
- the CFD comparison's models: ``validation.cfd.stored()`` (``stripcoef.cfd.compare.model_for``
  of every stored CFD case), in a process of its own (``--cfd``; it reads the hull memos).

- the issue-16 real-style diagnosis (``--diagnose``): ``diagnose`` of
  ``validation.synthetic.real_style_log(1, "sway-off", duration=200.0)`` with ``dof="all"``
  and ``holdout=0.3`` (the MAP fits of ``stripcoef.diagnose.fit``, the batch free simulations
  of ``stripcoef.diagnose.freesim``), the log's generation timed apart;
- the SUBOFF comparison's models (``--suboff``): ``validation.lift.suboff_comparisons()``
  (every configuration's ``estimate`` under the slender-body rule: the stern flow of
  ``stripcoef.hull.lift`` and ``stripcoef.hull.boundary_layer``), in a process of its own
  (it reads the hull memos); and ``validation.independent.generate`` of the BlueROV2 Heavy
  with an actuation delay, 60 s.

Each number is the least CPU time (``time.process_time``) of ``--repeat`` runs, BLAS on one
thread, as in the tests.

Usage: python -m benchmarks.library_hotpaths [--repeat 3] [--cfd | --diagnose | --suboff]
"""

import argparse
import os
import time
import warnings
from pathlib import Path

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import numpy as np  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent


def least(f, repeat: int) -> float:
    """Least CPU seconds of ``repeat`` calls of f."""
    out = []
    for _ in range(repeat):
        t0 = time.process_time()
        f()
        out.append(time.process_time() - t0)
    return min(out)


def main(argv=None):
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeat", type=int, default=3)
    ap.add_argument("--cfd", action="store_true", help="time validation.cfd.stored() only")
    ap.add_argument("--diagnose", action="store_true",
                    help="time the issue-16 real-style diagnosis only")
    ap.add_argument("--suboff", action="store_true",
                    help="time validation.lift.suboff_comparisons() and an independent log only")
    args = ap.parse_args(argv)
    if args.cfd:
        cfd_models()
        return
    if args.diagnose:
        real_style_diagnosis(args.repeat)
        return
    if args.suboff:
        suboff_and_independent()
        return
    from stripcoef import estimate
    from stripcoef.hull.finsheet import FinPlanform, ring_velocity, sheet_mesh
    from stripcoef.simulate import simulate
    from validation.synthetic import generate, manoeuvre, rov_model

    model = rov_model()
    t, cmds = manoeuvre(np.random.default_rng(0))
    print(f"simulate, 240 s manoeuvre, rtol 1e-6: "
          f"{least(lambda: simulate(model, t, commands=cmds, rtol=1e-6, atol=1e-8), args.repeat):.2f} s")
    print(f"generate('current', 11): {least(lambda: generate('current', 11), args.repeat):.2f} s")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        for name in ("bluerov2_heavy", "videoray_pro3"):
            path = ROOT / "geometry" / f"{name}.yaml"
            times = [least(lambda: estimate(path), 1) for _ in range(2)]
            print(f"estimate({name}.yaml): first {times[0]:.2f} s, second {times[1]:.2f} s")
    fins = [FinPlanform(k * np.pi / 2, -0.9, -0.6, 0.25) for k in range(4)]
    mesh = sheet_mesh(lambda x: np.where(np.abs(x) < 1,
                                         0.1 * np.sqrt(np.clip(1 - x * x, 0, None)), 0.0),
                      -1.0, 1.0, fins)
    pts = mesh.points[:256]
    print(f"ring_velocity, 256 points x {len(mesh.quads)} panels: "
          f"{least(lambda: ring_velocity(pts, mesh.nodes, mesh.quads), args.repeat + 1):.3f} s")
    panel_kernels(args.repeat)
    repeated_estimates()
    roll_series(args.repeat)
    moved_reference()


def panel_kernels(repeat: int):
    """``influence_matrices`` of the BlueROV2 Heavy's finest level of the input family."""
    from stripcoef.assembly.added_mass import panel_surface
    from stripcoef.geometry.vehicle import load_vehicle
    from stripcoef.hull.panel_kernels import influence_matrices
    from stripcoef.hull.panels import panel_levels

    surface = panel_surface(load_vehicle(ROOT / "geometry" / "bluerov2_heavy.yaml"), 1600)
    v, f = panel_levels(surface.vertices, surface.faces, 1600)[-1]
    tri = np.asarray(v, float)[np.asarray(f)]
    print(f"influence_matrices, BlueROV2 Heavy level of {len(tri)} panels: "
          f"{least(lambda: influence_matrices(tri), repeat):.2f} s")


def repeated_estimates():
    """The first ``estimate`` of MARES in this process and the mean of the next 10."""
    from stripcoef import estimate

    path = ROOT / "geometry" / "mares.yaml"
    first = least(lambda: estimate(path), 1)
    rest = sum(least(lambda: estimate(path), 1) for _ in range(10)) / 10
    print(f"estimate(mares.yaml): first {first:.3f} s, next 10 {rest:.3f} s each")


def roll_series(repeat: int):
    """The finned circle's roll series for 240 (radius, tip, fins), memo bypassed."""
    from stripcoef.sections.added_mass import _unit_roll_series

    cases = [(r, a, k) for r in (0.0, 0.05, 0.1) for a in np.linspace(0.11, 0.3, 40)
             for k in (2, 4)]
    series = _unit_roll_series.__wrapped__
    print(f"finned-circle roll series, 240 cases: "
          f"{least(lambda: [series(*c) for c in cases], repeat):.2f} s")


def moved_reference():
    """``estimate`` of the BlueROV2 Heavy vehicle file about its centre of gravity, after the
    file's own estimate (about the centre of buoyancy) in this process."""
    from stripcoef import estimate

    path = ROOT / "geometry" / "bluerov2_heavy.yaml"
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        estimate(path, reference_point=[0.0, 0.0, 0.0])
        moved = least(lambda: estimate(path, reference_point="center_of_gravity"), 1)
    print(f"estimate(bluerov2_heavy.yaml) about its CG after one about the origin: {moved:.2f} s")


def cfd_models():
    """``validation.cfd.stored()``: the comparison model of every stored CFD case."""
    from validation.cfd import stored

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        print(f"validation.cfd.stored(), every stored CFD case's model: "
              f"{least(stored, 1):.2f} s")


def real_style_diagnosis(repeat: int):
    """``diagnose`` of the issue-16 real-style log (the slowest diagnose test's), and the
    log's generation."""
    from stripcoef.diagnose import diagnose
    from validation.synthetic import real_style_log

    made = least(lambda: real_style_log(1, "sway-off", duration=200.0), 1)
    log, prior, _ = real_style_log(1, "sway-off", duration=200.0)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        cpu = least(lambda: diagnose(log, prior, dof="all", holdout=0.3,
                                     time_limit=float("inf")), repeat)
    print(f"real_style_log(1, 'sway-off', 200 s): {made:.2f} s; its diagnose: {cpu:.2f} s")


def suboff_and_independent():
    """``validation.lift.suboff_comparisons()`` in a fresh process, and 60 s of the independent
    simulator."""
    from stripcoef.modelfile import load_model
    from validation.independent import generate
    from validation.lift import suboff_comparisons

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        print(f"validation.lift.suboff_comparisons(): {least(suboff_comparisons, 1):.2f} s")
        prior = load_model(ROOT / "geometry" / "bluerov2_heavy.yaml").to_dict()
        print("validation.independent.generate(bluerov2_heavy, actuation_delay, 60 s): "
              f"{least(lambda: generate(prior, 'actuation_delay', 5, duration=60.0), 1):.2f} s")


if __name__ == "__main__":
    main()
