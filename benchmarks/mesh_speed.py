"""Speed of the mesh pipeline, and strip theory vs the BEM at equal accuracy, in one run.

Run:  .venv/bin/python -m benchmarks.mesh_speed     (about 5 minutes; BEM peak ~8 GB, see --max-gb)

1. A ~100k-face Myring (REMUS) hull as an STL file -> full matrices (M_A, D_L, D_Q, M_RB):
   wall time of each stage (read + repair, slicing into 200 strips, 2D panel method,
   axisymmetric 3D corrections given the 2D sections, the whole stripcoef.assembly.estimate.estimate,
   and file -> matrices) -- best of 3; then the open-frame ROV of mesh_accuracy.py refined
   to ~139k faces, file -> matrices (its members and junctions), best of 3.
2. Prolate spheroid L/D = 7.5 as triangle meshes (as from CAD, no symmetry used), every
   non-zero diagonal added-mass term against Lamb's exact values.
   a. Capytaine (direct, no free surface; stripcoef.bem.bem_added_mass) on a ladder of meshes,
      each solved in a child process of its own (one at a time) that reports its wall time and
      peak memory; the next rung is only tried when the measured peak, extrapolated as N^2,
      stays under --max-gb and under the memory available.
   b. Strip theory's accuracy over the knobs a user has: the mesh (the BEM's own meshes and
      finer ones), the number of strips, the meridian panels of the 3D corrections
      (estimate(correction_panels=)) and the panels per 2D section (estimate(section_panels=);
      96 is the adaptive default for these round sections).
   c. For each BEM rung, the cheapest strip-theory configuration whose largest diagonal error
      is at most the BEM's: every configuration that meets the error and is not dominated
      (another one meeting it with no more faces, strips and panels of either kind is never
      slower) is timed,
      best of 3, and the fastest is timed again, best of 7.
   Both methods are timed from the same triangle arrays in memory to the matrices: strip
   theory = mesh checks/repair (mesh_body) + stripcoef.assembly.estimate.estimate (slicing, 2D
   sections, 3D corrections, damping, rigid-body terms: the full model); BEM =
   bem_added_mass (Capytaine mesh + solve of the six radiation problems: the added mass
   only), after one warm-up solve on a tiny mesh in the same process (imports, first-call
   set-up), best of 3 below 4,000 faces, best of 2 above.  Strip theory runs with one BLAS
   thread (its many small solves are slower with more); the BEM gets --bem-threads (default:
   all cores; measured faster for its large dense solve).
"""

from __future__ import annotations

import os

# many small dense solves: a multi-threaded BLAS spins on a loaded 2-core machine (measured:
# a 160x160 solve takes 19 ms with OpenBLAS threads, 0.14 ms with one); set before numpy loads
THREAD_VARS = ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS")
for _var in THREAD_VARS:
    os.environ.setdefault(_var, "1")

import argparse  # noqa: E402
import json  # noqa: E402
import resource  # noqa: E402
import subprocess  # noqa: E402
import sys  # noqa: E402
import tempfile  # noqa: E402
import time  # noqa: E402
import warnings  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402
import trimesh  # noqa: E402

from benchmarks.mesh_accuracy import FLUID, RHO, lamb  # noqa: E402
from benchmarks.mesh_shapes import (body_of_revolution, myring_profile, open_frame_rov,  # noqa: E402
                         refine_to, spheroid_profile)

from stripcoef.assembly.added_mass import added_mass  # noqa: E402
from stripcoef.assembly.estimate import displaced_volume, estimate  # noqa: E402
from stripcoef.hull.corrections import hull_corrections, strip_section_added_mass  # noqa: E402
from stripcoef.geometry.mesh import load_mesh, mesh_body  # noqa: E402
from stripcoef.geometry.vehicle import MassSpec, Vehicle  # noqa: E402
from stripcoef.sections.panel import added_mass_sections  # noqa: E402

#: the spheroid: length and diameter [m] (L/D = 7.5)
LENGTH, DIAMETER = 1.5, 0.2
#: non-zero diagonal terms of a spheroid's M_A (roll is zero)
NONZERO = [0, 1, 2, 4, 5]
#: BEM ladder: (meridian intervals, panels around) of the revolved triangle mesh
BEM_MESHES = ((30, 26), (40, 38), (60, 50), (84, 72))
#: meshes offered to strip theory: the BEM's own and finer ones
STRIP_MESHES = BEM_MESHES + ((120, 96), (200, 160), (400, 256))
STRIPS = (10, 15, 20, 30, 50, 75, 100, 150, 200)
PANELS = (16, 24, 32, 48, 64, 96, 128, 160)
#: panels per 2D section (96: the adaptive default of a round section)
SECTION_PANELS = (32, 48, 96)
#: the 1000x target of issue 3
TARGET = 1000.0


def best(fn, n=3):
    out, times = None, []
    for _ in range(n):
        t0 = time.perf_counter()
        out = fn()
        times.append(time.perf_counter() - t0)
    return out, min(times)


def pipeline(path, strips=200):
    with tempfile.TemporaryDirectory():
        body, t_load = best(lambda: load_mesh(path))
        x = np.linspace(*body.x_extent(), strips + 1)
        xc, dx = 0.5 * (x[1:] + x[:-1]), np.diff(x)
        parts, t_slice = best(lambda: body.parts(xc, dx))
        _, t_panel = best(lambda: added_mass_sections(parts[0].contours, rho=RHO, about=None))
        v = Vehicle(name="myring", source=str(path), fluid=FLUID, hull=None, bodies=[body],
                    holes=[], mass=MassSpec(), thrusters=[], reference="center_of_buoyancy")
        st = v.cut(strips)
        _, cb = displaced_volume(st)
        m2d = strip_section_added_mass(st, RHO)
        _, t_corr = best(lambda: hull_corrections(st, rho=RHO, center=cb, section_added_mass=m2d))
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            _, t_est = best(lambda: estimate(v, strips=strips))

        _, t_total = best(lambda: file_to_matrices(path, strips))
    return {"faces": len(body.mesh.faces), "load": t_load, "slice": t_slice, "panel": t_panel,
            "corrections": t_corr, "estimate": t_est, "total": t_total}


def file_to_matrices(path, strips=200):
    """What a user of `stripcoef coefficients MESH` waits for, in process: read + repair the
    mesh file, then the full model (3D corrections included, the default)."""
    body = load_mesh(path)
    v = Vehicle(name=Path(path).stem, source=str(path), fluid=FLUID, hull=None, bodies=[body],
                holes=[], mass=MassSpec(), thrusters=[], reference="center_of_buoyancy")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return estimate(v, strips=strips)


def part1():
    print("## 1. 100k-face mesh to full matrices (best of 3, 200 strips)")
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "myring.stl"
        mesh = body_of_revolution(myring_profile(400), 128)
        mesh.export(path)
        r = pipeline(path)
    print(f"faces {r['faces']}: read+repair {r['load']:.3f} s, slice {r['slice']:.3f} s, "
          f"2D panel (200 sections) {r['panel']:.3f} s, axisym corrections {r['corrections']:.3f} s, "
          f"assemble.estimate (slice + sections + corrections + damping) {r['estimate']:.3f} s; "
          f"file -> full matrices {r['total']:.3f} s")
    # an open frame: several members, junctions, sharp corners (the member decomposition)
    try:
        rov = refine_to(open_frame_rov(), 100_000)
    except Exception as exc:                   # no boolean engine: pip install -e '.[bench]'
        print(f"open-frame ROV: skipped ({type(exc).__name__}: its boolean unions need the "
              "bench extra)")
        return
    with tempfile.TemporaryDirectory() as tmp:
        path = Path(tmp) / "rov.stl"
        rov.export(path)
        _, t_rov = best(lambda: file_to_matrices(path))
    print(f"open-frame ROV, {len(rov.faces)} faces: file -> full matrices {t_rov:.3f} s")


def spheroid_mesh(n_axial, n_circ):
    """Closed triangle mesh of the spheroid (eccentric-angle meridian, ``n_circ`` around)."""
    return body_of_revolution(spheroid_profile(LENGTH, DIAMETER, n_axial), n_circ)


def max_error(a):
    """Largest relative error [%] of the non-zero diagonal terms against Lamb."""
    ref = np.diag(lamb(LENGTH, DIAMETER))
    return 100.0 * max(abs(a[i, i] / ref[i] - 1.0) for i in NONZERO)


def spheroid_vehicle(body):
    return Vehicle(name="spheroid", source="benchmark", fluid=FLUID, hull=None, bodies=[body],
                   holes=[], mass=MassSpec(), thrusters=[], reference="center_of_buoyancy")


def strip_model(vertices, faces, strips, panels, section_panels=None):
    """What the user waits for: triangle arrays in memory -> the full strip-theory model."""
    body = mesh_body(trimesh.Trimesh(vertices, faces, process=False), origin="file",
                     name="spheroid")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return estimate(spheroid_vehicle(body), strips=strips, correction_panels=panels,
                        section_panels=section_panels)


# --------------------------------------------------------------------------- BEM (child)

def _rss_gb():
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1e6    # kB on Linux


def bem_worker(n_axial, n_circ):
    """Child process: one BEM solve, its time, error and peak memory as one JSON line."""
    from stripcoef.bem import bem_added_mass

    tiny = spheroid_mesh(8, 8)                                  # warm-up, not timed
    bem_added_mass(trimesh.Trimesh(tiny.vertices, tiny.faces, process=False), rho=RHO)
    base = _rss_gb()
    mesh = spheroid_mesh(n_axial, n_circ)
    v, f = np.asarray(mesh.vertices), np.asarray(mesh.faces)
    runs = 3 if len(f) < 4000 else 2       # best of: timing scatter is tens of % here
    times = []
    for _ in range(runs):
        t0 = time.perf_counter()
        a = bem_added_mass(trimesh.Trimesh(v, f, process=False), rho=RHO, max_faces=len(f))
        times.append(time.perf_counter() - t0)
    print(json.dumps({"faces": len(f), "seconds": min(times), "runs": runs,
                      "error": max_error(a), "base_gb": base, "peak_gb": _rss_gb()}))


def available_gb():
    with open("/proc/meminfo") as fh:
        for line in fh:
            if line.startswith("MemAvailable:"):
                return int(line.split()[1]) / 1e6
    return float("inf")


def bem_ladder(max_gb, threads):
    env = dict(os.environ)
    env.update({var: str(threads) for var in THREAD_VARS})
    rows, last = [], None
    for n_axial, n_circ in BEM_MESHES:
        n = len(spheroid_mesh(n_axial, n_circ).faces)
        if last is not None:
            need = last["base_gb"] + (last["peak_gb"] - last["base_gb"]) * (n / last["faces"]) ** 2
            avail = available_gb()
            if need > max_gb or need > avail - 1.0:
                print(f"Capytaine {n} faces: skipped, expected peak {need:.1f} GB (limit "
                      f"{max_gb:.1f} GB, available {avail:.1f} GB)")
                break
            print(f"Capytaine {n} faces: expected peak {need:.1f} GB ...", flush=True)
        out = subprocess.run([sys.executable, __file__, "--bem-worker", str(n_axial), str(n_circ)],
                             env=env, capture_output=True, text=True, check=False)
        if out.returncode != 0:
            print(f"Capytaine {n} faces: failed ({out.stderr.strip().splitlines()[-1:]})")
            break
        last = json.loads(out.stdout.strip().splitlines()[-1])
        last["mesh"] = (n_axial, n_circ)
        rows.append(last)
        print(f"Capytaine {last['faces']} faces: max diagonal error {last['error']:.3f} %, "
              f"{last['seconds']:.2f} s (best of {last['runs']}), peak {last['peak_gb']:.2f} GB",
              flush=True)
    return rows


# --------------------------------------------------------------------------- strip theory

def strip_accuracy():
    """Error [%] of every (mesh faces, strips, correction panels, section panels): the M_A
    that estimate computes (same call)."""
    table = {}
    for n_axial, n_circ in STRIP_MESHES:
        mesh = spheroid_mesh(n_axial, n_circ)
        body = mesh_body(mesh, origin="file", name="spheroid")
        vehicle = spheroid_vehicle(body)
        for strips in STRIPS:
            st = vehicle.cut(strips)
            volume, cb = displaced_volume(st)
            for panels in PANELS:
                for sp in SECTION_PANELS:
                    m, _ = added_mass(st, RHO, about=cb, volume=volume, center=cb,
                                      correction_panels=panels, section_panels=sp)
                    table[(len(mesh.faces), strips, panels, sp)] = max_error(m)
    return table


def undominated(configs):
    """Configurations no other one beats with no more faces, strips and panels (both)."""
    return [c for c in configs
            if not any(o != c and all(oi <= ci for oi, ci in zip(o, c)) for o in configs)]


def cheapest(table, error, arrays, timings, faces=None):
    """Fastest configuration with error <= ``error`` (on the mesh of ``faces`` faces if
    given), its error and time (best of 7)."""
    ok = undominated([c for c, e in table.items()
                      if e <= error and (faces is None or c[0] == faces)])
    if not ok:
        return None
    for c in ok:
        if c not in timings:
            timings[c] = best(lambda c=c: strip_model(*arrays[c[0]], *c[1:]), n=3)[1]
    pick = min(ok, key=timings.get)
    model, seconds = best(lambda: strip_model(*arrays[pick[0]], *pick[1:]), n=7)
    timings[pick] = min(timings[pick], seconds)
    return pick, max_error(model.added_mass), timings[pick], len(ok)


def part2(max_gb, threads):
    print("\n## 2. Spheroid L/D = 7.5 (triangle meshes): strip theory vs Capytaine at equal accuracy")
    print(f"\n### a. Capytaine ladder (one child process per mesh, {threads} BLAS/OpenMP threads)")
    bem = bem_ladder(max_gb, threads)
    print("\n### b. strip theory's accuracy over its knobs")
    t0 = time.perf_counter()
    table = strip_accuracy()
    arrays = {}
    for n_axial, n_circ in STRIP_MESHES:
        m = spheroid_mesh(n_axial, n_circ)
        arrays[len(m.faces)] = (np.asarray(m.vertices), np.asarray(m.faces))
    print(f"{len(table)} configurations ({len(arrays)} meshes x {len(STRIPS)} strip counts x "
          f"{len(PANELS)} correction panel counts x {len(SECTION_PANELS)} section panel counts)"
          f" in {time.perf_counter() - t0:.0f} s; "
          f"best error {min(table.values()):.3f} % ({min(table, key=table.get)})")
    print("\n### c. cheapest strip-theory configuration at the BEM's accuracy")
    print("\n| BEM faces | BEM max error | BEM time | strip theory: mesh faces, strips, "
          "correction panels, section panels | its max error | its time | ratio |")
    print("|---|---|---|---|---|---|---|")
    timings, verdict = {}, []
    for row in bem:
        found = cheapest(table, row["error"], arrays, timings)
        if found is None:
            print(f"| {row['faces']:,} | {row['error']:.3f} % | {row['seconds']:.2f} s | "
                  f"none in the grid reaches it | | | |")
            continue
        (faces, strips, panels, sp), err, sec, n_ok = found
        ratio = row["seconds"] / sec
        verdict.append((row["error"], ratio))
        print(f"| {row['faces']:,} | {row['error']:.3f} % | {row['seconds']:.2f} s | {faces:,}, "
              f"{strips}, {panels}, {sp} (fastest of {n_ok} timed) | {err:.3f} % | "
              f"{1e3 * sec:.1f} ms | "
              f"**{ratio:,.0f}x** |")
    print("\nthe same, strip theory restricted to the BEM's own mesh:\n")
    print("| BEM faces | BEM max error | BEM time | strips, correction panels, section panels "
          "| its max error | its time | ratio |")
    print("|---|---|---|---|---|---|---|")
    for row in bem:
        found = cheapest(table, row["error"], arrays, timings, faces=row["faces"])
        if found is None:          # none reaches it: the most accurate one on that mesh
            own = min((c for c in table if c[0] == row["faces"]), key=table.get)
            _, sec = best(lambda: strip_model(*arrays[own[0]], *own[1:]), n=3)
            print(f"| {row['faces']:,} | {row['error']:.3f} % | {row['seconds']:.2f} s | none "
                  f"reaches it; the most accurate: {own[1]}, {own[2]}, {own[3]} | "
                  f"{table[own]:.3f} % | "
                  f"{1e3 * sec:.1f} ms | ({row['seconds'] / sec:,.0f}x, less accurate) |")
            continue
        (_, strips, panels, sp), err, sec, _ = found
        print(f"| {row['faces']:,} | {row['error']:.3f} % | {row['seconds']:.2f} s | {strips}, "
              f"{panels}, {sp} | {err:.3f} % | {1e3 * sec:.1f} ms | "
              f"{row['seconds'] / sec:,.0f}x |")
    top = min(table, key=table.get)
    _, t_top = best(lambda: strip_model(*arrays[top[0]], *top[1:]), n=3)
    print(f"\nmost accurate strip configuration of the grid: {top[0]:,} faces, {top[1]} strips, "
          f"{top[2]} correction panels, {top[3]} section panels: {table[top]:.3f} %, "
          f"{t_top:.3f} s"
          + (f"; the largest BEM ({bem[-1]['faces']:,} faces, {bem[-1]['error']:.3f} %, "
             f"{bem[-1]['seconds']:.1f} s) is {bem[-1]['seconds'] / t_top:,.0f}x slower and "
             f"{bem[-1]['error'] / table[top]:.1f}x less accurate" if bem else ""))
    met = [f"{e:.3f} %" for e, r in verdict if r >= TARGET]
    missed = [f"{e:.3f} % ({r:,.0f}x)" for e, r in verdict if r < TARGET]
    print(f"\n{TARGET:,.0f}x target met at: {', '.join(met) or 'none'}; "
          f"not met at: {', '.join(missed) or 'none'}")


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--max-gb", type=float, default=11.0,
                    help="largest expected peak memory of one BEM solve [GB] (default 11)")
    ap.add_argument("--bem-threads", type=int, default=os.cpu_count() or 1,
                    help="BLAS/OpenMP threads of the BEM child processes (default: all cores)")
    ap.add_argument("--bem-worker", nargs=2, type=int, help=argparse.SUPPRESS)
    ap.add_argument("--skip-part1", action="store_true", help="only the BEM comparison")
    ap.add_argument("--only-part1", action="store_true",
                    help="only the 100k-face pipeline timing (no BEM)")
    args = ap.parse_args(argv)
    if args.bem_worker:
        bem_worker(*args.bem_worker)
        return
    print("load average at the start: %.2f %.2f %.2f" % os.getloadavg())
    if not args.skip_part1:
        part1()
    if not args.only_part1:
        part2(args.max_gb, args.bem_threads)
    print("\nload average at the end: %.2f %.2f %.2f" % os.getloadavg())


if __name__ == "__main__":
    main()
