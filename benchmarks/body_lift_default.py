"""What adopting ``body_lift: stratford_panel`` as the default (``auto``) would change beyond SUBOFF.

The default body-lift rule (``auto``: the DATCOM rule, Hopkins's separation station x_0 from the
hull's shape, USAF DATCOM sec. 4.2.1.1) against Stratford's criterion on the axisymmetric panel
solution's axial flow (``stratford_panel``, Stratford 1959; Hess & Smith 1967), measured on:

1. every shipped vehicle of geometry/: whether ``auto`` gives it body lift at all (a round hull
   with l/d >= 4 and fins or control surfaces), and where it does the separation station, the
   criterion's outcome, the warnings and the CPU seconds of one ``stripcoef.estimate`` in a
   fresh interpreter (``time.process_time`` around the estimate alone, the smallest of
   ``--repeats``, BLAS on one thread);
2. REMUS 100 (geometry/remus100.yaml, the one shipped vehicle with body lift): the station against
   the reference speed, the body lift's Y_uv, N_uv (about the file's reference point) and the
   steady manoeuvre limits' minimum turning radius at half the top speed
   (``stripcoef.limits.solve_limits``, as ``stripcoef limits`` prints it); SUBOFF's station
   against the speed, for comparison;
3. a family of finned Myring hulls (the REMUS hull and fins of validation/finned.py, tail
   half-angle 10-27.5 deg, middle body 1 or 2 times as long: l/d 7.3 and 10.7) at 0.5-3 m/s: where Stratford's
   criterion separates and where it finds no separation (station at the tail, body lift only
   from the truncated base), i.e. how continuous the rule is in the hull's shape and speed;
4. a non-axisymmetric finned hull: what ``auto`` and the explicit rules do with it.

Writes nothing. Usage: python -m benchmarks.body_lift_default [--repeats N] [--quick]
(about 1 min of CPU; ``--quick``: part 3 on three angles, one length, two speeds).
"""

from __future__ import annotations

import argparse
import copy
import math
import os
import sys
import subprocess
import time
import warnings
from pathlib import Path

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import numpy as np  # noqa: E402
import yaml  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
GEOMETRY = ROOT / "geometry"
RULES = ("datcom", "stratford_panel")


def _vehicle(data: dict, source: str):
    from stripcoef.geometry.vehicle import parse_vehicle

    return parse_vehicle(data, file=source)


def body_lift_info(vehicle, speed: float | None = None) -> dict | None:
    """The body-lift summary of ``vehicle`` under its own ``body_lift`` rule
    (stripcoef.assembly.lift._body_lift at the reference point 0): None without body lift, else
    {'method', 'fraction' s_0/l from the nose, 'limit' (Stratford: None, 'end' or 'cp'),
    'warnings': [text]}."""
    from stripcoef.assembly.lift import _body_lift

    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        body = _body_lift(vehicle, float(vehicle.fluid.density), [0.0, 0.0, 0.0],
                          [0.0, 0.0, 0.0], speed=speed)
    if body is None:
        return None
    lo, hi = vehicle.hull.x_extent()
    info = body[1]
    return {"method": info["method"], "fraction": (hi - info["separation_x"]) / (hi - lo),
            "limit": info.get("stratford", {}).get("limit"),
            "warnings": [str(w.message) for w in caught]}


def _estimate(vehicle):
    """The model of ``vehicle`` (warnings silenced)."""
    import stripcoef

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return stripcoef.estimate(vehicle)


#: One estimate timed in a fresh interpreter (no memoised hull flows from an earlier call):
#: CPU seconds of ``stripcoef.estimate`` alone, the imports and the file's parsing excluded.
_FRESH = """
import sys, time, warnings
import yaml
import stripcoef
from stripcoef.geometry.vehicle import load_vehicle
warnings.simplefilter("ignore")
veh = load_vehicle(sys.argv[1])
t0 = time.process_time()
stripcoef.estimate(veh)
print(time.process_time() - t0)
"""


def fresh_cpu(path: Path, data: dict, repeats: int) -> float:
    """Smallest CPU seconds [s] of ``repeats`` first estimates of the vehicle file's mapping
    ``data`` (written beside ``path`` so that relative mesh paths resolve), each in a fresh
    interpreter."""
    tmp = path.with_name(f".{path.stem}.body_lift_default.yaml")
    tmp.write_text(yaml.safe_dump(data))
    try:
        return min(float(subprocess.run([sys.executable, "-c", _FRESH, str(tmp)], check=True,
                                        capture_output=True, text=True).stdout.split()[-1])
                   for _ in range(repeats))
    finally:
        tmp.unlink()


def with_rule(data: dict, rule: str) -> dict:
    out = copy.deepcopy(data)
    out["body_lift"] = rule
    return out


def shipped(repeats: int) -> None:
    print("1. Shipped vehicles (geometry/*.yaml): body lift under 'auto' and under the switch")
    for path in sorted(GEOMETRY.glob("*.yaml")):
        data = yaml.safe_load(path.read_text())
        name = path.name
        try:
            auto = body_lift_info(_load(path, data))
        except Exception as exc:  # noqa: BLE001  (report, do not stop)
            print(f"   {name:22s} auto: error {type(exc).__name__}: {exc}")
            continue
        if auto is None:
            cpu = fresh_cpu(path, data, repeats)
            print(f"   {name:22s} no body lift under 'auto' (no fins/control surfaces, or not a "
                  f"slender round hull): unchanged; estimate {cpu:.3f} s CPU")
            continue
        parts = []
        for rule in RULES:
            veh = _load(path, with_rule(data, rule))
            info = body_lift_info(veh)
            cpu = fresh_cpu(path, with_rule(data, rule), repeats)
            parts.append(f"{rule}: station {info['fraction']:.4f} l, limit {info['limit']}, "
                         f"warnings {len(info['warnings'])}, estimate {cpu:.3f} s CPU")
        print(f"   {name:22s} " + "; ".join(parts))


def _load(path: Path, data: dict):
    """A vehicle file's mapping parsed as if read from ``path`` (relative mesh paths resolve
    from geometry/)."""
    from stripcoef.geometry.vehicle import load_vehicle

    tmp = path.with_name(f".{path.stem}.body_lift_default.yaml")
    tmp.write_text(yaml.safe_dump(data))
    try:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            return load_vehicle(tmp)
    finally:
        tmp.unlink()


def remus() -> None:
    from stripcoef.limits.solver import solve_limits

    path = GEOMETRY / "remus100.yaml"
    data = yaml.safe_load(path.read_text())
    print("2. REMUS 100: station against the reference speed; lift; turning circle")
    for speed in (0.5, 1.0, 1.5, 2.0, 2.5, 3.0):
        row = []
        for rule in RULES:
            info = body_lift_info(_load(path, with_rule(data, rule)), speed=speed)
            row.append(f"{rule} {info['fraction']:.4f} l ({info['limit']})")
        print(f"   U = {speed:.1f} m/s: " + ", ".join(row))
    from stripcoef.assembly.lift import _body_lift
    from validation.lift import total_linear

    for rule in RULES:
        veh = _load(path, with_rule(data, rule))
        with warnings.catch_warnings():     # said in part 1 (the 'warnings' count)
            warnings.simplefilter("ignore")
            body = _body_lift(veh, float(veh.fluid.density), [0.0, 0.0, 0.0],
                              [0.0, 0.0, 0.0])[0]
        model = _estimate(veh)
        lift = np.asarray(model.lift)
        # controls-fixed directional stability (Crane, Eda & Landsburg 1989, PNA III sec. 9.2),
        # the lift and Munk parts at the reference speed, as validation.lift.stability_indices
        jac = total_linear(model, float(veh.reference_speed))
        mass = float(model.rigid_body_mass[0, 0])
        xg = float(model.rigid_body_mass[1, 5]) / mass
        g_h = 1.0 - jac[5, 1] * (jac[1, 5] - mass) / (jac[1, 1] * (jac[5, 5] - mass * xg))
        print(f"   {rule:16s} body lift alone Y_uv {-body[1, 1]:+.3f} kg/m, N_uv {-body[5, 1]:+.4f} kg; "
              f"directional stability G_H {g_h:+.3f}")
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            t0 = time.process_time()
            lim = solve_limits(model)
            cpu_lim = time.process_time() - t0
        print(f"   {rule:16s} body+fin lift Y_uv {-lift[1, 1]:+.3f} kg/m, N_uv {-lift[5, 1]:+.4f} kg, "
              f"Y_ur {-lift[1, 5]:+.4f} kg, N_ur {-lift[5, 5]:+.5f} kg m; min turning radius "
              f"{lim.min_turning_radius:.3f} m at u = {lim.min_turning_speed:.3f} m/s "
              f"(limits {cpu_lim:.2f} s CPU)")


def myring_vehicle(theta_deg: float, stretch: float, rule: str) -> dict:
    """A finned Myring hull (validation/finned.py's MYRING, tail half-angle ``theta_deg``, the
    middle body ``stretch`` times as long) with the 'remus_tail' cruciform re-seated on it:
    fin mid-chord and chord as validation.finned.CASES['remus_tail'], the root on the hull at
    the fin's aft edge, tip 1.5 hull radii from the axis; body lift ``rule``."""
    from stripcoef.geometry.profiles import myring_tail
    from validation.finned import CASES, MYRING, THICKNESS, X0

    p = MYRING
    radius = 0.5 * p["d"]
    tail_end = X0 + p["c"]
    mid_end = tail_end + stretch * p["b"]
    xc, chord, _ = CASES["remus_tail"]
    r_root = float(myring_tail(np.array([xc - 0.5 * chord]), X0, tail_end, radius,
                               math.radians(theta_deg))[0])
    tip = 1.5 * radius
    span, mid = tip - r_root, 0.5 * (tip + r_root)
    fins = [{"name": n, "type": "fin", "center": c, "span_axis": a, "span": span,
             "chord": chord, "thickness": THICKNESS}
            for n, a, c in (("top", "z", [xc, 0.0, -mid]), ("bottom", "z", [xc, 0.0, mid]),
                            ("port", "y", [xc, -mid, 0.0]), ("starboard", "y", [xc, mid, 0.0]))]
    return {"name": f"myring {theta_deg:g} deg x{stretch:g}", "strips": 200,
            "reference_point": [0.0, 0.0, 0.0], "body_lift": rule,
            "hull": {"profile": [
                {"type": "myring_tail", "x": [X0, tail_end], "radius": radius,
                 "theta_deg": theta_deg},
                {"type": "cylinder", "x": [tail_end, mid_end], "radius": radius},
                {"type": "myring_nose", "x": [mid_end, mid_end + p["a"]], "radius": radius,
                 "n": p["n"]}]},
            "appendages": fins}


def myring_family(quick: bool) -> None:
    from validation.finned import MYRING

    print("3. Finned Myring hulls (validation/finned.py's hull, 'remus_tail' fins re-seated): "
          "the station s_0/l from the nose (Stratford's limit when not met) by tail half-angle, "
          "middle-body stretch and speed, datcom / stratford_panel")
    angles = (10.0, 20.0, 25.0) if quick else (10.0, 15.0, 20.0, 25.0, 27.5)
    speeds = (0.5, 3.0) if quick else (0.5, 1.5, 3.0)
    stretch = (1.0,) if quick else (1.0, 2.0)
    for k in stretch:
        for theta in angles:
            length = MYRING["a"] + k * MYRING["b"] + MYRING["c"]
            cells = []
            for speed in speeds:
                out = []
                for rule in RULES:
                    try:
                        veh = _vehicle(myring_vehicle(theta, k, rule), f"<myring {theta:g} deg>")
                        info = body_lift_info(veh, speed=speed)
                        out.append("none" if info is None else
                                   f"{info['fraction']:.3f}" + ("" if info["limit"] is None
                                                                else f" ({info['limit']})")
                                   + (f" [{len(info['warnings'])} warning]"
                                      if info["warnings"] else ""))
                    except Exception as exc:  # noqa: BLE001  (report, do not stop)
                        out.append(f"error {type(exc).__name__}: {exc}")
                cells.append(f"U {speed:.1f}: " + " / ".join(out))
            print(f"   theta {theta:4.1f} deg, l/d {length / MYRING['d']:5.2f}: " + "; ".join(cells))


def suboff_speeds() -> None:
    """Roddy's configuration 5 (validation.lift.suboff_vehicle_data: the Groves et al. hull with
    four stern planes): the station against the speed, 0.5 to 8 m/s (Roddy's 3.34 m/s among
    them): how the rule behaves on the hull it was measured on."""
    from validation.lift import RODDY_SPEED, suboff_vehicle_data

    print("2b. SUBOFF (Roddy's configuration 5): station against the speed")
    for speed in (0.5, 1.0, 2.0, RODDY_SPEED, 5.0, 8.0):
        row = []
        for rule in RULES:
            info = body_lift_info(_vehicle(suboff_vehicle_data(5, rule), "<SUBOFF 5>"),
                                  speed=speed)
            row.append(f"{rule} {info['fraction']:.4f} l ({info['limit']})")
        print(f"   U = {speed:.2f} m/s: " + ", ".join(row))


def non_round() -> None:
    """REMUS 100 with its hull made elliptic (half-height 1.2 times the half-breadth), fins
    unchanged: 'auto' leaves body lift out under either default; an explicit rule is refused
    with the vehicle file's one-line error."""
    path = GEOMETRY / "remus100.yaml"
    data = yaml.safe_load(path.read_text())
    prof = data["hull"].pop("profile")
    tall = copy.deepcopy(prof)
    for seg in tall:
        seg["radius"] = 1.2 * seg["radius"]
    data["hull"]["half_breadth"], data["hull"]["half_height"] = prof, tall
    print("4. A non-axisymmetric finned hull (REMUS 100, half-height 1.2 x half-breadth)")
    for rule in ("auto", *RULES):
        try:
            info = body_lift_info(_load(path, with_rule(data, rule)))
            print(f"   body_lift: {rule:16s} " + ("no body lift" if info is None else
                                                  f"station {info['fraction']:.4f} l"))
        except Exception as exc:  # noqa: BLE001  (report, do not stop)
            print(f"   body_lift: {rule:16s} {type(exc).__name__}: "
                  + str(exc).replace(str(GEOMETRY), "geometry"))


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--repeats", type=int, default=2,
                    help="fresh-interpreter estimates per CPU measurement (the smallest kept)")
    ap.add_argument("--quick", action="store_true", help="part 3 on fewer shapes and speeds")
    args = ap.parse_args(argv)
    t0 = time.process_time()
    shipped(args.repeats)
    remus()
    suboff_speeds()
    myring_family(args.quick)
    non_round()
    print(f"this process {time.process_time() - t0:.1f} s CPU (the fresh interpreters of part 1 "
          "not counted)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
