"""docs/validation.md: held-out prediction on logs as users have them (issue 33).

Reads the stored run of ``benchmarks/real_logs.py``
(``reference_tables/real_logs/heldout.csv``: its command on the first line, then one row per
log, split and excited DOF; columns in ``reference_tables/real_logs/README.md``).
"""

from __future__ import annotations

from validation import ROOT, markdown_table, read_stored_run

DATA = ROOT / "reference_tables" / "real_logs" / "heldout.csv"
#: The stored oracle run (``--oracle-only``), joined to a held-out run that lacks its columns.
ORACLE = ROOT / "reference_tables" / "real_logs" / "oracle.csv"
#: The stored attribution run (``python -m benchmarks.real_logs --attribution K``).
ATTRIBUTION = ROOT / "reference_tables" / "real_logs" / "attribution.csv"
#: Its models and predictors, as its columns name them, and as the table shows them.
ATTRIBUTION_COLUMNS = {"prior": "prior", "prior_true_thrusters": "prior, true thrusters",
                       "true_matrices_prior_thrusters": "true matrices, prior thrusters",
                       "truth_coefficients": "truth's coefficients",
                       "hold_last_velocity": "hold-last-velocity",
                       "zero_velocity": "zero velocity"}


def attribution_section() -> list:
    """The attribution table (one row per horizon and DOF) and its command, or nothing."""
    if not ATTRIBUTION.exists():
        return []
    command, rows = read_stored_run(ATTRIBUTION)
    table = [[f"{float(r['horizon_s']):g}", r["dof"],
              *(_num(r[c]) for c in ATTRIBUTION_COLUMNS)] for r in rows]
    return [f"Where the error comes from, on {rows[0]['log']} ({rows[0]['truth']}), the whole "
            f"log as read back, no fit: `{command}`. *prior, true thrusters*: the prior with "
            "the truth's per-thruster coefficients; *true matrices, prior thrusters*: the "
            "truth's added mass, damping and buoyancy with the prior's thrusters [m/s or "
            "rad/s].\n",
            markdown_table(["horizon [s]", "DOF", *ATTRIBUTION_COLUMNS.values()], table), ""]


#: The stored analysis of why even the truth loses (``python -m benchmarks.real_logs --why K``).
WHY = ROOT / "reference_tables" / "real_logs" / "why.csv"
#: Its per-DOF columns, as the table shows them.
WHY_COLUMNS = {"truth_noise_free": "truth, noise-free log",
               "truth_noisy": "truth, noisy log",
               "simulator_noisy_start": "simulator itself, noisy start",
               "noise_growth_truth": "noise growth (truth)",
               "noise_growth_prior": "noise growth (prior)",
               "twin_spread_prior": "twin spread (prior)",
               "hold_last_velocity": "hold-last-velocity", "zero_velocity": "zero velocity"}


def why_section() -> list:
    """The stored analysis of why even the truth loses in some DOFs (per DOF, and the
    linearised stability per speed), and its command, or nothing."""
    if not WHY.exists():
        return []
    command, rows = read_stored_run(WHY)
    per_dof = [r for r in rows if r["kind"] == "dof"]
    speeds = [r for r in rows if r["kind"] == "speed"]
    table = [[r["dof"], *(_num(r[c]) for c in WHY_COLUMNS)] for r in per_dof]
    stab = "; ".join(f"{float(r['speed_m_s']):g} m/s: {float(r['largest_real_part']):+.3f} 1/s "
                     f"({r['leading_dof']})" for r in speeds)
    return [f"The analysis, on {per_dof[0]['log']} ({per_dof[0]['truth']}) made without "
            f"sensor noise and then with it added: `{command}` (`benchmarks.real_logs.why`; "
            "*simulator itself*: the independent simulator's own 10-s free simulations from "
            "the noisy starting states against the noise-free velocities; *twin spread*: the "
            "noise carried along the model's own simulation instead of the log) [m/s or "
            "rad/s].\n",
            markdown_table(["DOF", *WHY_COLUMNS.values()], table), "",
            f"Largest real part of the truth's linearised eigenvalues at steady surge, and "
            f"the DOF leading its eigenvector: {stab}.\n"]


def _num(s):
    return f"{float(s):.4f}" if s not in ("", "None") else "diverged"


def summary(rows) -> dict:
    """Counts of the stored run: (log, split, DOF) rows, those where the calibrated model
    beats all three other predictors, and the (log, split) pairs where it does in every
    excited DOF; for the logs whose truth is known (``truth_coefficients``: the oracle), the
    rows where even the truth loses to a trivial predictor (not predictable over the
    horizon) and the calibrated model's count on the others."""
    pairs = {}
    for r in rows:
        pairs.setdefault((r["log"], r["split"]), []).append(r["beats_all"] == "1")
    known = [r for r in rows if r.get("truth_beats_trivial", "") in ("0", "1")]
    predictable = [r for r in known if r["truth_beats_trivial"] == "1"]
    return {"rows": len(rows), "beats": sum(r["beats_all"] == "1" for r in rows),
            "known": len(known), "unpredictable": len(known) - len(predictable),
            "predictable": len(predictable),
            "beats_predictable": sum(r["beats_all"] == "1" for r in predictable),
            "pairs": len(pairs), "pairs_all": sum(all(v) for v in pairs.values()),
            **_predictable_counts(rows, known),
            "prior_beats_trivial": sum(r["prior_beats_trivial"] == "1" for r in rows),
            "real": sum(r["kind"] == "real" for r in rows),
            "unchanged": sum(r["calibrated"] == r["prior"] for r in rows)}


#: The paired tests' records of a stored run (``benchmarks.real_logs.paired_tests``): the
#: verdict column, the truth's verdict column and what the segments are.
PAIRED = (("roll_verdict", "roll_truth_verdict", "10-s simulations restarted every 2 s"),
          ("h2_verdict", "h2_truth_verdict", "consecutive 2-s simulations"))


def verdicts(rows, column) -> dict:
    """``{"win": n, "loss": n, "not distinguishable": n}`` of ``column`` over ``rows``."""
    out = {"win": 0, "loss": 0, "not distinguishable": 0}
    for r in rows:
        if r.get(column, "") in out:
            out[r[column]] += 1
    return out


def paired_section(rows) -> list:
    """A paragraph on the paired Diebold-Mariano verdicts of the stored run (the columns of
    :data:`PAIRED` it has; none: nothing): the calibrated model's against the prior and the
    two trivial predictors, over all rows and the excited and predictable ones, and the
    truth's against the two trivial predictors (could any model win the cell)."""
    parts = []
    for col, truth_col, what in PAIRED:
        if not any(r.get(col, "") for r in rows):
            continue
        a, p = verdicts(rows, col), verdicts([r for r in rows if predictable(r)], col)
        t = verdicts(rows, truth_col)
        parts.append(f"on {what}: {a['win']} wins, {a['loss']} losses, "
                     f"{a['not distinguishable']} not distinguishable of {sum(a.values())} "
                     f"({p['win']} / {p['loss']} / {p['not distinguishable']} of the excited "
                     f"and predictable); the truth beats both trivial predictors in "
                     f"{t['win']} of {sum(t.values())}")
    if not parts:
        return []
    return ["**Paired tests per cell** (`stripcoef.diagnose.heldout.paired_verdicts`: the "
            "Diebold-Mariano test of the per-segment losses; win: below the prior, "
            "hold-last-velocity and zero velocity, one-sided 5 % each; loss: above one of "
            "them at 5 %/3; otherwise not distinguishable): " + "; ".join(parts) + ".\n"]


def _growth_verdict(r, key) -> str:
    """'1' when the noise growth ``key`` of row ``r`` is below both trivial predictors'
    errors (heldout.predictable), '0' when not, '' when the row has none."""
    if r.get(key, "") in ("", "None"):
        return ""
    trivial = min(float(r["hold_last_velocity"]), float(r["zero_velocity"]))
    return "1" if float(r[key]) < trivial else "0"


def predictable(r) -> bool:
    """Whether row ``r`` counts among the excited and predictable ones: the rule of
    heldout.predictable with the prior's and the calibrated model's noise growth (exempted
    only where each of them reaches both trivial predictors' errors; a row without a growth
    counts, a row with the prior's alone is judged by it)."""
    verdicts = [_growth_verdict(r, f"noise_growth_{m}") for m in ("prior", "calibrated")]
    known = [v for v in verdicts if v]
    return not known or any(v != "0" for v in known)


def _predictable_counts(rows, known) -> dict:
    """The counts on the excited and predictable rows (:func:`predictable`; a run without the
    noise growth judges every row), and how often each model's noise-growth verdict is the
    truth's."""
    judged = [r for r in rows if predictable(r)]
    pairs = {}
    for r in judged:
        pairs.setdefault((r["log"], r["split"]), []).append(r["beats_all"] == "1")
    agree = {m: sum(_growth_verdict(r, f"noise_growth_{m}") == r["truth_beats_trivial"]
                    for r in known) for m in ("calibrated", "prior", "truth")}
    rule = sum(("1" if predictable(r) else "0") == r["truth_beats_trivial"] for r in known
               if r.get("noise_growth_prior", "") not in ("", "None"))
    return {"judged": len(judged), "beats_judged": sum(r["beats_all"] == "1" for r in judged),
            "growth_agrees_rule": rule,
            "pairs_judged": len(pairs), "pairs_judged_all": sum(all(v) for v in pairs.values()),
            "growth_known": sum(r.get("noise_growth_prior", "") not in ("", "None")
                                for r in known),
            **{f"growth_agrees_{m}": n for m, n in agree.items()}}


#: The columns a stored oracle run gives the held-out rows that lack them (the oracle is
#: computed without diagnosing, :func:`with_oracle`).
ORACLE_KEYS = ("truth_coefficients", "truth_beats_trivial", "noise_growth_prior",
               "noise_growth_truth")


def with_oracle(rows) -> tuple:
    """``rows`` with the columns of the stored oracle run (:data:`ORACLE`, joined by log,
    split and DOF) that the rows lack, and that run's command (or None)."""
    if not ORACLE.exists():
        return rows, None
    command, oracle = read_stored_run(ORACLE)
    by_key = {(r["log"], r["split"], r["dof"]): r for r in oracle}
    keys = ORACLE_KEYS
    out, used = [], False
    for r in rows:
        o = by_key.get((r["log"], r["split"], r["dof"]), {})
        fill = {k: o.get(k, "") for k in keys if r.get(k, "") in ("", None)}
        used = used or any(fill.values())
        out.append({**r, **fill})
    return out, (command if used else None)


def section() -> str:
    if not DATA.exists():
        return ""
    command, rows = read_stored_run(DATA)
    rows, oracle_command = with_oracle(rows)
    s = summary(rows)
    table = [[r["log"], r["split"], r["dof"], _num(r["prior"]), _num(r["calibrated"]),
              _num(r["hold_last_velocity"]), _num(r["zero_velocity"]),
              _num(r["truth_coefficients"]) if r.get("truth_coefficients") else "-",
              *(_num(r[k]) if r.get(k, "") not in ("", "None") else "-"
                for k in ("noise_growth_prior", "noise_growth_truth")),
              ("yes" if predictable(r) else "no") if r.get("noise_growth_prior", "") not in
              ("", "None") else "-",
              "yes" if r["beats_all"] == "1" else "**no**"] for r in rows]
    logs = {}
    for r in rows:
        logs.setdefault(r["log"], r)
    described = [f"- {name}: {r['truth']}; {r['rows']} rows at {float(r['rate_hz']):.3g} Hz "
                 f"as read back; command-clock offset estimated "
                 f"{float(r['clock_offset_s']):+.3f} s (truth -0.350 s)"
                 if r["clock_offset_s"] else f"- {name}: {r['truth']}"
                 for name, r in logs.items()]
    effects = sorted({(r["log"], r["split"], r["effects_written"]) for r in rows})
    dropped = sorted({(r["log"], r["split"], r["not_diagnosed"]) for r in rows
                      if r["not_diagnosed"] != "none"})
    parts = [
        "## Held-out prediction on logs as users have them (issue 33)\n",
        "The target: on held-out real-style logs (and on any real public log), the calibrated "
        "model beats the prior, hold-last-velocity and zero velocity in every excited DOF, on "
        "both splits. **No real public log with actuation could be read here** "
        "(`reference_tables/real_logs/README.md` lists the sources looked at; the closest, "
        "the BlueROV2 Heavy tank runs of ViktorNfa/bluerov2_dynamics, MIT, are Git LFS "
        "objects absent from the mirror; `--mirror DIR` runs them where they are). "
        f"Stored real-log rows: {s['real']}.\n",
        "The real-style logs are written as loggers write them and read back through "
        "`stripcoef.ingest`: a navigation stream in ROS conventions (ENU, FLU, quaternions, "
        "epoch stamps) and a 50-Hz stream of ArduSub-like PWM commands (whole microseconds) "
        "stamped by a second computer 0.35 s ahead, each in one-minute chunk files, the clocks "
        "aligned by the depth both record. *forward*: fitted on the first 70 %, errors on the "
        "last 30 % (`diagnose --holdout 0.3`); *reverse*: fitted on the last 70 %, errors on "
        "the first 30 %. Errors: RMS of 10-s free simulations from the logged state [m/s or "
        "rad/s] (`diagnose/heldout.py`).\n",
        f"Command: `{command}`" + (f"; the column *truth*: "
                                   f"`{oracle_command}`" if oracle_command else "") + "\n",
        *described, "",
        markdown_table(["log", "split", "DOF", "prior", "calibrated", "hold-last-velocity",
                        "zero velocity", "truth", "noise growth (prior)",
                        "noise growth (truth)", "predictable", "calibrated beats all three"],
                       table),
        "",
        f"The calibrated model beats the prior, hold-last-velocity and zero velocity in "
        f"**{s['beats']} of {s['rows']}** (log, split, excited DOF); in every excited DOF of "
        f"**{s['pairs_all']} of {s['pairs']}** (log, split) pairs. In the **excited and "
        f"predictable** DOFs (column *predictable*, the rule below) it beats all three in "
        f"**{s['beats_judged']} of {s['judged']}**, in every one of them in "
        f"**{s['pairs_judged_all']} of {s['pairs_judged']}** pairs. The prior alone beats both "
        f"trivial predictors in {s['prior_beats_trivial']} of {s['rows']}. In {s['unchanged']} of "
        f"{s['rows']} the calibrated model predicts exactly as the prior: the diagnosis's "
        "validation by free simulation removed every change of that DOF (a change is kept only "
        "if it improves the free simulation of data it was not fitted on, and a DOF's own "
        "changes only if that DOF then simulates the validation part better than the prior: "
        "`diagnose/validate.py`), so it cannot beat the prior there. The thrusters' lag is "
        "fitted once for all DOFs (`diagnose.calibrate.share_timing`).\n",
        *paired_section(rows),
        *([f"**Why even the vehicle's own model loses in some DOFs.** The column *truth* is the "
           f"BlueROV2-Heavy-like logs' own vehicle (the simulator's perturbed coefficients "
           f"and thrusters, its undeclared effect as the effects library writes it: "
           f"`benchmarks.real_logs.truth_model`) simulated the same way: it loses to a "
           f"trivial predictor in **{s['unpredictable']} of {s['known']}** of those rows (on "
           f"the {s['predictable']} others the calibrated model beats all three in "
           f"{s['beats_predictable']}). Not the replay: on a noise-free log of the simulator "
           f"the truth, replayed as here, gives its velocities back to 1e-3 m/s or rad/s "
           f"(`tests/test_real_logs.py`), and the log read back through `stripcoef.ingest` "
           f"(frames, PWM, clocks) gives the truth the errors of the simulator's own log. The "
           f"starting state is: the sensors' noise on it grows within the 10 s because the "
           f"vehicle, steadied in the log by its pilot's holds, is unstable open-loop under "
           f"way (the Munk moment of its added mass, (Y_vdot - X_udot) u v in yaw and "
           f"(Z_wdot - X_udot) u w in pitch, against no restoring moment in yaw and the small "
           f"metacentric one in pitch; roll and pitch are almost undamped). *noise growth*: "
           f"that noise (the log's own white noise, second differences, 3 draws) carried "
           f"along the logged motion by a model's dynamics, RMS over the segments "
           f"(`stripcoef.diagnose.heldout.noise_growth`: the tangent-linear growth of a "
           f"predictability study, Lorenz 1965, Tellus 17; Kalnay 2003, sec. 6.3); with the "
           f"truth's dynamics it is of the size of the truth's own error where the truth "
           f"loses.\n"] if s["known"] else []),
        *why_section(),
        "**Excited and predictable** (`stripcoef.diagnose.heldout.predictable`): a DOF the "
        "diagnosis found excited whose noise growth with the prior's or with the calibrated "
        "model's dynamics stays below both trivial predictors' errors (exempted only where "
        "both reach them). Where it does not, the noise on the starting state alone moves "
        "any prediction farther from the data than predicting no change or no motion, and the "
        "comparison measures the noise, not the model (a simulation error is judged on fresh "
        "data over a horizon on which the process is predictable: Ljung 1999, sec. 16.4). "
        "The rule uses no truth; the prior is fixed before the fit, so no calibration can "
        "exempt its own DOFs, and a prior whose dynamics are wrong cannot exempt a DOF the "
        "calibrated model predicts" + (
            f"; its verdict is the truth's (the truth beats both trivial predictors or not) "
            f"in **{s['growth_agrees_rule']} of {s['growth_known']}** rows (the prior's "
            f"growth alone: {s['growth_agrees_prior']}; the truth's own dynamics: "
            f"{s['growth_agrees_truth']}"
            + (f", with the calibrated model's in {s['growth_agrees_calibrated']}"
               if s["growth_agrees_calibrated"] else "") + ").\n"
            if s["growth_known"] else ".\n"),
        *attribution_section(),
        "Effects in the written models: " + "; ".join(
            f"{log} ({split}): {eff}" for log, split, eff in effects) + ".\n",
        *(["DOFs not diagnosed (`dof=\"all\"`): " + "; ".join(
            f"{log} ({split}): {why}" for log, split, why in dropped) + ".\n"]
          if dropped else [])]
    return "\n".join(parts)
