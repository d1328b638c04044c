"""Measure how far real vehicles are from the models predicted from their geometry, and make
the diagnosis's vehicle-mismatch table.

    python -m scripts.make_vehicle_mismatch      # seconds: deterministic

The calibration of ``stripcoef diagnose`` starts from the model of a vehicle file. The method
table (``src/stripcoef/data/method_uncertainty.csv``) says how far the *method* is from an
exact or converged answer for the *same shape*; a real vehicle differs from its file by more
(cables, payload, flooded volumes, parts the file leaves out, a linear damping the method does
not predict). This script measures that difference on the stored papers whose vehicles have
both a geometric prediction and an identified model of the real vehicle:

- VideoRay Pro III (Wang & Clark 2006, Table I, ``reference_tables/videoray_pro3``): the
  experimental column (identified on the vehicle: X_u, Y_v, Z_w, N_r, X_u|u|, Y_v|v|,
  Z_w|w|, N_r|r|, N_rdot) against stripcoef's default model of
  ``geometry/videoray_pro3.yaml`` and against the paper's own strip-theory column. N_r|r| is
  the yaw fit's beta/gamma = 0.0416 (``text_and_derived.csv``), not Table I's 0.4504, which
  the same fit contradicts (reference_tables/videoray_pro3/README.md, inconsistency 1);
- ROV II (Eng et al. 2009, Tables III and IV, ``reference_tables/rov2``): the identified
  full-scale added mass and drag against the paper's WAMIT and ANSYS CFX predictions of the
  same geometry (there is no vehicle file of ROV II here). The yaw K_L of CFX is 0, whose
  ratio is undefined: left out.

ROMEO (identified heave and yaw, ``reference_tables/romeo``) and MARES have no geometric
prediction stored beside an identified model, so they add no row.

Each row is e = ln(identified / predicted) [-]. Per coefficient family (added mass M, linear
damping D_L, quadratic damping D_Q) and DOF group (translational, rotational) the spread is
the root mean square of e (not centred: a systematic bias is part of how far a vehicle is
from its file), sigma = sqrt(mean(e^2)). A family measured on fewer than MIN_VEHICLES
vehicles does not stand alone: it takes the pooled RMS of its matrix over both DOF groups
(basis ``pooled``). The table says the number of rows and vehicles behind each value: few
(3-7 rows, 1-2 vehicles), the best the stored papers give.

Writes ``reference_tables/method_errors/vehicle_mismatch.csv`` (one row per compared
coefficient) and ``src/stripcoef/data/vehicle_mismatch.csv`` (the family table the diagnosis
reads, :mod:`stripcoef.diagnose.priors`).
"""

from __future__ import annotations

import argparse
import csv
import io
import math
import warnings

from validation import ROOT
from validation.reference import load_table

TABLE = ROOT / "src" / "stripcoef" / "data" / "vehicle_mismatch.csv"
ROWS = ROOT / "reference_tables" / "method_errors" / "vehicle_mismatch.csv"
#: A family measured on fewer vehicles takes its matrix's pooled value.
MIN_VEHICLES = 2
COMMAND = "python -m scripts.make_vehicle_mismatch"

#: VideoRay Table I term -> (family, group, stripcoef matrix, diagonal index)
VIDEORAY = {
    "X_u": ("D_L", "translational", "linear_damping", 0),
    "Y_v": ("D_L", "translational", "linear_damping", 1),
    "Z_w": ("D_L", "translational", "linear_damping", 2),
    "N_r": ("D_L", "rotational", "linear_damping", 5),
    "X_uu": ("D_Q", "translational", "quadratic_damping", 0),
    "Y_vv": ("D_Q", "translational", "quadratic_damping", 1),
    "Z_ww": ("D_Q", "translational", "quadratic_damping", 2),
    "N_rr": ("D_Q", "rotational", "quadratic_damping", 5),
    "N_rdot": ("M", "rotational", "added_mass", 5),
}
TABLE_OF = {"D_L": "table1_linear_drag", "D_Q": "table1_quadratic_drag", "M": "table1_added_mass"}


def _values(source: str, table: str) -> dict:
    return {r["name"]: float(r["value"]) for r in load_table(source, table)}


def comparisons() -> list[dict]:
    """One row per compared coefficient (module docstring)."""
    import stripcoef

    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        model = stripcoef.estimate(ROOT / "geometry" / "videoray_pro3.yaml")
    derived = _values("videoray_pro3", "text_and_derived")
    rows = []
    for term, (family, group, matrix, i) in VIDEORAY.items():
        ref = _values("videoray_pro3", TABLE_OF[family])
        if term == "N_rr":
            identified = derived["N_rr.from_yaw_fit"]
            id_source = "Wang & Clark 2006 eq. 8 yaw fit, beta/gamma (text_and_derived.csv)"
        else:
            identified = ref[f"{term}.experimental"]
            id_source = f"Wang & Clark 2006 Table I, {term} experimental"
        predictions = (("stripcoef", float(getattr(model, matrix)[i, i]),
                        "stripcoef default model of geometry/videoray_pro3.yaml"),
                       ("paper strip theory", ref[f"{term}.analytical"],
                        f"Wang & Clark 2006 Table I, {term} analytical"))
        for predictor, predicted, p_source in predictions:
            rows.append(_row("videoray_pro3", term, family, group, predictor, predicted,
                             identified, p_source, id_source))
    am, drag = _values("rov2", "table3_added_mass"), _values("rov2", "table4_drag")
    for dof, group in (("surge", "translational"), ("sway", "translational"),
                       ("heave", "translational"), ("yaw", "rotational")):
        rows.append(_row("rov2", f"{dof} m_a", "M", group, "WAMIT", am[f"{dof}.wamit"],
                         am[f"{dof}.experiment"], f"Eng et al. 2009 Table III, {dof} WAMIT",
                         f"Eng et al. 2009 Table III, {dof} experiment"))
    for dof, group in (("surge", "translational"), ("yaw", "rotational")):
        for key, family in (("K_L", "D_L"), ("K_Q", "D_Q")):
            predicted = drag[f"{dof}.{key}.cfx"]
            if predicted == 0.0:      # CFX yaw K_L = 0: no ratio
                continue
            rows.append(_row("rov2", f"{dof} {key}", family, group, "ANSYS CFX", predicted,
                             drag[f"{dof}.{key}.experiment"],
                             f"Eng et al. 2009 Table IV, {dof} {key} CFX",
                             f"Eng et al. 2009 Table IV, {dof} {key} experiment"))
    return rows


def _row(vehicle, term, family, group, predictor, predicted, identified, p_source, id_source):
    return {"vehicle": vehicle, "term": term, "family": family, "group": group,
            "predictor": predictor, "predicted": predicted, "identified": identified,
            "ln_ratio": math.log(abs(identified) / abs(predicted)),
            "predicted_source": p_source, "identified_source": id_source}


def families(rows: list[dict]) -> list[dict]:
    """The family table: sigma = RMS of ln(identified / predicted) (module docstring)."""
    def rms(rs):
        return math.sqrt(sum(r["ln_ratio"] ** 2 for r in rs) / len(rs))

    out = []
    for family in ("M", "D_L", "D_Q"):
        pooled = [r for r in rows if r["family"] == family]
        for group in ("translational", "rotational"):
            own = [r for r in pooled if r["group"] == group]
            vehicles = sorted({r["vehicle"] for r in own})
            if len(vehicles) >= MIN_VEHICLES:
                use, basis = own, "measured"
            else:
                use, basis = pooled, "pooled"
            largest = max(use, key=lambda r: abs(r["ln_ratio"]))
            out.append({
                "group": group, "term": family, "sd": round(rms(use), 4), "basis": basis,
                "n_rows": len(use), "n_vehicles": len({r["vehicle"] for r in use}),
                "source": (f"RMS of ln(identified/predicted) over {len(use)} coefficients of "
                           + ", ".join(sorted({r['vehicle'] for r in use}))
                           + (f" ({family} of both DOF groups: only {len(vehicles)} vehicle(s) "
                              f"measured in this group)" if basis == "pooled" else "")
                           + f"; largest {largest['ln_ratio']:+.2f} ({largest['vehicle']} "
                           f"{largest['term']}, {largest['predictor']})")})
    return out


def _csv(rows, columns) -> str:
    buf = io.StringIO()
    w = csv.DictWriter(buf, fieldnames=columns, lineterminator="\n")
    w.writeheader()
    for r in rows:
        w.writerow({k: (f"{r[k]:.6g}" if isinstance(r[k], float) else r[k]) for k in columns})
    return buf.getvalue()


def main(argv=None) -> int:
    argparse.ArgumentParser(description=__doc__.splitlines()[0]).parse_args(argv)
    rows = comparisons()
    fams = families(rows)
    head = (f"# Generated by {COMMAND} (scripts/make_vehicle_mismatch.py): do not edit by hand.\n"
            "# ln(identified / predicted) of each coefficient of the stored papers' vehicles that\n"
            "# have both a geometric prediction and an identified model: VideoRay Pro III (Wang &\n"
            "# Clark 2006 Table I; predicted by stripcoef from geometry/videoray_pro3.yaml and by\n"
            "# the paper's strip theory) and ROV II (Eng et al. 2009 Tables III-IV; WAMIT, CFX).\n"
            "# predicted, identified: magnitudes [kg, kg m^2, N s/m, N m s, N s^2/m^2, N m s^2].\n")
    from stripcoef.files import write_text
    write_text(ROWS, head + _csv(rows, ["vehicle", "term", "family", "group", "predictor",
                                        "predicted", "identified", "ln_ratio",
                                        "predicted_source", "identified_source"]))
    head2 = (f"# Vehicle mismatch: how far a real vehicle's identified coefficients are from those\n"
             f"# predicted from its geometry, sd of ln(identified / predicted) [-] per family.\n"
             f"# Generated by {COMMAND} from reference_tables/method_errors/vehicle_mismatch.csv\n"
             "# (VideoRay Pro III, Wang & Clark 2006 Table I; ROV II, Eng et al. 2009 Tables\n"
             "# III-IV). sd: root mean square of ln(identified/predicted) (not centred); basis:\n"
             f"# measured (rows of >= {MIN_VEHICLES} vehicles in the group) | pooled (the family's\n"
             "# rows of both DOF groups). Read by stripcoef.diagnose.priors: the calibration's prior\n"
             "# width of a vehicle file is max(method band, this sd). Do not edit by hand.\n")
    write_text(TABLE, head2 + _csv(fams, ["group", "term", "sd", "basis", "n_rows",
                                          "n_vehicles", "source"]))
    for f in fams:
        print(f"{f['group']:14s} {f['term']:4s} sd {f['sd']:.3f} ({f['basis']}, "
              f"{f['n_rows']} rows, {f['n_vehicles']} vehicles)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
