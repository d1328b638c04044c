"""Validation section: the papers' cases of the closed-loop diagnosis (issue 7).

The same computations as tests/test_diagnose_papers.py (validation.cases).
"""

from __future__ import annotations

from validation import markdown_table


def section() -> str:
    from validation.cases import (TETHER_CD, TETHER_CF, VIDEORAY_TETHER_DIAMETER, romeo_case,
                                  videoray_case)

    out = ["## Diagnosis: the papers' cases (issue 7)", ""]
    vr = videoray_case(seed=0)
    gap = vr["gap"]
    out += ["### VideoRay Pro III surge and its tether (Wang & Clark 2006, sec. IV.A)", "",
            "The paper's model predicted 0.51 m/s at n = 60 and the pool measured 0.47 m/s; the "
            "authors blamed the unmodelled tether. With Table I's experimental X_u = 0.946 N s/m "
            "and X_u|u| = 6.04 N s^2/m^2, the thrust that gives 0.51 m/s is "
            f"{gap['thrust']:.3f} N, and at 0.47 m/s the hull drag takes only "
            f"{gap['thrust'] - gap['tether_force']:.3f} N: the tether must take "
            f"**{gap['tether_force']:.3f} N**, i.e. c_t L = {gap['c_t_L']:.3f} N s^2/m^2 "
            "(F = c_t L u|u|). Assuming the VideoRay tether diameter "
            f"{1000 * VIDEORAY_TETHER_DIAMETER:.1f} mm, that is {gap['length_cross_flow']:.2f} m "
            f"of tether in full cross-flow (C_d = {TETHER_CD}) or {gap['length_along_flow']:.1f} m "
            f"trailing along the flow (skin friction C_f = {TETHER_CF}): a few metres of trailing "
            "tether explain the gap. (Our reconstruction of the model from Table I, C_t forward "
            f"and two thrusters at n = 60, predicts {gap['table_speed']:.3f} m/s rather than the "
            "printed 0.51 m/s; the generated pool runs use the thrust that reproduces 0.51 m/s.)",
            ""]
    rows = []
    for key, label in (("with_tether_length", "with a tether_length column (3 to 15 m)"),
                       ("without_tether_length", "without (the paper's situation)")):
        r = vr[key]
        s = r["per_dof"]["surge"]
        steps = ", ".join(f"{st['effect']} c_t = {st['parameters']['c_t']:.4f} ± "
                          f"{st['std']['c_t']:.4f}"
                          + (" (removed by the validation)" if st.get("kept") is False else "")
                          for st in r["steps"]) or "none"
        rows.append([label, r["baseline_error"], r["calibrated_error"], r["final_error"],
                     f"{s['calibration']['band_z']['D_Q']:+.2f}", steps])
    out += ["Diagnosis of generated pool runs (n = 30 to 90, both ways; tether drag per metre "
            f"c_t = {vr['c_t_truth']:.4f} N s^2/m^3 chosen to close the gap at mid length; noise "
            "1 cm/s):", "",
            markdown_table(["log", "baseline [N]", "calibrated [N]", "final [N]",
                            "D_Q moved (bands)", "effects added"], rows), "",
            "With the paid-out length logged, the tether's signature (drag growing with the "
            "length) identifies it and its coefficient. Without it the tether is a 20 % larger "
            "X_u|u|, inside strip theory's 30 % band: the calibration absorbs it and the "
            "diagnosis says so instead of naming an effect — the data of the paper could not "
            "have told a tether from a larger drag coefficient." + _removed_text(vr), ""]
    rc = romeo_case(seed=0)
    shrink = [(abs(r["standard_buoyancy"] - r["weight_truth"]),
               abs(r["eta_buoyancy"] - r["weight_truth"])) for r in rc]
    rows = []
    for row in rc:
        d = row["diagnosis"]
        steps = d["steps"]
        eta = next((s["final_parameters"] for s in steps if s["effect"] == "thrust_asymmetry"),
                   None)
        rows.append([row["experiment"], f"{row['weight_truth']:+.2f}",
                     f"{row['standard_buoyancy']:+.2f} ± {row['standard_buoyancy_std']:.2f}",
                     f"{row['eta_buoyancy']:+.2f} ± {row['eta_buoyancy_std']:.2f}",
                     "-" if eta is None else f"{eta['eta_backward'] / eta['eta_forward']:.3f}",
                     ", ".join(s["effect"] for s in steps) or "none",
                     f"{d['baseline_error']:.2f} → {d['final_error']:.2f}"])
    out += ["### ROMEO heave and the propeller-hull interaction (Indiveri 1998, sec. 4.2.4)", "",
            "Five generated heave experiments (applied force ±10 to ±60 N held 20 s; upward "
            "force delivered with eta = 0.57; one 2 kg lead per experiment, experiment 3 "
            "neutral; heave velocity noise 5 mm/s). The prior is the chapter's standard model "
            "(k_w = 116 N s/m, k_w|w| = 403 N s^2/m^2, eq. 4.17), neutrally buoyant. W is the "
            "net weight, down positive [N]:", "",
            markdown_table(["exp.", "W truth", "W, standard model", "W, with efficiency",
                            "eta_up / eta_down found", "effects added (in order)",
                            "error [N] before → after"], rows), "",
            "As in the chapter, the standard model compensates the over-estimated upward thrust "
            "with weight: its buoyancy estimate is biased (toward heavy) in all five experiments. "
            "The diagnosis finds the direction-dependent efficiency from the residuals in every "
            "experiment, and with it the weight bias shrinks "
            + ", ".join(f"{b:.1f} → {a:.1f} N" for b, a in shrink) + " (experiments 1-5). "
            + _within_text(rc) + " In the neutral experiment no buoyancy term is added "
            "at all.", ""]
    return "\n".join(out)


def _removed_text(vr) -> str:
    """What the validation by free simulation did with the tether (the final error is the
    written model's: a removed step is not in it)."""
    r = vr["with_tether_length"]
    if all(st.get("kept", True) for st in r["steps"]):
        return ""
    val = r["validation"]
    return (" The validation by free simulation (the last quarter of the fitting log, "
            f"{val['validation_s'][0]:.0f}-{val['validation_s'][1]:.0f} s) then removed the "
            "tether from the written model: its surge error there is "
            f"{val['all_changes']['surge']:.4f} m/s with it and "
            f"{val['kept_changes']['surge']:.4f} m/s without (prior "
            f"{val['prior']['surge']:.4f}), so the final error is the calibrated model's.")


def _within_text(rc) -> str:
    """Which experiments' weight with the efficiency lies within 3 sigma of the truth."""
    off = [r["experiment"] for r in rc
           if abs(r["eta_buoyancy"] - r["weight_truth"]) >= 3 * r["eta_buoyancy_std"]]
    if not off:
        return "Every estimate with the efficiency lies within 3σ of the truth."
    return ("Within 3σ of the truth in all but experiment(s) " + ", ".join(map(str, off))
            + ", where the fitted scale (inertia, efficiency) comes out high and the bias, "
            "though much smaller, stays beyond its error bar (a strict xfail in "
            "tests/test_diagnose_papers.py; cause not traced).")
