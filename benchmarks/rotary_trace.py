"""Where the SUBOFF model's yaw-rate force and large-drift yaw moment come from (issue 34).

Prints configuration 5's horizontal-plane derivatives by part under the default's rule
(``datcom``) and ``stratford_panel``, the stern planes against Roddy's increment (Table 4,
configuration 5 - 3), the non-linear part of the drift curves' yaw moment and its arm, and the
separation station the bare hull's N'(beta) would need (validation.rotary_trace; docs/validation.md,
'SUBOFF: where the rotary and large-drift misses come from').
``--candidates``: the published rules for a fin's incidence in drift and in rotation, each
applied to the stern planes (5 - 3) and the sail (4 - 3) and to the issue's Table 4 and drift
checks under both rules (validation.fin_incidence; docs/validation.md, 'SUBOFF: published rules
for a fin's incidence in drift and in rotation').
Usage: python -m benchmarks.rotary_trace [--config 5|2] [--candidates]
(about 4 s of CPU; --candidates about 7.7 s: 6.6 s user, 1.0 s sys on the idle machine, with the MMG what-ifs)
"""

from __future__ import annotations

import argparse
import sys

from validation.rotary_trace import (TERMS, TRACE_METHODS, drift_moment_split, implied_station,
                                     measured, measured_increment, rest_arm, yaw_rate_split)


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--config", type=int, choices=(2, 5), default=5,
                    help="Roddy's configuration split by part (5: hull + planes; 2: fully "
                         "appended with ring wing No. 1)")
    ap.add_argument("--candidates", action="store_true",
                    help="the published incidence rules (3/4 chord, vortex lattice, trailing "
                         "edge, the sidewash option, downwash on the static terms only) "
                         "against the stern planes' and the sail's increments and the "
                         "issue's checks")
    args = ap.parse_args(argv)
    if args.candidates:
        return _candidates()
    head = "  ".join(f"{k:>10s}" for k in TERMS)
    for method in TRACE_METHODS:
        s = yaw_rate_split(args.config, method)
        print(f"{method}: configuration {args.config}, separation at {s['x_separation']:.4f} l")
        print(f"  {'part':28s}{head}      lever")
        for name, d in s.items():
            if isinstance(d, dict) and "Yv" in d and any(abs(d[k]) > 0 for k in TERMS):
                lever = f"{d['Yr'] / d['Yv']:+.3f}" if abs(d["Yv"]) > 1e-9 else ""
                print(f"  {name:28s}" + "  ".join(f"{d[k]:+.6f}"[:10].rjust(10) for k in TERMS)
                      + f"  {lever:>9s}")
    print(f"Roddy configuration {args.config}: "
          + "  ".join(f"{k} {v:+.6f}" for k, v in measured(args.config).items()))
    inc = measured_increment(5, 3)
    print("Roddy stern planes (5 - 3): " + "  ".join(f"{k} {v:+.6f}" for k, v in inc.items())
          + f"  lever {inc['Yr'] / inc['Yv']:+.3f}  Y'_r/N'_v {inc['Yr'] / inc['Nv']:.2f}")
    for method in TRACE_METHODS:
        for config in (3, 5):
            for r in drift_moment_split(config, method):
                if r["q"] == "N":
                    print(f"{method:15s} config {config} N'({r['beta']:4.1f}) measured "
                          f"{r['measured']:+.5f} (linear {r['measured_linear']:+.5f}, rest "
                          f"{r['measured_rest']:+.5f}) model {r['model']:+.5f} = Munk "
                          f"{r['munk']:+.5f} + lift {r['lift']:+.5f} + cross-flow "
                          f"{r['crossflow']:+.5f}")
            for beta in (12.0, 18.0):
                a = rest_arm(config, method, beta)
                print(f"{method:15s} config {config} non-linear force's arm at {beta:.0f} deg: "
                      f"measured {a['measured']:+.3f} L_BP, model {a['model']:+.3f} L_BP")
    for beta in (8.0, 12.0, 16.0, 18.0):
        s = implied_station("stratford_panel", beta)
        print(f"bare hull N'({beta:.0f} deg) met with the potential lift cut at "
              f"{s['station']:.4f} l (rule: {s['station_model']:.4f} l); Y' there "
              f"{s['Y_ratio']:.2f} of measured")
    return 0


def _candidates() -> int:
    """Print validation.fin_incidence's rows and checks."""
    from validation.fin_incidence import CANDIDATES, RULES, checks, component_rows

    for method in RULES:
        for r in component_rows(method):
            print(f"{method:15s} {r['component']:12s} {r['candidate']:15s} "
                  + "  ".join(f"{k} {r[k]:5.2f}" for k in TERMS)
                  + f"  lever {r['lever']:+.3f} (measured {r['measured_lever']:+.3f})")
    for method in RULES:
        for c in CANDIDATES:
            k = checks(method, c)
            print(f"{method:15s} {c:15s} issue checks (Table 4) {k['table4'][0]}/"
                  f"{k['table4'][1]}; drift curves within 20 %: {k['drift'][0]}/{k['drift'][1]}; "
                  f"lift sd(ln) {k['band']:.3f}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
