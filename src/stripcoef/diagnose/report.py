"""Text and markdown renderings of a diagnosis (``stripcoef diagnose``), with residual plots."""

from __future__ import annotations

from pathlib import Path

import numpy as np

from stripcoef.files import write_text
from stripcoef.diagnose.result import Diagnosis
from stripcoef.diagnose.settings import (BANDS, MIMIC_BANDS, MIN_DELTA_BIC, MIN_HELD_OUT_GAIN,
                                        MIN_Z, N_BLOCKS, TIE, UNEXPLAINED_GAIN)


def _fmt(x, digits=4):
    if x is None:
        return "-"
    if isinstance(x, bool):
        return "yes" if x else "no"
    if isinstance(x, (int, float, np.floating)):
        return f"{float(x):.{digits}g}"
    return str(x)


def _params(p, s=None):
    s = s or {}
    return ", ".join(f"{k} = {_fmt(v)}" + (f" ± {_fmt(s[k], 2)}" if k in s else "")
                     for k, v in p.items())


def _written(cal) -> dict:
    """{coefficient: its value in the written model} of a DOF's calibration record (the
    prior plus the final change for a record without ``written``)."""
    if "written" in cal:
        return dict(cal["written"])
    return {k: cal["prior"][k] + v for k, v in cal.get("final_parameters",
                                                        cal["parameters"]).items()}


def _step_params(s) -> str:
    """A step's parameters in words; for one whose value one DOF does not determine
    (``not_determined``, :mod:`stripcoef.diagnose.undetermined`) that, with the values
    fitted with each thruster's gain free and with the prior's thrust map."""
    nd = s.get("not_determined")
    if not nd:
        return _params(s["parameters"], s["std"])
    return (f"{nd['parameter']} not determined by one DOF (with each thruster's gain free "
            f"{_fmt(nd['gains_free'])} ± {_fmt(nd['gains_free_std'], 2)}, with the prior's "
            f"thrust map {_fmt(nd['prior_map'])} ± {_fmt(nd['prior_map_std'], 2)}; difference "
            f"{_fmt(nd['z'], 2)} sd)")


def _beside(cal) -> str:
    """The sentence on the other DOFs' added masses a DOF was fitted beside at another value
    than the written one (its calibration record's ``fitted_with``)."""
    w = _written(cal)
    return ("fitted beside " + ", ".join(f"{k} {_fmt(v)} (written {_fmt(w[k])})"
                                         for k, v in cal["fitted_with"].items())
            + ": each added mass is written once (its own DOF's calibration); this DOF's "
            "other values were fitted beside these, and its final error is the written "
            "model's")


def _bands(cal, key, value):
    """How many bands ``value`` is from the prior [-]."""
    sd = cal["band_relative"][key] * abs(cal["prior"][key])
    return (value - cal["prior"][key]) / sd if sd > 0 else None


def text_summary(result) -> str:
    """Plain-text table for the terminal (of a :class:`Diagnosis` or its :meth:`to_dict`)."""
    if isinstance(result, Diagnosis):
        result = result.to_dict()
    lines = [f"diagnosis of {result['log']} against {result['vehicle']}",
             f"metric: {result['metric']} ({result['units']})"]
    for d, r in result["per_dof"].items():
        lines.append(f"\n{d} [{r['units']}]  baseline {_fmt(r['baseline_error'])}  "
                     f"calibrated {_fmt(r['calibrated_error'])}  final {_fmt(r['final_error'])}"
                     f"  unexplained {_fmt(r['unexplained'])}")
        if r.get("unexplained_signature"):
            lines.append(f"  residual signature: {r['unexplained_signature']}")
        cal = r["calibration"]
        lines.append("  calibration" + (" [removed: worse free simulation on the validation "
                                        "data]" if cal.get("kept") is False else "")
                     + " (prior -> written model): " + ", ".join(
            f"{k} {_fmt(cal['prior'][k])} -> {_fmt(w)} ({_fmt(_bands(cal, k, w), 2)} bands)"
            for k, w in _written(cal).items()))
        if cal.get("fitted_with"):
            lines.append("  " + _beside(cal))
        for i, s in enumerate(r["steps"], 1):
            alt = (" (ties: " + ", ".join(a["effect"] for a in s["alternatives"]) + ")"
                   if s["alternatives"] else "")
            if s.get("ambiguous_with"):
                alt += (" (the log does not tell it from "
                        + ", ".join(s["ambiguous_with"]) + ")")
            nd = s.get("not_determined")
            if nd:
                alt += f" [named, not written: {nd['reason']}; {nd['advice']}]"
            elif s.get("kept") is False:
                alt += (" [removed: worse free simulation on the validation data; not in the "
                        "written model]")
            lines.append(f"  step {i}: {s['effect']}: {_step_params(s)}; "
                         f"at its selection: error {_fmt(s['error_before'])} -> "
                         f"{_fmt(s['error_after'])}, held-out {_fmt(s['held_out_error_before'])}"
                         f" -> {_fmt(s['held_out_error_after'])}{alt}")
        for c in r.get("calibration_named") or ():
            lines.append(f"  named by the calibration (in the written model): {c['effect']}: "
                         + ", ".join(f"{k} {_fmt(v)}" for k, v in c["parameters"].items())
                         + f" ({c['coefficient']} {_fmt(c['prior'])} -> {_fmt(c['written'])}, "
                         f"{100 * c['relative']:+.0f} %; {c['rule']})")
        if not r["steps"] and not r.get("calibration_named"):
            lines.append("  no effect is significant")
        for w in r.get("withdrawn") or ():
            lines.append(f"  withdrawn after the shared fits (not in the written model): "
                         f"{w['effect']}: {w['reason']}")
    kept = {d: v for d, v in (result.get("kept_at_prior") or {}).items() if v}
    if kept:
        lines.append("\nkept at the prior (the log does not determine them):")
        for d, v in kept.items():
            lines += [f"  {d} {k}: {why}" for k, why in v.items()]
    widths = result.get("prior_widths")
    if widths:
        lines.append(f"\ncalibration priors from the method table ({widths['shape_class']}; "
                     "1 sigma of ln c: " + "; ".join(
                         f"{k} " + ", ".join(f"{n} {v:g}" for n, v in b.items())
                         for k, b in widths["sd_ln"].items())
                     + "; linear damping not predicted: a very wide prior)")
    band = result.get("added_mass_band")
    if band:
        lines.append(f"\nadded mass bounded by +-{band['z']:g} sigma of its method uncertainty "
                     "(1 sigma of ln M: " + ", ".join(f"{d} {100 * v:g} %" for d, v in
                                              band["relative_sd"].items() if v is not None)
                     + ")")
    hits = result.get("bounds_hit") or {}
    if hits:
        lines.append("\nat a physical bound in the calibrated model:")
        for d, v in hits.items():
            lines += [f"  {d} {k}: {why}" for k, why in v.items()]
    gains = result.get("thruster_gains")
    if gains:
        lines.append(f"\nthruster gains (fitted jointly over the DOFs, prior sd "
                     f"{_fmt(gains['prior_sd'], 3)}; {'written' if gains['applied'] else 'not written'}"
                     f": {gains['reason']}):")
        lines += [f"  {n}: {_fmt(g)} +- {_fmt(gains['std'][n], 2)}"
                  for n, g in gains["gains"].items()]
        det = [c for c in gains["combinations"] if c["determined"]]
        lines.append(f"  the log determines {len(det)} of {len(gains['combinations'])} "
                     "combinations (Fisher information)")
    val = result.get("validation")
    if val and "skipped" in val:
        lines.append(f"\nvalidation skipped (every change kept): {val['skipped']}")
    elif val:
        lines.append("\nvalidation (free simulation, " + "-".join(
            f"{x:.0f}" for x in val["validation_s"]) + " s; prior / all changes / kept):")
        tests = val.get("per_dof_test") or {}
        for d in val["prior"] or {}:
            dm = tests.get(d)
            lines.append(f"  {d}: {_fmt((val['prior'] or {}).get(d))} / "
                         f"{_fmt((val['all_changes'] or {}).get(d))} / "
                         f"{_fmt((val['kept_changes'] or {}).get(d))}"
                         + (f" (Diebold-Mariano kept vs prior {dm['statistic']:+.2f}, "
                            f"p {dm['p_value']:.2f}, {dm['segments']} segments)"
                            if dm and dm.get("statistic") is not None else ""))
        if val.get("removed_for_own_dof"):
            lines.append("  removed because their own DOF simulated no better than the "
                         "prior: " + ", ".join(val["removed_for_own_dof"]))
        if val["removed"]:
            lines.append("  removed: " + ", ".join(val["removed"]))
        for d, kept in (val.get("refitted") or {}).items():
            if kept:
                lines.append(f"  {d}: refitted without the removed changes: "
                             + ", ".join(kept))
    hold = result.get("holdout")
    if hold:
        lines.append("\nheld-out free simulation, " + "-".join(
            f"{x:.0f}" for x in hold["held_out_s"]) + " s (prior / calibrated / "
            "hold-last-velocity / zero velocity)" + (f", model read back from {hold['model_file']}"
                                     if hold.get("model_file") else "") + ":")
        for d, v in hold["errors"].items():
            lines.append(f"  {d}: {_fmt(v['prior'])} / {_fmt(v['calibrated'])} / "
                         f"{_fmt(v['hold_last_velocity'])} / "
                         f"{_fmt(v.get('zero_velocity'))}")
    if "resimulated_velocity_rms" in result:
        lines.append("\nre-simulated velocity RMS (baseline / calibrated / final):")
        for d, v in result["resimulated_velocity_rms"].items():
            lines.append(f"  {d}: {_fmt(v['baseline'])} / {_fmt(v['calibrated'])} / "
                         f"{_fmt(v['final'])}")
    return "\n".join(lines) + "\n"


def residual_figure(result: Diagnosis, dof, *, key: str = "report"):
    """The window force residual of ``dof`` before (prior, calibrated) and after each
    accepted effect, against the window's mid time [s] (:meth:`Diagnosis.residual_curves`);
    a Figure (:mod:`stripcoef.figures`)."""
    from stripcoef.figures import new_figure

    tw, curves = result.residual_curves(dof)
    fig = new_figure(figsize=(9, 3.4), key=key)
    ax = fig.subplots()
    for label, y in curves:
        ax.plot(tw, y, lw=1, label=label)
    ax.axhline(0, color="k", lw=0.5)
    ax.set_xlabel("window mid time t [s]")
    ax.set_ylabel(f"missing force [{result.per_dof[dof].units}]")
    ax.set_title(f"{dof}: window force residual before and after each step")
    ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    ax.grid(True, alpha=0.3)
    return fig


def _plot(result, dof, path):
    """Write :func:`residual_figure` as PNG; False when matplotlib is missing."""
    from stripcoef.errors import InputError
    from stripcoef.figures import save_figure

    try:
        fig = residual_figure(result, dof)
    except InputError:           # no matplotlib: the report says so
        return False
    save_figure(fig, path, key="report", dpi=110)
    return True


def _bands_text(widths) -> str:
    """The report's sentence on the widths of the calibration's priors."""
    if not widths:
        return ("Bands (1 sigma, relative to the prior; Wang & Clark 2006 Table I analytical vs "
                "experimental): " + "; ".join(f"{k}: " + ", ".join(
                    f"{n} {100 * v:.0f} %" for n, v in b.items()) for k, b in BANDS.items())
                + ".")
    out = [f"Bands (1 sigma of ln c, applied as sigma |c0| at the prior value c0) from the "
           f"method table, shape class {widths['shape_class']} (docs/uncertainty.md):", ""]
    for kind, rows in widths["rows"].items():
        for term, row in rows.items():
            out.append(f"- {kind} {term}: {widths['sd_ln'][kind][term]:g} ({row})")
    return "\n".join(out)


def _step_names(steps) -> str:
    """The steps of a DOF for the summary table, those the validation removed marked."""
    return ", ".join(s["effect"] + (" (not determined by one DOF)" if s.get("not_determined")
                                    else " (removed)" if s.get("kept") is False else "")
                     for s in steps) or "-"


def markdown_report(result: Diagnosis, path) -> None:
    """Write the markdown report (and one PNG per DOF beside it) atomically."""
    path = Path(path)
    pub = result.to_dict()
    out = [f"# Diagnosis of `{pub['log']}`", "",
           f"Vehicle model: `{pub['vehicle']}`. Metric: **{pub['metric']}** — "
           f"{pub['metric_description']}; windows of {pub['window_s']:g} s.", "",
           "| DOF | baseline | calibrated | final | steps | unexplained |",
           "| --- | --- | --- | --- | --- | --- |"]
    for d, r in pub["per_dof"].items():
        out.append(f"| {d} [{r['units']}] | {_fmt(r['baseline_error'])} | "
                   f"{_fmt(r['calibrated_error'])} | {_fmt(r['final_error'])} | "
                   f"{_step_names(r['steps'])} | "
                   f"{_fmt(r['unexplained'])} |")
    if "resimulated_velocity_rms" in pub:
        out += ["", "Re-simulated velocity RMS [m/s or rad/s] (the log's inputs through each "
                "model, restarted from the logged state every 10 s):", "",
                "| DOF | prior | calibrated | final |", "| --- | --- | --- | --- |"]
        for d, v in pub["resimulated_velocity_rms"].items():
            out.append(f"| {d} | {_fmt(v['baseline'])} | {_fmt(v['calibrated'])} | "
                       f"{_fmt(v['final'])} |")
    text = text_summary(pub)
    extra = text[text.find("\nkept at the prior"):] if "\nkept at the prior" in text else ""
    for marker in ("\nat a physical bound", "\nvalidation (free", "\nvalidation skipped",
                   "\nheld-out free"):
        if not extra and marker in text:
            extra = text[text.find(marker):]
    extra = extra.split("\nre-simulated velocity RMS")[0]
    if extra.strip():
        out += ["", "## Identifiability, validation and held-out error", "", "```",
                extra.strip("\n"), "```"]
    out += ["", "## Method", "",
            f"Held-out error: blocked cross-validation, {N_BLOCKS} contiguous blocks each "
            f"predicted by a fit on the others. An effect is significant when the held-out error drops by "
            f"{100 * MIN_HELD_OUT_GAIN:.0f} % or more, BIC by {MIN_DELTA_BIC:g} or more, a "
            f"signature parameter is {MIN_Z:g} sigma from zero and the parameters are "
            f"plausible; an effect without a signature in the log must push the prior "
            f"coefficient it mimics beyond {MIMIC_BANDS:g} bands. Ties: within "
            f"{100 * TIE:.0f} % of the best held-out error. Unexplained: a generic basis cuts "
            f"the final held-out error by {100 * UNEXPLAINED_GAIN:.0f} % or more.",
            "", _bands_text(pub.get("prior_widths"))]
    for d, r in pub["per_dof"].items():
        out += ["", f"## {d}", ""]
        cal = r["calibration"]
        out += ["Calibration of the prior's coefficients (MAP within the bands)"
                + (", removed by the validation" if cal.get("kept") is False else "")
                + "; the value is the written model's:", "",
                "| coefficient | prior | written | std | bands from prior |",
                "| --- | --- | --- | --- | --- |"]
        for k, w in _written(cal).items():
            out.append(f"| {k}[{d}] | {_fmt(cal['prior'][k])} | {_fmt(w)} | "
                       f"{_fmt(cal['std'][k], 2)} | {_fmt(_bands(cal, k, w), 2)} |")
        if cal.get("fitted_with"):
            out += ["", _beside(cal)[0].upper() + _beside(cal)[1:] + "."]
        st = r["structure_before"]
        out += ["", "Residual after calibration: bias "
                f"{_fmt(st['bias'])} (z = {_fmt(st['bias_z'], 2)}), lag-1 autocorrelation "
                f"{_fmt(st['lag1_autocorrelation'], 2)}, runs z {_fmt(st['runs_z'], 2)}; mean "
                f"when velocity > 0 / < 0: {_fmt(st['mean_when_velocity_positive'])} / "
                f"{_fmt(st['mean_when_velocity_negative'])}; when force > 0 / < 0: "
                f"{_fmt(st['mean_when_force_positive'])} / "
                f"{_fmt(st['mean_when_force_negative'])}.", "",
                "Candidates at the first step:", "",
                "| effect | parameters | held-out gain | ΔBIC | z | signature | verdict |",
                "| --- | --- | --- | --- | --- | --- | --- |"]
        for c in r["candidates"]:
            if not c.get("applicable"):
                out.append(f"| {c['effect']} | - | - | - | - | - | not applicable: "
                           f"{c.get('reason', '')} |")
                continue
            verdict = "significant" if c["significant"] else "; ".join(c["rejected_because"])
            out.append(f"| {c['effect']} | {_params(c['parameters'], c['std'])} | "
                       f"{_fmt(100 * c['held_out_gain'], 3)} % | {_fmt(c['delta_bic'], 3)} | "
                       f"{_fmt(c['z'], 3)} | {c['signature'] or 'none (mimics ' + str(c['mimics']) + ')'} | "
                       f"{verdict} |")
        out += ["", "Steps:", ""]
        if not r["steps"]:
            out.append("No effect is significant.")
        for i, s in enumerate(r["steps"], 1):
            nd = s.get("not_determined")
            removed = (f" **Named, not written**: {nd['reason']}; {nd['advice']}." if nd
                       else " **Removed by the validation** (worse free simulation on the "
                       "validation data): not in the written model." if s.get("kept") is False
                       else "")
            out.append(f"{i}. **{s['effect']}**: {_step_params(s)}; at its "
                       f"selection: error "
                       f"{_fmt(s['error_before'])} → {_fmt(s['error_after'])}, held-out "
                       f"{_fmt(s['held_out_error_before'])} → "
                       f"{_fmt(s['held_out_error_after'])} (ΔBIC {_fmt(s['delta_bic'], 3)}); "
                       f"evidence: {s['signature'] or 'coefficient outside its band'}; "
                       f"source: {s['source']}.{removed}")
            if s.get("ambiguous_with"):
                out.append(f"   - not told apart from: {', '.join(s['ambiguous_with'])} "
                           f"({s['choice']['reason']})")
            for a in s["alternatives"]:
                out.append(f"   - tie: {a['effect']} ({_params(a['parameters'])}), held-out "
                           f"{_fmt(a['held_out_error_after'])}: the data do not separate them.")
        ev = r["unexplained_evidence"]
        out += ["", f"What remains: final error (the written model) {_fmt(r['final_error'])}, held-out "
                f"{_fmt(r['final_held_out_error'])}; a generic basis of "
                f"{ev['generic_basis_columns']} columns changes the held-out error by "
                f"{_fmt(-100 * ev['held_out_gain'], 3)} %: "
                + ("**the residual is still structured and no effect of the library "
                   "explains it (unexplained)**." if r["unexplained"] else
                   "no structure left that the library or the generic basis explains.")
                + (f" Its signature: {r['unexplained_signature']}."
                   if r.get("unexplained_signature") else "")]
        png = path.with_name(f"{path.stem}_{d}.png")
        if _plot(result, d, png):
            out += ["", f"![{d} residuals]({png.name})"]
        else:
            out += ["", "(plots need matplotlib: pip install 'stripcoef[plot]')"]
    write_text(path, "\n".join(out) + "\n", key="report")
