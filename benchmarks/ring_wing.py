"""Ring wing No. 1 of DARPA SUBOFF: the ring's lift slope and its force on the hull against
Roddy 1990's configurations 1, 2 and 6 (issue 34).

Prints
1. Weissinger's ring-wing lift slope (``stripcoef.hull.lift.ring_wing_lift_slope``) against
   Fletcher's five measured rings (reference_tables/annular_wing) and against the vortex lattice
   of the thin ring (``validation.lift.ring_vortex_lattice``, 64 x 8 panels);
2. the ring's increments (configuration 6 minus 3, about Roddy's moment point), measured and
   modelled under each body-lift rule, with the ring in the hull's separated wake (an
   option, ``wake=True`` of ``stripcoef.assembly.lift.ring_wing_lift``) and in the
   undisturbed local cross-flow (``wake=False``), with the wake fraction f and the separation
   station's radius;
3. every Table 4 term of the configurations that carry the ring (1, 2, 6), model / measured,
   under each rule with and without the wake;
4. configuration 6's Y'(beta), N'(beta) against Roddy's Appendix B curve, 4 to 18 deg
   (``validation.lift.ring_drift_rows``), and the measured configuration 6 over 3.

Usage: python -m benchmarks.ring_wing [--methods datcom,stratford_panel]  (about 5 s of CPU)
"""

from __future__ import annotations

import argparse
import math

from stripcoef.hull.lift import ring_wing_lift_slope
from validation import reference as ref
from validation.lift import (FT, ring_drift_rows, ring_vortex_lattice, ring_wing_terms,
                             suboff_derivatives, val)

TERMS = ("Yv", "Nv", "Yr", "Nr")
RING_CONFIGS = {6: ("Yv", "Nv", "Yr", "Nr"), 2: ("Yv", "Nv", "Yr", "Nr"),
                1: ("Zw", "Mw", "Zq", "Mq")}
#: the model configuration each compared configuration is built from (1: the vertical plane of 2)
BUILT = {6: 3, 2: 2, 1: 2}


def slope_rows() -> list[tuple]:
    out = []
    for i in range(1, 6):
        a = ref.reference_value("annular_wing", f"A.{i}")["value"]
        measured = math.degrees(ref.reference_value("annular_wing", f"CLa.{i}")["value"])
        out.append(("Fletcher", a, measured, ring_wing_lift_slope(a)))
    for a in (0.3, 1.05, 3.0, 10.0):
        out.append(("lattice", a, ring_vortex_lattice(a, 64, 8), ring_wing_lift_slope(a)))
    return out


def increments(method: str, wake: bool) -> dict:
    a = suboff_derivatives(3, method)
    b = suboff_derivatives(3, method, True, wake=wake)
    return {k: b[k] - a[k] for k in TERMS}


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--methods", default="datcom,stratford_panel,stratford,slender",
                        help="comma-separated body-lift rules")
    args = parser.parse_args(argv)
    methods = [m.strip() for m in args.methods.split(",") if m.strip()]

    print("ring lift slope [1/rad on D c]: Weissinger against Fletcher 1957 (measured) and the "
          "thin ring's vortex lattice")
    for what, a, ref_value, model in slope_rows():
        print(f"  {what:8s} A = D/c {a:6.3f}  reference {ref_value:6.3f}  Weissinger "
              f"{model:6.3f}  ratio {model / ref_value:5.3f}")

    measured = {k: val(f"c6.{k}") - val(f"c3.{k}") for k in TERMS}
    print("\nring increments, configuration 6 - 3 (about the moment point); ratio model/measured")
    print("  measured           " + "  ".join(f"{k}' {measured[k]:+.6f}" for k in TERMS))
    for method in methods:
        for wake in (True, False):
            inc = increments(method, wake)
            info = ring_wing_terms(3, method, wake)[1]
            r0 = info.get("separation_radius", float("nan")) / FT
            print(f"  {method:15s} wake {'on ' if wake else 'off'} "
                  + "  ".join(f"{k}' {inc[k]:+.6f} ({inc[k] / measured[k]:+.2f})" for k in TERMS)
                  + f"  f {info['wake_fraction']:.2f}, q {info['pressure_ratio']:.3f}, "
                  f"r(x_0) {r0:.3f} ft, ring R {info['radius'] / FT:.3f} ft")

    print("\nTable 4 terms of the configurations with the ring, model / measured")
    for method in methods:
        for wake in (True, False):
            parts = []
            for config, names in RING_CONFIGS.items():
                model = suboff_derivatives(BUILT[config], method, True, wake=wake)
                parts += [f"{config}:{n} {model[n] / val(f'c{config}.{n}'):5.2f}" for n in names]
            print(f"  {method:15s} wake {'on ' if wake else 'off'} " + "  ".join(parts))

    print("\nconfiguration 6 against Appendix B, model / measured at beta [deg]")
    for method in methods:
        for wake in (True, False):
            rows = ring_drift_rows(method, wake)
            print(f"  {method:15s} wake {'on ' if wake else 'off'} " + "  ".join(
                f"{r['q']}'({r['beta']:.0f}) {r['model'] / r['measured']:4.2f}" for r in rows))
    print("  measured, configuration 6 / 3    " + "  ".join(
        f"{r['q']}'({r['beta']:.0f}) {r['measured'] / r['bare']:4.2f}" for r in rows))


if __name__ == "__main__":
    main()
