"""Measure strip theory's error against the stored references, and make the method table.

Two steps, both deterministic:

    python -m scripts.make_method_uncertainty --measure   # about 1 min: runs the model
    python -m scripts.make_method_uncertainty             # seconds: the table from the errors

``--measure`` runs stripcoef on every reference shape and writes
reference_tables/method_errors/method_errors.csv, one row per compared term (strip value, reference value,
error, the reference's source). The references, all stored data or exact formulas:

- Lamb's exact prolate spheroids L/D 2, 3, 5, 7.5, 10 (stripcoef.hull.lamb.spheroid_added_mass);
- the capsule against its converged Capytaine run (reference_tables/capytaine_anchor);
- three finned Myring hulls against Capytaine (reference_tables/bem/bem_finned_bodies.csv,
  the Richardson rows; vehicle files of validation/finned.py);
- the 24 bluff shapes against Capytaine (reference_tables/bem/bem_bluff.csv, Richardson), the
  ellipsoids' diagonals against Lamb, and the edge-graded references where stored (the boxes,
  the chamfered box, the unions of prisms: reference_tables/bem/graded_*.csv) as
  benchmarks/bluff_shapes.py does (``reference_matrix``, ``reference_source``);
- translational quadratic drag: a sphere (across), a cube face-on and edge-on, three cones and a
  hemisphere against their measured whole-body drag coefficients (reference_tables/body_drag_3d,
  Hoerner 1965 via public copies; bodies, sizes and Re = 1e5 in benchmarks/drag_bodies.py), the
  held-out rows only: a row whose number the model's own curves are built from (the sphere and
  the 2:1 ellipsoid nose-on, the disc, the square plate, cylinders end-on: drag_bodies.BUILT_FROM,
  issue 35) is not used, nor are the bodies of reference_tables/body_drag_3d/README.md that the
  method reads from the same number;
- rotational quadratic drag: the stored OpenFOAM rotations of reference_tables/cfd (steady RANS,
  the rows docs/validation.md counts: converged, mesh spread within 25 %, finest levels, not
  friction-only; validation/cfd.py), error ln(model / CFD) of the damping moment at the CFD's
  rate (``--measure-rotation`` refreshes these rows alone, in seconds of model time).

Each shape is put in its class by its geometry (stripcoef.study.shapes.shape_class), never by
its name. The second step reads that file and writes src/stripcoef/data/method_uncertainty.csv:
per class, matrix and term family (translational / rotational added mass; translational
quadratic drag where a class has at least MIN_SHAPES measured shapes), the sd of ln
sigma = q95 / 1.96 from the split-conformal 95 % quantile q95 of |ln(strip / reference)|
(the k-th smallest, k = min(n, ceil(0.95 (n + 1))): a new exchangeable term falls within it
with probability k / (n + 1), stripcoef.study.calibration); couplings are measured as
(strip - ref) / sqrt(A_ii A_jj) and sampled as an additive move c sqrt(A_ii A_jj)
(stripcoef.study.sources.couple); drag of a class and DOF group with fewer than MIN_SHAPES
reference shapes (translation: finned, open_frame; rotation: all but bluff) has no independent
reference stored (assumed rows, labelled so), and linear damping is not predicted by the method
(placeholder rows, labelled so).
"""

from __future__ import annotations

import argparse
import csv
import io
import os
import sys

for _var in ("OPENBLAS_NUM_THREADS", "OMP_NUM_THREADS", "MKL_NUM_THREADS"):
    os.environ.setdefault(_var, "1")

import numpy as np  # noqa: E402

from stripcoef.study.calibration import (Z95, claimed_coverage, leave_one_group_out,  # noqa: E402
                                         log_error, quantile95)
from stripcoef.study.shapes import CLASSES  # noqa: E402
from stripcoef.study.sources import PANELS  # noqa: E402
from validation import ROOT  # noqa: E402
from validation.method_errors import ERRORS, read_errors  # noqa: E402

TABLE = ROOT / "src" / "stripcoef" / "data" / "method_uncertainty.csv"
TERMS = ("X_udot", "Y_vdot", "Z_wdot", "K_pdot", "M_qdot", "N_rdot")
SPHEROIDS = (2.0, 3.0, 5.0, 7.5, 10.0)
FIELDS = ("set", "shape", "class", "matrix", "family", "term", "strip", "reference", "error", "mirrors",
          "allowed", "reference_source", "slenderness")

#: fewest shapes of a class that make a measured row (leave-one-shape-out needs two)
MIN_SHAPES = 2
DRAG_SET = "Published 3D drag"
#: the set of the rotational drag rows: stripcoef against the stored OpenFOAM rotations
CFD_SET = "OpenFOAM rotations"
#: drag with no independent reference stored for the class (rotation: none for any class)
ASSUMED_DRAG = {
    "revolution": (0.15, 0.25), "finned": (0.15, 0.25), "bluff": (0.20, 0.30),
    "open_frame": (0.20, 0.30)}
#: lift derivatives: measured on the DARPA SUBOFF captive-model data (Roddy 1990 Table 4,
#: configurations 1-6: benchmarks/lift_band.py writes their ln(model/measured) here)
LIFT_ERRORS = ROOT / "reference_tables" / "method_errors" / "lift_errors.csv"
#: control derivatives: an assumed sd(ln). On SUBOFF the default (slender-body) rule has the four
#: control derivatives within 11 % (sd(ln) 0.060) and each stern plane's own force within 20 % of
#: the force measured on its stock, the carry-over onto the afterbody from slender-body theory
#: (docs/validation.md); but four terms of one tail measure no spread for other tails, and
#: Prestero 2001's semi-empirical REMUS table differs from the model by larger factors, so the
#: assumed spread is kept.
ASSUMED_LIFT = 0.75
CONTROL_REASON = ("not calibrated: on Roddy 1990's SUBOFF the four control derivatives (Y'_dr, "
                  "N'_dr, Z'_ds, M'_ds) are within 11 % (sd(ln) 0.060, benchmarks/lift_band.py) "
                  "and each stern plane's own force within 20 % of its measured stock force "
                  "(docs/validation.md), but four terms of one tail measure no spread for other "
                  "tails; against Prestero 2001's semi-empirical REMUS 100 values the model's "
                  "control derivatives (Y_uudr ... M_uuds) differ by larger factors; an assumed "
                  "sd(ln) that spans them, one factor for all these terms: excluded from the "
                  "coverage check")


#: classes whose lift the SUBOFF data measure (a slender body of revolution, with or without
#: fins); other classes keep the assumed spread
LIFT_MEASURED_CLASSES = ("revolution", "finned")
LIFT_ELSEWHERE = ("not calibrated: lift is measured on a slender body of revolution only (Roddy "
                  "1990's SUBOFF, sd(ln) 0.59 for the revolution and finned classes, "
                  "benchmarks/lift_band.py); for this class an assumed sd(ln) of the same size, "
                  "one factor for the lift matrix: excluded from the coverage check")


def lift_row(cls, path=LIFT_ERRORS) -> list:
    """The measured lift row: sd(ln) = q95 / 1.96 of the right-signed SUBOFF terms; a wrong-signed
    term lies outside every factor band, so the claim is the rank of the band's edge among all
    terms, k/(n+1) (stripcoef.study.calibration)."""
    with open(path, newline="") as fh:
        body = [line for line in fh if not line.startswith("#")]
    terms = [r for r in csv.DictReader(body) if r["matrix"] == "lift"]
    err = np.array([abs(float(r["error"])) for r in terms if r["error"]])
    q = quantile95(err)
    k = int(np.sum(err <= q))
    n = len(terms)
    configs = sorted({r["config"] for r in terms})
    wrong = [f"{r['config']}:{r['term']}" for r in terms if not r["error"]]
    worst = max((r for r in terms if r["error"]), key=lambda r: abs(float(r["error"])))
    held = leave_one_group_out([float(r["error"]) if r["error"] else np.nan for r in terms],
                               [r["config"] for r in terms])
    text = (f"|ln(model/measured)| of {n} lift terms (static and rotary, Y'_v ... M'_q) of Roddy "
            f"1990's DARPA SUBOFF, configurations {', '.join(configs)} (benchmarks/lift_band.py): "
            f"q95 of the {len(err)} right-signed terms {q:.4g}, largest {abs(float(worst['error'])):.4g} "
            f"(configuration {worst['config']} {worst['term']}); {len(wrong)} terms have the wrong "
            f"sign or a measured zero ({', '.join(wrong)}) and lie outside every factor band; a "
            f"new term falls in the band with probability {k / (n + 1):.3f} (k/(n+1)); leaving "
            f"one configuration out, {int(held.sum())} of {n} fall in the band of the others. One hull only")
    return [cls, "lift", "all", "lognormal", f"{q / Z95:.4g}", "measured", len(configs), n,
            f"{q:.4g}", f"{k / (n + 1):.3f}", text, ""]


def _family(i, j):
    if i != j:
        return "coupling"
    return "translation" if i < 3 else "rotation"


def _term(i, j):
    return TERMS[i] if i == j else f"{TERMS[i][0]}{TERMS[j][2:]}"


def _rows(set_name, shape, cls, strip, ref, source, terms, mirrors, slenderness):
    """One row per compared term; ``mirrors``: the shape's mirror symmetries through the
    model's reference point (stripcoef.assembly.symmetry), ``allowed``: whether they allow the
    coupling (the sampling moves it: stripcoef.study.sources.couple); ``slenderness``: the
    shape's L/D (stripcoef.study.shapes.features), the scope of the rows it measures."""
    from stripcoef.assembly.symmetry import allowed_couplings

    out = []
    ok = allowed_couplings(mirrors)
    d = np.abs(np.diag(ref))
    for i, j in terms:
        if i == j:
            err = float(log_error(strip[i, i], ref[i, i]))
        else:
            err = float((strip[i, j] - ref[i, j]) / np.sqrt(d[i] * d[j]))
        out.append({"set": set_name, "shape": shape, "class": cls, "matrix": "added_mass",
                    "family": _family(i, j),
                    "term": _term(i, j), "strip": f"{strip[i, j]:.8g}",
                    "reference": f"{ref[i, j]:.8g}", "error": f"{err:.6g}",
                    "mirrors": " ".join(sorted(mirrors)) or "none",
                    "allowed": "" if i == j else ("yes" if ok[i, j] else "no"),
                    "reference_source": source, "slenderness": f"{slenderness:.4g}"})
    return out


def _compared(bs, ref, strip):
    """The diagonal terms significant in the reference, and the couplings significant in the
    reference OR the strip model (a coupling the model invents is an error too)
    (bluff_shapes.significant_terms: |A_ij| >= 1 % of sqrt(A_ii A_jj))."""
    terms = bs.significant_terms(ref)
    d = np.abs(np.diag(ref))
    for i in range(6):
        for j in range(i + 1, 6):
            if (i, j) not in terms and d[i] * d[j] > 0 and \
                    abs(strip[i, j]) >= bs.SIGNIFICANT * np.sqrt(d[i] * d[j]):
                terms.append((i, j))
    return terms


def measure() -> list[dict]:
    import yaml

    from benchmarks import bluff_shapes as bs
    from validation import finned as fb
    from stripcoef.assembly.estimate import estimate as estimate_any
    from stripcoef.fluid import Fluid

    def estimate(veh, method="strips"):
        # the table is the error of one method: strips unless a row says panels
        return estimate_any(veh, added_mass_method=method)

    def mirrors(veh, model):
        return mirror_symmetries(veh, model.reference_point)

    def slender(veh):
        return features(veh)["slenderness"]
    from stripcoef.geometry.vehicle import Vehicle, load_vehicle, parse_vehicle
    from stripcoef.hull.lamb import spheroid_added_mass
    from stripcoef.study.shapes import features, shape_class
    from stripcoef.assembly.symmetry import mirror_symmetries
    from validation.reference import load_table

    rows = []
    diag = [(i, i) for i in range(6)]
    for ld in SPHEROIDS:
        a, b = 0.75, 0.75 / ld
        data = yaml.safe_load(yaml.safe_dump({
            "name": f"spheroid L/D {ld:g}", "strips": 1000,
            "fluid": {"density": 1000.0, "kinematic_viscosity": 1e-6},
            "hull": {"profile": [{"type": "ellipsoid_tail", "x": [-a, 0.0], "radius": b},
                                 {"type": "ellipsoid_nose", "x": [0.0, a], "radius": b}]}}))
        veh = parse_vehicle(data, file=f"spheroid_{ld:g}")
        model = estimate(veh)
        strip = np.asarray(model.added_mass)
        ref = np.diag(spheroid_added_mass(a, b, rho=1000.0))
        rows += _rows("Lamb spheroids", f"spheroid_ld{ld:g}", shape_class(veh), strip, ref,
                      "Lamb 1932 sec. 373 (stripcoef.hull.lamb.spheroid_added_mass)",
                      [t for t in diag if abs(ref[t]) > 1e-9 * np.abs(ref).max()],
                      mirrors(veh, model), slender(veh))
    veh = load_vehicle(ROOT / "geometry" / "capsule.yaml")
    model = estimate(veh)
    strip = np.asarray(model.added_mass)
    ref = np.zeros((6, 6))
    for r in load_table("capytaine_anchor", "capsule"):
        k = int(r["name"][1]) - 1
        ref[k, k] = r["value"]
    rows += _rows("Capytaine capsule", "capsule", shape_class(veh), strip, ref,
                  "reference_tables/capytaine_anchor/capsule.csv",
                  [t for t in diag if ref[t] != 0.0], mirrors(veh, model), slender(veh))
    bem = {case: refs["richardson"] for case, refs in fb.load_references().items()}
    for case in fb.CASES:
        veh = parse_vehicle(fb.vehicle_dict(case), file=case)
        model = estimate(veh)
        strip = np.asarray(model.added_mass)
        rows += _rows("Capytaine finned hulls", case, shape_class(veh), strip, bem[case],
                      "reference_tables/bem/bem_finned_bodies.csv (richardson)",
                      _compared(bs, bem[case], strip), mirrors(veh, model), slender(veh))
    refs = bs.read_references()
    for name in bs.SHAPES:
        ref = bs.reference_matrix(name, refs)
        source = bs.reference_source(name)
        veh = Vehicle.from_mesh(bs.strip_mesh(name), name=name,
                                fluid=Fluid(density=bs.RHO, kinematic_viscosity=1e-6,
                                            source="benchmark"))
        model = estimate(veh)
        strip = np.asarray(model.added_mass)
        sym, ld = mirrors(veh, model), slender(veh)
        rows += _rows("Capytaine bluff shapes", name, shape_class(veh), strip, ref, source,
                      _compared(bs, ref, strip), sym, ld)
        panel = np.asarray(estimate(veh, "panels").added_mass)
        rows += _rows("Capytaine bluff shapes", name, PANELS, panel, ref, source,
                      _compared(bs, ref, panel), sym, ld)
        print(f"{name}: {rows[-1]['class']}", flush=True)
    rows += drag_rows(mirrors)
    rows += cfd_rotation_rows()
    return rows


def cfd_rotation_rows() -> list[dict]:
    """One row per counted stored CFD rotation (validation.cfd.summary_rows): the model's
    and the CFD's damping moment [N m] at the CFD's rate, error ln(model / CFD)."""
    from stripcoef.conventions import quadratic_damping_name
    from stripcoef.study.shapes import features, shape_class
    from validation import cfd

    out = []
    for r in cfd.summary_rows([r for r in cfd.rows() if r["rotation"]]):
        veh = cfd._vehicle(f"reference_tables/cfd/{r['body']}"
                           if not r["body"].endswith(".yaml") else f"geometry/{r['body']}")
        k = 3 + ("roll", "pitch", "yaw").index(r["dof"])
        out.append({"set": CFD_SET, "shape": r["body"], "class": shape_class(veh),
                    "matrix": "quadratic_damping", "family": "rotation",
                    "term": quadratic_damping_name(k, k), "strip": f"{r['model']:.8g}",
                    "reference": f"{r['cfd']:.8g}",
                    "error": f"{float(np.log(r['ratio'])):.6g}", "mirrors": "", "allowed": "",
                    "reference_source": f"reference_tables/cfd/{r['file']} (OpenFOAM steady "
                                        f"RANS, levels {r['levels']}, GCI "
                                        f"{100 * r['gci']:.1f} %; moment at "
                                        f"{r['speed']:.3g} rad/s)",
                    "slenderness": f"{features(veh)['slenderness']:.4g}"})
        print(f"{r['body']} {r['dof']}: {out[-1]['class']} (CFD rotation)", flush=True)
    return out


def drag_rows(mirrors) -> list[dict]:
    """One row per compared direction of each body of benchmarks/drag_bodies.py: the model's
    and the measured C_D [-] on the reference's area, error ln(model / reference)."""
    from validation import drag_bodies as db
    from stripcoef.assembly.estimate import estimate
    from stripcoef.conventions import quadratic_damping_name
    from stripcoef.study.shapes import features, shape_class

    out = []
    for name in db.BODIES:
        veh, model, rows = db.compare(name, lambda v: estimate(
            v, added_mass_method="strips", speed=db.SPEED))
        cls, ld = shape_class(veh), features(veh)["slenderness"]
        sym = " ".join(sorted(mirrors(veh, model))) or "none"
        for r in rows:
            k = r["dof"]
            if not r["held_out"]:      # the reference is a number the model's curve is built from
                continue
            out.append({"set": DRAG_SET, "shape": name, "class": cls,
                        "matrix": "quadratic_damping", "family": _family(k, k),
                        "term": quadratic_damping_name(k, k), "strip": f"{r['cd_model']:.8g}",
                        "reference": f"{r['cd_ref']:.8g}",
                        "error": f"{float(log_error(r['cd_model'], r['cd_ref'])):.6g}",
                        "mirrors": sym, "allowed": "",
                        "reference_source": f"reference_tables/{db.SOURCE}/{db.TABLE}.csv "
                                            f"({r['row']}; C_D on {r['area']}, Re {r['reynolds']:.0e})",
                        "slenderness": f"{ld:.4g}"})
        print(f"{name}: {cls} (drag)", flush=True)
    return out


def write_errors(rows):
    with open(ERRORS, "w", newline="") as fh:
        fh.write("# Strip theory (added_mass_method strips, 3D corrections on), and the 3D panel method (class panels) on the bluff shapes, against stored references, one row\n"
                 "# per compared term. matrix added_mass: error: diagonal ln(strip / reference) [-] (inf: strip 0);\n"
                 "# coupling (strip - reference) / sqrt(A_ii A_jj) of the reference [-], for every coupling\n"
                 "# >= 1 % of sqrt(A_ii A_jj) in the reference or in the strip model (zero in the model\n"
                 "# included). mirrors: the shape's mirror symmetries through the model's reference point\n"
                 "# (stripcoef.assembly.symmetry); allowed: whether they allow the coupling (the sampling\n"
                 "# moves it, stripcoef.study.sources.couple; a forbidden one stays zero). class: by geometry\n"
                 "# (stripcoef.study.shapes). Units kg, kg m, kg m^2 (Fossen signs). matrix quadratic_damping\n"
                 "# (set Published 3D drag, benchmarks/drag_bodies.py): strip and reference are the model's\n"
                 "# |D_Q[k, k]| / (1/2 rho A) and the measured whole-body drag coefficient on the reference's\n"
                 "# area A [-], error ln(strip / reference). reference_source: where the reference is stored.\n"
                 "# set OpenFOAM rotations (validation/cfd.py): strip and reference are the model's and\n"
                 "# the stored CFD's damping moment [N m] of a rotation at the CFD's rate, error\n"
                 "# ln(strip / reference).\n"
                 "# slenderness: the shape's L/D [-] (stripcoef.study.shapes.features).\n"
                 "# Generated by python -m scripts.make_method_uncertainty --measure\n")
        w = csv.DictWriter(fh, FIELDS, lineterminator="\n")
        w.writeheader()
        w.writerows(rows)


HEADER = """\
# Method uncertainty of strip theory, by shape class, matrix and DOF group.
# Generated by python -m scripts.make_method_uncertainty from
# reference_tables/method_errors/method_errors.csv
# (written by the same script with --measure: stripcoef against Lamb's exact solutions and
# converged Capytaine runs) and reference_tables/method_errors/lift_errors.csv (python -m benchmarks.lift_band: the
# lift against Roddy 1990's SUBOFF captive-model derivatives). Do not edit by hand:
# tests/test_uncertainty_bands.py regenerates it.
# class: by geometry, stripcoef.study.shapes (revolution | finned | bluff | open_frame).
# matrix: added_mass | linear_damping | quadratic_damping | lift (the lift matrix L) | control
#   (the control surfaces' derivatives); dofs: translation | rotation | coupling (sampled as
#   M_ij + c sign(M_ij) sqrt(M_ii M_jj), c = sd z: stripcoef.study.sources.couple) | all (one
#   factor for the whole matrix: lift, control; sampled only for a model that has them).
# distribution: lognormal (sd of ln(term)) | normal (sd of the coupling error over sqrt(A_ii A_jj)).
# basis: measured (sd = q95 / 1.96, q95 the split-conformal 95 % quantile of |error| over
#   n_terms terms of n_shapes shapes: the k-th smallest, k = min(n, ceil(0.95 (n + 1)));
#   claim = k / (n + 1), the chance a new term of the class falls inside, distribution-free;
#   stripcoef.study.calibration; added mass: Lamb and converged Capytaine runs; translational
#   quadratic drag: measured whole-body drag of simple bodies, reference_tables/body_drag_3d,
#   for a class with at least 2 such shapes; rotational quadratic drag: the stored OpenFOAM
#   rotations, reference_tables/cfd, for a class with at least 2 such shapes) | assumed (no
#   independent reference stored) |
#   not_predicted (outside the model: a placeholder spread, not a calibrated band).
# slenderness: for a measured drag row, the range of L/D [-] of its reference shapes
#   (stripcoef.study.shapes.features): its scope, because the axial drag model changes regime
#   with L/D (form factor of a streamlined hull, blunt-end pressure drag) within one shape class;
#   a vehicle outside it gets the band as an extrapolation, said so in its source
#   (stripcoef.study.sources.method_sources). Added-mass rows: scoped by their class.
"""


def _measured(cls, matrix, fam, sel) -> list:
    """The measured row of ``sel`` (one class, matrix and family): sd = q95 / 1.96."""
    err = np.array([float(r["error"]) for r in sel])
    q = quantile95(err)
    shapes = sorted({r["shape"] for r in sel})
    sets = sorted({r["set"] for r in sel})
    worst = sel[int(np.argmax(np.abs(err)))]
    what = ("|ln(model/ref)|" if fam != "coupling" else "|model - ref| / sqrt(A_ii A_jj)")
    text = (f"{what} of {len(sel)} terms of {len(shapes)} "
            f"shape{'s' if len(shapes) != 1 else ''} ({'; '.join(sets)}): "
            f"q95 {q:.4g}, largest {abs(float(worst['error'])):.4g} "
            f"({worst['shape']} {worst['term']}); a new term of the class falls in the "
            f"band with probability {claimed_coverage(len(sel)):.3f} (k/(n+1))")
    # scope (drag rows): the axial drag model changes regime with L/D (streamlined-body form
    # factor, blunt-end pressure drag: stripcoef.assembly.damping), which the shape class
    # does not separate; added-mass rows are scoped by their class alone
    ld = [float(r["slenderness"]) for r in sel if r["slenderness"]]
    scope = f"{min(ld):.3g}-{max(ld):.3g}" \
        if matrix == "quadratic_damping" and ld and len(ld) == len(sel) else ""
    return [cls, matrix, fam, "lognormal" if fam != "coupling" else "normal",
            f"{q / Z95:.4g}", "measured", len(shapes), len(sel), f"{q:.4g}",
            f"{claimed_coverage(len(sel)):.3f}", text, scope]


def make_table(rows) -> str:
    out = io.StringIO()
    out.write(HEADER)
    w = csv.writer(out, lineterminator="\n")
    w.writerow(["class", "matrix", "dofs", "distribution", "sd", "basis", "n_shapes",
                "n_terms", "q95", "claim", "source", "slenderness"])
    for cls in (*CLASSES, PANELS):
        for fam in ("translation", "rotation", "coupling"):
            sel = [r for r in rows if r["class"] == cls and r["family"] == fam
                   and r["matrix"] == "added_mass"]
            if sel:
                w.writerow(_measured(cls, "added_mass", fam, sel))
        if cls == PANELS:
            continue              # damping of a panel-method model: its geometric class's rows
        tr, rot = ASSUMED_DRAG[cls]
        for fam, sd in (("translation", tr), ("rotation", rot)):
            sel = [r for r in rows if r["class"] == cls and r["family"] == fam
                   and r["matrix"] == "quadratic_damping"]
            if len({r["shape"] for r in sel}) >= MIN_SHAPES:
                w.writerow(_measured(cls, "quadratic_damping", fam, sel))
                continue
            what = (f"stored CFD rotations of {len({r['shape'] for r in sel})} shape(s) of "
                    f"the class (reference_tables/cfd; {MIN_SHAPES} needed)"
                    if fam == "rotation" else
                    f"measured drag of {len({r['shape'] for r in sel})} shape(s) of the class "
                    f"stored (reference_tables/body_drag_3d; {MIN_SHAPES} needed)")
            w.writerow([cls, "quadratic_damping", fam, "lognormal", f"{sd:g}", "assumed", 0, 0, "", "",
                        f"no drag reference independent of the method's own correlations (Hoerner "
                        f"1965, DNV-RP-C205) for this class and DOF group: {what}; an assumed "
                        f"sd(ln), checked on held-out measurements by benchmarks/band_coverage.py", ""])
        for fam in ("translation", "rotation"):
            w.writerow([cls, "linear_damping", fam, "lognormal", "2.5", "not_predicted", 0, 0,
                        "", "", "not predicted: the method's drag is quadratic and its linear part "
                            "only the Reynolds-number share; measured linear damping (Wang & Clark "
                            "2006) is 13-560x larger. A placeholder spread, not a band: excluded "
                            "from the coverage check", ""])
        if cls in LIFT_MEASURED_CLASSES:
            w.writerow(lift_row(cls))
        else:
            w.writerow([cls, "lift", "all", "lognormal", f"{ASSUMED_LIFT:g}", "assumed", 0, 0,
                        "", "", LIFT_ELSEWHERE, ""])
        w.writerow([cls, "control", "all", "lognormal", f"{ASSUMED_LIFT:g}", "assumed", 0, 0,
                    "", "", CONTROL_REASON, ""])
    return out.getvalue()


def main(argv=None):
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--measure", action="store_true",
                    help="rerun stripcoef on the reference shapes (writes method_errors.csv)")
    ap.add_argument("--measure-rotation", action="store_true",
                    help="refresh only the rotational drag rows of method_errors.csv (the "
                         "stored CFD rotations against the model)")
    ap.add_argument("--check", action="store_true",
                    help="exit 1 if the committed table differs from the regenerated one")
    args = ap.parse_args(argv)
    if args.measure:
        write_errors(measure())
    elif args.measure_rotation:
        write_errors([r for r in read_errors() if r["set"] != CFD_SET] + cfd_rotation_rows())
    text = make_table(read_errors())
    if args.check:
        return 0 if TABLE.read_text() == text else 1
    TABLE.write_text(text)
    print(f"wrote {TABLE.relative_to(ROOT)}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
