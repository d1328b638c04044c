"""Validation section: geometry/videoray_pro3.yaml against Table I of Wang & Clark (Wang & Clark 2006).

The paper's analytical column is strip theory with Fossen's 2D coefficients, so it is
compared with stripcoef's *pure* strip theory (no 3D corrections); the default corrected
model is shown beside it.  Each term has a tolerance and the reason for it, or is a known
mismatch with its reason (the tests mark those as strict xfail).
"""

from __future__ import annotations

from functools import lru_cache

from validation import ROOT, markdown_table


#: term -> (Table I table, relative tolerance or None for a known mismatch, reason)
COMPARISONS = {
    "Y_vdot": ("table1_added_mass", 0.10,
               "the hull section reproduces the paper's 6.0572 to 0.1 % (it was inferred from "
               "it); the thruster pods and struts, absent from the paper's strips, add 7 %"),
    "Z_wdot": ("table1_added_mass", None,
               "the pods and struts add 18 % in heave (the paper's hull-only strips give "
               "3.9482 to 0.1 %): a geometric difference, not a method error"),
    "X_udot": ("table1_added_mass", None,
               "the paper does not say how its axial term was obtained; Lamb's k1 on the "
               "equal-volume spheroid (L/D = 2.1) gives about half of it"),
    "K_pdot": ("table1_added_mass", None,
               "roll added mass of a near-elliptic section is small "
               "(rho pi (b^2 - h^2)^2 / 8); the paper's 0.0326 needs a section or method it "
               "does not describe"),
    "M_qdot": ("table1_added_mass", None,
               "the paper's rotational terms are 0.35-0.5 of the integral of x^2 m(x) over its "
               "own L = 0.36 m with its own translational values (0.0426, 0.0654): a different "
               "integration length or coefficient was used"),
    "N_rdot": ("table1_added_mass", None, "as M_qdot"),
    "X_uu": ("table1_quadratic_drag", 0.15,
             "drag coefficients from other sources (friction + blunt-body pressure drag vs the "
             "paper's unstated values); the paper's own analytical and experimental columns "
             "differ by 27-36 %, so 15 % is within the method's known spread"),
    "Y_vv": ("table1_quadratic_drag", 0.15, "as X_uu (cross-flow: DNV cylinder curve, kappa)"),
    "Z_ww": ("table1_quadratic_drag", 0.15, "as X_uu"),
    "K_pp": ("table1_quadratic_drag", None,
             "rotational drag from the cross-flow of the pods at their lever arm; the paper's "
             "value implies a smaller arm or coefficient it does not give"),
    "M_qq": ("table1_quadratic_drag", None,
             "cross-flow integral of |x|^3 c(x) over the hull; the paper's value is 4x smaller "
             "without a stated reason"),
    "N_rr": ("table1_quadratic_drag", None, "as M_qq"),
    "X_u": ("table1_linear_drag", None,
            "the paper's linear terms are 28-39 % of its quadratic ones at 1 m/s; no Reynolds "
            "dependence of the drag gives a linear part that large (stripcoef's power-law split "
            "gives < 1 %); the paper does not document its linear model"),
    "Y_v": ("table1_linear_drag", None, "as X_u"),
    "Z_w": ("table1_linear_drag", None, "as X_u"),
}


@lru_cache(maxsize=1)
def _models():
    from stripcoef.assembly.estimate import estimate
    from stripcoef.geometry.vehicle import load_vehicle

    v = load_vehicle(ROOT / "geometry" / "videoray_pro3.yaml")
    # pure: the paper's strip theory (a bluff vehicle file's default added mass is the 3D
    # panel method's since issue 32)
    return estimate(v, corrections=False, added_mass_method="strips"), estimate(v)


def hull_only_added_mass():
    """Pure strip theory on the VideoRay hull alone (no pods, struts): Y_vdot, Z_wdot [kg]."""
    from stripcoef.assembly.estimate import estimate
    from stripcoef.geometry.vehicle import parse_vehicle

    v = parse_vehicle({"name": "VideoRay hull", "fluid": {"density": 1000.0,
                                                          "kinematic_viscosity": 1e-6},
                       "hull": {"half_breadth": [{"type": "cylinder", "x": [-0.18, 0.18],
                                                  "radius": 0.05909}],
                                "half_height": [{"type": "cylinder", "x": [-0.18, 0.18],
                                                 "radius": 0.07318}]}}, file="<videoray hull>")
    c = estimate(v, corrections=False, added_mass_method="strips").coefficients()
    return -c["Y_vdot"], -c["Z_wdot"]


def comparison():
    """Rows: term, analytical, experimental, pure strip, corrected, diff %, rtol, ok, reason."""
    from validation.reference import load_table

    pure, corrected = _models()
    cp, cc = pure.coefficients(), corrected.coefficients()
    rows = []
    for term, (table, rtol, reason) in COMPARISONS.items():
        ref = {r["name"]: r["value"] for r in load_table("videoray_pro3", table)}
        ana = ref[f"{term}.analytical"]
        exp = ref.get(f"{term}.experimental")
        ours = abs(cp.get(term, 0.0))
        diff = 100.0 * (ours / ana - 1.0)
        ok = rtol is not None and abs(diff) <= 100 * rtol
        rows.append({"term": term, "analytical": ana, "experimental": exp, "pure": ours,
                     "corrected": abs(cc.get(term, 0.0)), "diff_percent": diff, "rtol": rtol,
                     "ok": ok, "reason": reason})
    return rows


def section() -> str:
    rows = comparison()
    y, z = hull_only_added_mass()
    out = ["## VideoRay Pro III against Table I (Wang & Clark 2006)", "",
           "`geometry/videoray_pro3.yaml`, fresh water, reference speed 0.5 m/s. Magnitudes "
           "(SNAME derivative = −value). *pure* = strip theory without 3D corrections (the "
           "paper's method); *corrected* = the default model (its added mass by the 3D panel "
           "method on the parts united: a bluff vehicle file, issue 32). A tolerance is the "
           "agreement the "
           "tests assert; *mismatch* rows are strict xfails with the reason given.", "",
           f"Consistency of the inferred hull section: the hull alone gives Y_vdot = {y:.4f} "
           f"and Z_wdot = {z:.4f} kg against the paper's 6.0572 and 3.9482.", ""]
    out.append(markdown_table(
        ["term", "Table I analytical", "Table I experimental", "stripcoef pure",
         "stripcoef corrected", "diff % (pure)", "tolerance", "reason"],
        [(r["term"], f"{r['analytical']:.4g}",
          "NA" if r["experimental"] is None else f"{r['experimental']:.4g}",
          f"{r['pure']:.4g}", f"{r['corrected']:.4g}", f"{r['diff_percent']:+.1f}",
          (f"{100 * r['rtol']:.0f} % " + ("pass" if r["ok"] else "FAIL"))
          if r["rtol"] is not None else "mismatch", r["reason"]) for r in rows]))
    return "\n".join(out) + "\n"
