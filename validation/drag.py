"""Validation section: whole-body drag against measured simple bodies (issue 35).

The bodies, sizes and Reynolds number are those of validation/drag_bodies.py (its docstring);
the references are reference_tables/body_drag_3d (Hoerner 1965 via public copies). Each row is
held out (no number of it is an input of the model) or built from one of the model's own
curves (drag_bodies.BUILT_FROM): the latter check only that a mesh reaches its curve, and are
not used to measure the method's band (scripts/make_method_uncertainty.py).
"""

from __future__ import annotations

import warnings

import numpy as np

from validation import markdown_table

#: the issue's target: every translational term within 25 % of its reference
TARGET = 0.25


def _rows():
    from validation import drag_bodies as db
    from stripcoef.assembly.estimate import estimate
    from stripcoef.conventions import quadratic_damping_name
    from stripcoef.study.shapes import shape_class

    out = []
    for name in db.BODIES:
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            # the section reads the damping only, which does not read the 2D sections' added
            # mass: 16 panels per section instead of the adaptive 96+ (every body's linear and
            # quadratic damping and short-body conditions bit for bit the same; 12.5 -> 6.5 s
            # of CPU for the section)
            veh, model, rows = db.compare(name, lambda v: estimate(
                v, added_mass_method="strips", speed=db.SPEED, section_panels=16))
        short = dict(model.conditions.get("short_body_crossflow", {}))
        cls = shape_class(veh)             # slices the body: once per body, not per row
        for r in rows:
            k = r["dof"]
            sb = [v["yz"[k - 1]] for v in short.values() if k and "yz"[k - 1] in v]
            method = (model.conditions.axial_drag_method + (" (astern)" if r["astern"] else "")
                      if k == 0 else
                      f"short body ({sb[0]['class']}, w {sb[0]['weight']:.2f})" if sb else
                      "cross-flow strips")
            out.append({"body": name, "class": cls,
                        "term": quadratic_damping_name(k, k) + (" astern" if r["astern"] else ""),
                        "model": r["cd_model"], "ref": r["cd_ref"], "row": r["row"],
                        "area": r["area"], "held_out": r["held_out"],
                        "built_from": r["built_from"],
                        "method": method, "d_q": r.get("cd_d_q")})
    return out


def section() -> str:
    rows = _rows()
    table = []
    for r in rows:
        err = r["model"] / r["ref"] - 1.0
        table.append([r["body"], r["class"], r["term"], f"{r['model']:.3f}",
                      f"{r['ref']:.3f} ({r['row']})", r["area"], f"{100 * err:+.1f} %",
                      f"{np.log(r['model'] / r['ref']):+.3f}", r["method"],
                      "held out" if r["held_out"] else f"built from {r['built_from']}"])
    summary = []
    for cls in sorted({r["class"] for r in rows}):
        held = [np.log(r["model"] / r["ref"]) for r in rows
                if r["class"] == cls and r["held_out"]]
        if not held:
            continue
        within = sum(abs(np.exp(e) - 1.0) <= TARGET for e in held)
        distinct = len({r["row"] for r in rows if r["class"] == cls and r["held_out"]})
        summary.append([cls, len(held), distinct, f"{within}/{len(held)}",
                        f"{np.sqrt(np.mean(np.square(held))):.3f}",
                        f"{np.std(held, ddof=1) if len(held) > 1 else 0.0:.3f}",
                        f"{max(held, key=abs):+.3f}"])
    built = [abs(np.log(r["model"] / r["ref"])) for r in rows if not r["held_out"]]
    astern = [r for r in rows if r["term"].endswith("astern")]
    missed = [r for r in rows if r["held_out"] and abs(r["model"] / r["ref"] - 1.0) > TARGET]
    return "\n".join([
        "## Whole-body drag against measured simple bodies (issue 35)\n",
        "`python -m benchmarks.drag_bodies`: closed meshes of size D = 0.1 m in water at 1 m/s "
        "(Re = 1e5 on D), the model's quadratic term over the reference's area, "
        "C_D = |D_Q[k,k]| / (1/2 rho A), against the measured whole-body drag of "
        "reference_tables/body_drag_3d (Hoerner 1965 via public copies: which copy, its page and "
        "figure in each row). `method`: how the model got the term "
        "(`damping.damping_matrices`; axial: `measured_short_body` the measured drag of "
        "ellipsoids, `blunt` (flat bow) the measured drag of flat-ended bodies end-on, "
        "`blunt_base` (closed bow, flat stern) the measured drag of ellipsoids of its L/D, "
        "`form_factor` friction with Hoerner's streamlined-body form factor; sway and heave: "
        "`cross-flow strips`, or `short body` for a part no longer than its section "
        "(`damping.short_body_crossflow`: L / max(height across, depth along the flow) below 2, "
        "the whole-body drag of a short body of its class seen along the flow, `flat` (a flat "
        "face meets the flow: the flat-ended bodies' curve) or `closed` (the ellipsoids'), with "
        "the share w of it, 1 at L/max <= 1, bridged linearly to the strips at 2)). A row *built "
        "from* one of the model's curves is not an independent check (the number is the "
        "model's input): it shows that a mesh reaches its curve with the right L/D, aspect ratio "
        "and area, and is not used to measure the method's band. The `astern` row compares the "
        "model's surge drag going astern (`conditions.surge_quadratic_damping_astern`, reported "
        "with a warning when it differs from the drag going ahead by more than 1.5x), not its "
        "|u|u term, which holds the drag going ahead (Fossen's D_Q is symmetric in the sign of "
        "u): against X_uu itself the hemisphere flat face first is "
        + ", ".join(f"{100 * (r['d_q'] / r['ref'] - 1):+.1f} %" for r in astern) + ".\n",
        markdown_table(["body", "class", "term", "C_D model", "C_D measured (row)", "area",
                        "error", "ln(model/ref)", "method", "role"], table),
        "\nHeld-out rows per shape class (the rows the method's translational drag band is "
        "measured from, scripts/make_method_uncertainty.py); the target of issue 35 is every "
        f"term within {100 * TARGET:.0f} % and sd(ln) below 0.25:\n",
        markdown_table(["class", "held-out terms", "measured values", f"within {100 * TARGET:.0f} %",
                        "rms ln", "sd ln", "largest ln"], summary),
        f"\nBuilt-from rows: largest |ln(model/ref)| {max(built):.3f} over {len(built)} rows "
        "(the mesh's plain friction and its L/D against the curve's printed points). "
        "A hull with a closed bow and a flat stern only (the cones apex-first, the hemisphere "
        "dome-first: bow at +x) takes the measured drag of closed bodies of its L/D, the "
        "ellipsoids: the rule was chosen after these rows had been seen with the flat-ended "
        "curve (+0.64 to +1.06 in ln), so for that choice they are not a clean hold-out. The "
        "short-body cross-flow rule was chosen after the sphere across (+48.5 % by the strips) "
        "and the cube turned 45 deg in sway (+128 %) had been seen; it has no parameter fitted "
        "to them (its curves are the axial ones, its bounds the length factor's first L/D and "
        "L = section size), and the sphere across is now built from the ellipsoid curve's L/d 1 "
        "point (0.47, by the sphere's symmetry), not held out. `cube_edge_x` repeats the cube's "
        "measured values through another path of the model (diamond sections): more terms, not "
        "more data. "
        + ("Every held-out term is within the target." if not missed else "Not met: " + "; ".join(
            f"{r['body']} {r['term']} {100 * (r['model'] / r['ref'] - 1):+.1f} %"
            for r in missed) + ".")
        + " Nearest the limit: "
        + "; ".join(f"{r['body']} {r['term']} {100 * (r['model'] / r['ref'] - 1):+.1f} %"
                    for r in sorted((r for r in rows if r["held_out"]),
                                    key=lambda r: -abs(np.log(r["model"] / r["ref"])))[:3])
        + " (the finite cylinder across: the closed-body curve at its depth over equal-circle "
        "diameter, where its flat ends separate the flow at sharp edges, which the ellipsoids' "
        "do not; the cube edge-on: the ellipsoids' curve at its L/D on the projected area, a "
        "body of revolution's drag for a prism).\n",
    ])
