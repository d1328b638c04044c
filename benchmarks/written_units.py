"""Stored rows of ``benchmarks.diagnose_independent`` scored again with the magnitude rule in
the written model's units (issue 33, fresh33f).

Before fresh33f, :func:`benchmarks.diagnose_independent.magnitude_truth` expressed a force
effect at the thrust the written model gives the effect's DOF, :math:`s\\,g_w/g` (s the
fitted thrust scale, :math:`g_w` the written thrusters' gain there, g the truth's), but the
added mass only at :math:`s/g` and the thrust effectiveness as g: a change that moves a DOF's
mean written gain off 1 (the whole-log thruster gains with ``linked_gains``) was charged for
it. The rule now expresses both at the written gains too; a row records it as
``magnitude_units == "written"`` with its ``written_gain``. A row written before carries
neither; its :math:`g_w` is read from the row's own ``thruster_gains`` (the applied gains,
None when none were applied) with the benchmark's weights
(:func:`benchmarks.diagnose_independent.written_gain`), and its reference converted
(:func:`benchmarks.diagnose_independent.converted`):

- thrust effectiveness: :math:`g \\to g/g_w`;
- added mass: :math:`r \\to (r + M_0)\\,g_w - M_0`, :math:`M_0 = M_{RB,ii} + M_{A,ii}` of the
  prior (:func:`benchmarks.diagnose_independent.prior_inertia`), since
  :math:`r + M_0 = (M_{RB} + M_{A,true})\\,s/g`.

Force effects were already at :math:`g_w`. Second, a kept effect's value is the written
model's, which holds only the kept thrust scales, but the reference took every scale of the
DOF, a removed one too: a kept effect's reference (force effect or added mass) is now at the
kept scales (:func:`benchmarks.diagnose_independent.held_scales`), converted from the row's
``step_detail`` as :math:`r \\to (r + b)\\,\\rho - b`, :math:`\\rho` the kept scales' product
over every scale's, b the prior's own term (inertia, surge linear drag, net weight; 0 for a
tether or momentum drag). Every other row is left as it is. No diagnosis is run. Usage:

    python -m benchmarks.written_units OUTPUT[,OUTPUT...]

prints, per file, the rows whose reference changes (old -> new reference and error) and the
count within 15 % before and after.
"""

from __future__ import annotations

import argparse
import json

def main(argv=None) -> int:
    from benchmarks.diagnose_independent import converted_rows
    from stripcoef.files import read_text
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("outputs", help="comma-separated printed outputs of "
                                    "benchmarks.diagnose_independent (their 'row' lines)")
    args = ap.parse_args(argv)
    for path in args.outputs.split(","):
        rows = [json.loads(line.split(" row ", 1)[1])
                for line in read_text(path, kind="benchmark output").splitlines()
                if " row {" in line]
        got = converted_rows(rows)
        moved = [g for g in got if "magnitude_truth_before" in g]

        def within(r, key):
            return r.get(key) is not None and r[key] <= 0.15
        claimed = [g for g in moved if "estimate" in g]
        print(f"{path}: {len(rows)} rows, {len(moved)} converted ({len(claimed)} with an "
              f"estimate); within 15 %: {sum(within(g, 'magnitude_error_before') for g in claimed)}"
              f" -> {sum(within(g, 'magnitude_error') for g in claimed)}")
        for g in moved:
            if abs(g["magnitude_truth"] - g["magnitude_truth_before"]) < 1e-12:
                continue
            err = (f", error {100 * g['magnitude_error_before']:.1f} % -> "
                   f"{100 * g['magnitude_error']:.1f} %" if "estimate" in g else "")
            print(f"  {g['vehicle']} {g['category']} {g['seed']} {g['mode']}: g_w "
                  f"{g.get('written_gain', 1.0):.4f}, held scales / all "
                  f"{g['held_scale_ratio']:.4f}, reference {g['magnitude_truth_before']:+.4g} -> "
                  f"{g['magnitude_truth']:+.4g}" + (f", estimate {g['estimate']:+.4g}"
                                                    if "estimate" in g else "") + err)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
