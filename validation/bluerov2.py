"""docs/validation.md: the shipped BlueROV2 Heavy against its published dimensions and the
published identified models of the vehicle (issue 32).

Two parts:

- **dimensions**: the shipped vehicle file and mesh (``scripts/make_bluerov2_heavy.py``)
  against what Blue Robotics publishes (``reference_tables/bluerov2/dimensions.csv``; sources,
  commits and licenses in its README), read live (a YAML parse and an STL's bounds);
- **added mass**: the stored run of this module
  (``reference_tables/bluerov2/runs/stripcoef_run.csv``, its command on the first line):
  ``stripcoef coefficients FILE --rho 1000 --json`` on the shipped vehicle file and mesh and
  on the physical meshes of the public Stonefish BlueROV2 description, beside the identified
  added mass of von Benzon et al. (2022) and Wu (2018)
  (``reference_tables/bluerov2/identified.csv``). A measurement: nothing is fitted.

Potential-flow added mass A_ii = rho * integral(phi_i n_i dS) (Newman 1977, *Marine
Hydrodynamics*, sec. 4.13, eq. 4.125) [kg, kg m^2] is what stripcoef computes; an identified
"added mass" is the inertia term a time-domain fit assigns to acceleration (tank tests at finite
amplitude and frequency, viscous and tether effects lumped in), so the two need not agree even
for an exact geometry.

Re-run (the Stonefish meshes are read from a local clone of bvibhav/stonefish_bluerov2 at the
commit below, ``MIRROR/bvibhav+stonefish_bluerov2`` or ``MIRROR/stonefish_bluerov2``, a working
tree or a bare git directory):

    OPENBLAS_NUM_THREADS=1 python -m validation.bluerov2 --mirror MIRROR \\
        --csv reference_tables/bluerov2/runs/stripcoef_run.csv
"""

from __future__ import annotations

import argparse
import csv
import json
import os
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from validation import ROOT, markdown_table, read_stored_run

DATA = ROOT / "reference_tables" / "bluerov2"
RUN = DATA / "runs" / "stripcoef_run.csv"
DOFS = ("surge", "sway", "heave", "roll", "pitch", "yaw")
#: identified-model row names per DOF (reference_tables/bluerov2/identified.csv)
TERMS = ("X_udot", "Y_vdot", "Z_wdot", "K_pdot", "M_qdot", "N_rdot")
RHO = 1000.0

#: the public Stonefish BlueROV2 description (Apache-2.0): repository, commit, physical meshes
SF_REPO = "bvibhav/stonefish_bluerov2"
SF_COMMIT = "6448383af6b7ef6083b0eac2c08102660591e318"
SF_BASE = "data/bluerov2/bluerov2_phy.obj"
SF_HEAVY = "data/bluerov2/bluerov2_ring.obj"
#: scenarios/bluerov2.scn places the heavy part's physical mesh at <origin xyz="0 0 0.03"/> [m]
SF_HEAVY_OFFSET = (0.0, 0.0, 0.03)

#: the runs of the stored table: label, file, the options after ``--rho 1000 --json``
FILES = (
    ("shipped vehicle file", "geometry/bluerov2_heavy.yaml", ()),
    ("shipped vehicle file, 6000 panels", "geometry/bluerov2_heavy.yaml",
     ("--added-mass-panels", "6000")),
    ("shipped vehicle file, strips", "geometry/bluerov2_heavy.yaml",
     ("--added-mass-method", "strips")),
    ("shipped mesh", "geometry/bluerov2_heavy.stl", ()),
    ("Stonefish physical mesh, base", f"{SF_REPO}@{SF_COMMIT[:10]}:{SF_BASE}", ()),
    ("Stonefish physical mesh, heavy", f"{SF_REPO}@{SF_COMMIT[:10]}:{SF_BASE} + {SF_HEAVY}",
     ()),
)
COLUMNS = ("label", "file", "options", "dof", "added_mass", "estimated_error", "volume", "method",
           "panel_levels", "converged", "extent", "seconds", "error")


# ---------------------------------------------------------------------------- the stored run

def _git_show(mirror: Path, path: str) -> bytes:
    """A file of the Stonefish description at :data:`SF_COMMIT` from a local clone."""
    owner, name = SF_REPO.split("/")
    for base in (mirror / f"{owner}+{name}", mirror / name):
        for cand in (base / "repo", base / ".git", base):
            if not cand.is_dir():
                continue
            out = subprocess.run(["git", "--git-dir", str(cand), "show", f"{SF_COMMIT}:{path}"],
                                 capture_output=True)
            if out.returncode == 0:
                return out.stdout
    raise FileNotFoundError(f"{SF_REPO}@{SF_COMMIT[:10]}:{path} not under {mirror}")


def _run_cli(path: Path, extra=()) -> tuple[dict | None, str, float]:
    """``stripcoef coefficients PATH --rho 1000 --json [EXTRA]`` as a user runs it:
    (JSON or None, the error line of a refused run, wall [s])."""
    cmd = [sys.executable, "-m", "stripcoef", "coefficients", str(path), "--rho", str(RHO),
           "--json", *extra]
    t0 = time.perf_counter()
    out = subprocess.run(cmd, capture_output=True, text=True)
    dt = time.perf_counter() - t0
    if out.returncode != 0:
        err = [ln for ln in out.stderr.splitlines() if "error:" in ln] or [f"exit {out.returncode}"]
        return None, err[-1].split("error:", 1)[-1].strip().replace(str(path), path.name), dt
    return json.loads(out.stdout), "", dt


def _rows(label: str, file: str, extra, data: dict | None, error: str,
          seconds: float) -> list[dict]:
    import numpy as np

    common = {"label": label, "file": file, "options": " ".join(extra), "error": error,
              "seconds": f"{seconds:.1f}"}
    if data is None:
        return [{**common, "dof": d, "added_mass": "nan", "estimated_error": "nan",
                 "volume": "nan", "method": "", "panel_levels": "", "converged": "0",
                 "extent": ""} for d in DOFS]
    a = np.asarray(data["added_mass"], float)
    err = np.asarray(data.get("added_mass_error") or np.zeros((6, 6)), float)
    cond = data["conditions"]
    levels = cond.get("added_mass_panel_levels") or []
    extent = [cond.get(k) for k in ("length", "breadth", "height")]
    return [{**common, "dof": DOFS[i], "added_mass": f"{a[i, i]:.6g}",
             "estimated_error": f"{err[i, i]:.6g}", "volume": f"{data['volume']:.6g}",
             "method": cond.get("added_mass_method", ""),
             "panel_levels": "/".join(str(n) for n in levels),
             "converged": str(int(bool(cond.get("added_mass_converged", True)))),
             "extent": " x ".join(f"{float(e):.4g}" for e in extent if e is not None)}
            for i in range(6)]


def main(argv=None) -> int:
    import trimesh

    p = argparse.ArgumentParser(prog="python -m validation.bluerov2", description=__doc__,
                                formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("--mirror", type=Path, required=True,
                   help="folder holding a clone of bvibhav/stonefish_bluerov2")
    p.add_argument("--csv", type=Path, default=RUN, help="the stored run to write")
    args = p.parse_args(argv)
    os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        base = tmp / "bluerov2_phy.obj"
        base.write_bytes(_git_show(args.mirror, SF_BASE))
        ring = tmp / "bluerov2_ring.obj"
        ring.write_bytes(_git_show(args.mirror, SF_HEAVY))
        heavy = tmp / "bluerov2_heavy_phy.obj"
        r = trimesh.load(ring, force="mesh")
        r.apply_translation(SF_HEAVY_OFFSET)
        trimesh.util.concatenate([trimesh.load(base, force="mesh"), r]).export(heavy)
        paths = {"Stonefish physical mesh, base": base, "Stonefish physical mesh, heavy": heavy}
        for label, file, extra in FILES:
            data, error, dt = _run_cli(paths.get(label, ROOT / file), extra)
            rows += _rows(label, file, extra, data, error, dt)
            print(f"{label}: {dt:.1f} s", file=sys.stderr)
    command = ("OPENBLAS_NUM_THREADS=1 python -m validation.bluerov2 --mirror MIRROR --csv "
               + str(args.csv))
    tmp_csv = args.csv.with_suffix(".tmp")
    with open(tmp_csv, "w", newline="") as fh:
        fh.write(f"# {command}\n")
        w = csv.DictWriter(fh, fieldnames=COLUMNS)
        w.writeheader()
        w.writerows(rows)
    tmp_csv.replace(args.csv)
    return 0


# ---------------------------------------------------------------------------- the section

def _published() -> dict[str, float]:
    from validation import reference as ref

    return {r["name"]: r["value"] for r in ref.load_table("bluerov2", "dimensions")}


def _identified() -> dict[str, dict[str, float]]:
    from validation import reference as ref

    out: dict[str, dict[str, float]] = {}
    for r in ref.load_table("bluerov2", "identified"):
        model, term = r["name"].split(".", 1)
        out.setdefault(model, {})[term] = r["value"]
    return out


def dimension_rows() -> list[list]:
    """(quantity, shipped, published, source): the shipped files against the published
    dimensions (reference_tables/bluerov2/dimensions.csv)."""
    import numpy as np
    import trimesh
    import yaml

    pub = _published()
    data = yaml.safe_load((ROOT / "geometry" / "bluerov2_heavy.yaml").read_text())
    mesh = trimesh.load(ROOT / "geometry" / "bluerov2_heavy.stl", force="mesh")
    ext = np.ptp(mesh.vertices, axis=0)
    parts = {a["name"]: a for a in data["appendages"]}
    side = parts["post_fore_starboard"]
    frame_width = 2 * (side["center"][1] + 0.5 * side["size"][1])
    hull = data["hull"]["profile"]
    tube = hull[0]["x"][1] - hull[0]["x"][0]
    thr = data["thrusters"]
    hor = [t for t in thr if t["direction"][2] == 0]
    ver = [t for t in thr if t["direction"][2] != 0]
    mm = 1e-3
    return [
        ["length [m]", f"{ext[0]:.4f} (mesh)", f"{pub['heavy.length'] * mm:.3f}", "BR-H"],
        ["height [m]", f"{ext[2]:.4f} (mesh)", f"{pub['heavy.height'] * mm:.3f}", "BR-H"],
        ["frame width [m]", f"{frame_width:.4f}", f"{pub['base.width'] * mm:.3f}", "BR-2"],
        ["overall width [m]", f"{ext[1]:.4f} (mesh: guards left out)",
         f"{pub['heavy.width'] * mm:.3f} (with guards)", "BR-H"],
        ["mass in air [kg]", f"{data['mass']['mass']:.4g}", f"{pub['heavy.mass_in_air']:.4g}",
         "BR-H"],
        ["displaced volume x rho [kg]", f"{mesh.volume * RHO:.4g} (mesh)",
         f"{pub['heavy.mass_in_air']:.4g} (near neutral)", "BR-2"],
        ["side panel thickness [m]", f"{side['size'][1]:.6f}",
         f"{pub['side_panel.thickness'] * mm:.6f}", "BR-A"],
        ["bottom panel thickness [m]", f"{parts['bottom_strip_fore']['size'][2]:.4f}",
         f"{pub['bottom_panel.thickness'] * mm:.4f}", "BR-A"],
        ["electronics tube outside diameter [m]", f"{2 * hull[0]['radius']:.4f}",
         f"{pub['tube4.outer_diameter'] * mm:.4f}", "BR-W"],
        ["electronics tube with flanges and end caps [m]", f"{tube:.4f}",
         f"{pub['tube4.total_length'] * mm:.4f}", "BR-W"],
        ["battery tube outside diameter [m]", f"{parts['battery_tube']['diameter']:.4f}",
         f"{pub['tube3.outer_diameter'] * mm:.4f}", "BR-W"],
        ["battery enclosure length [m]", f"{parts['battery_tube']['length']:.5f}",
         f"{pub['battery_enclosure.length'] * mm:.5f}", "BR-A, BR-W"],
        ["T200 duct outside diameter x length [m]",
         f"{parts['t200_vert_fs']['diameter']:.3f} x {parts['t200_vert_fs']['length']:.3f}",
         f"{pub['t200.diameter'] * mm:.3f} x {pub['t200.length'] * mm:.3f}", "BR-T"],
        ["T200 thrust forward / reverse [N]",
         f"{thr[0]['max_forward']:.2f} / {thr[0]['max_backward']:.2f}",
         f"{pub['t200.max_forward_16V'] * 9.80665:.2f} / "
         f"{pub['t200.max_reverse_16V'] * 9.80665:.2f}", "BR-T"],
        ["horizontal thrusters x fore / aft, |y| [m]",
         f"{max(t['position'][0] for t in hor):.4f} / {min(t['position'][0] for t in hor):.4f},"
         f" {abs(hor[0]['position'][1]):.3f}",
         f"{pub['sf.horizontal_fore.x']:.4f} / {pub['sf.horizontal_aft.x']:.4f}, "
         f"{pub['sf.horizontal.y']:.3f}", "SF"],
        ["vertical thrusters |x|, |y| [m]",
         f"{abs(ver[0]['position'][0]):.3f}, {abs(ver[0]['position'][1]):.3f}",
         f"{pub['sf.vertical.x']:.3f}, {pub['sf.vertical.y']:.3f} (IG: "
         f"{pub['ig.vertical.x']:.3f}, {pub['ig.vertical.y']:.3f})", "SF, IG"],
        ["thrusters' height below the frame's middle: horizontal / vertical [m]",
         f"{hor[0]['position'][2]:.4f} / {ver[0]['position'][2]:.4f}",
         f"{pub['sf.horizontal.z'] - pub['sf.origin_above_mid_height']:.4f} / "
         f"{-pub['sf.origin_above_mid_height']:.4f}", "SF"],
    ]


def added_mass_table() -> tuple[str, list[list], dict]:
    """(command, rows, facts): per run of the stored table and per identified model the
    diagonal added mass (magnitudes), the shipped vehicle file's default run over each
    identified model, and the facts the text states."""
    command, rows = read_stored_run(RUN)
    runs: dict[str, dict] = {}
    for r in rows:
        runs.setdefault(r["label"], {})[r["dof"]] = r
    ident = _identified()
    table = []
    for label, _, _ in FILES:
        terms = runs[label]
        head = terms[DOFS[0]]
        if head["error"]:
            table.append([label, *["refused"] * 6, "-", "no", "-", head["seconds"]])
            continue
        table.append([label, *[f"{float(terms[d]['added_mass']):.4g} ± "
                               f"{float(terms[d]['estimated_error']):.2g}" for d in DOFS],
                      head["panel_levels"] or "-", "yes" if head["converged"] == "1" else "no",
                      f"{float(head['volume']):.4g}", head["seconds"]])
    for model in ("vb2022", "wu2018"):
        table.append([model + " (identified)", *[f"{ident[model][t]:.4g}" for t in TERMS],
                      "-", "-", "-", "-"])
    # the shipped vehicle file as a user runs it: the default, else the run its error advises
    ours_label = next((label for label, file, extra in FILES
                       if file.endswith(".yaml") and "strips" not in extra
                       and not runs[label][DOFS[0]]["error"]), FILES[0][0])
    ours = runs[ours_label]
    a = {d: float(ours[d]["added_mass"]) for d in DOFS}
    e = {d: float(ours[d]["estimated_error"]) for d in DOFS}
    for model in ("vb2022", "wu2018"):
        table.append([f"{ours_label} / {model}",
                      *[f"{a[d] / ident[model][t]:.2f}" for d, t in zip(DOFS, TERMS)],
                      "-", "-", "-", "-"])
    lo = {d: min(ident[m][t] for m in ident) for d, t in zip(DOFS, TERMS)}
    hi = {d: max(ident[m][t] for m in ident) for d, t in zip(DOFS, TERMS)}
    spread = max(DOFS, key=lambda d: hi[d] / lo[d])
    facts = {
        "ours": ours_label,
        "in_range": [d for d in DOFS if lo[d] <= a[d] <= hi[d]],
        "in_range_with_error": [d for d in DOFS if lo[d] - e[d] <= a[d] <= hi[d] + e[d]],
        "spread_dof": spread, "spread": hi[spread] / lo[spread],
        "converged": {label: runs[label][DOFS[0]]["converged"] == "1" for label, _, _ in FILES},
        "volume": {label: float(runs[label][DOFS[0]]["volume"]) for label, _, _ in FILES},
        "worst_error": max(DOFS, key=lambda d: e[d] / max(abs(a[d]), 1e-12)),
        "refused": {label: runs[label][DOFS[0]]["error"] for label, _, _ in FILES
                    if runs[label][DOFS[0]]["error"]},
    }
    return command, table, facts


def section() -> str:
    parts = ["## BlueROV2 Heavy against its published dimensions and identified models "
             "(issue 32)\n",
             "The shipped `geometry/bluerov2_heavy.yaml` and `.stl` are written by "
             "`python -m scripts.make_bluerov2_heavy` from Blue Robotics' published dimensions "
             "(tags BR-H, BR-2, BR-A, BR-W, BR-T: reference_tables/bluerov2/README.md, each with "
             "repository, commit, path and section) and the thruster places of the public "
             "Stonefish BlueROV2 Heavy description (SF, Apache-2.0); what is not published (the "
             "panels' cut-outs, the enclosures' places, the foam block) is marked assumed in the "
             "script. Shipped against published:\n",
             markdown_table(["quantity", "shipped", "published", "source"], dimension_rows()),
             "\nThe surface is narrower than the published width because the heavy kit's "
             "thruster guards (open grilles) are left out: potential flow passes them.\n"]
    if not RUN.exists():
        return "\n".join(parts)
    command, table, f = added_mass_table()
    ours = f["ours"]
    default = FILES[0][0]
    first = ("The shipped vehicle file's default run was refused (listed above)"
             if default in f["refused"] else "")
    n_in, n_err = len(f["in_range"]), len(f["in_range_with_error"])
    parts += [
        "Added mass (diagonal, magnitudes [kg; kg m^2 for roll, pitch, yaw], about each run's "
        "centre of buoyancy; ± the model's estimated error) of `stripcoef coefficients FILE "
        "--rho 1000 --json` (and the options named) on the shipped files and on SF's physical "
        "meshes (`data/bluerov2/bluerov2_phy.obj`; heavy: with `bluerov2_ring.obj` where SF's "
        "scenario places it), beside the identified models of von Benzon et al. (2022, vb2022) "
        "and Wu (2018, wu2018) as transcribed by public simulator descriptions "
        "(reference_tables/bluerov2/identified.csv: the papers' tables were not reachable, so "
        "these are unverified transcriptions). The stored run:\n",
        f"    {command}\n",
        markdown_table(["run", *DOFS, "panel levels", "converged", "volume [m^3]", "time [s]"],
                       table),
        *(["\nRefused runs (their one-line error):\n"]
          + [f"- {label}: `{msg}`" for label, msg in f["refused"].items()] if f["refused"]
          else []),
        "\nA measurement against published identified data, not a calibration: nothing was "
        "fitted. " + (first + "; the run " if first else "The run ")
        + f"'{ours}' lies between the two identified "
        f"models in {n_in} of 6 DOFs ({', '.join(f['in_range']) or 'none'}), and within them "
        f"widened by its own estimated error in {n_err} of 6; its panel method "
        f"{'converged' if f['converged'][ours] else 'did not converge'} (largest estimated "
        f"error relative to its term: {f['worst_error']}), so the comparison says more about "
        "the panel method on thin frame members (issue 32) than about the geometry. The "
        f"identified models differ from each other by up to {f['spread']:.2f}x "
        f"({f['spread_dof']}) and were fitted to tank motions (finite amplitude and "
        "frequency, viscous and tether forces lumped into the inertia term), so agreement "
        "within their spread is the most a potential-flow added mass (Newman 1977, sec. 4.13) "
        "can be held to. SF's physical meshes are simulator proxies (solid slabs and posts, "
        f"{f['volume'][FILES[4][0]]:.4g} m^3 against the shipped mesh's "
        f"{f['volume'][FILES[3][0]]:.4g} m^3), not the vehicle's geometry; they are the public "
        "mesh of this vehicle found with a license and a commit (Blue Robotics' own CAD is on "
        "GrabCAD; the meshes of bluerov_ros_playground and bluerov2_ignition are large files "
        "missing from the clones).\n"]
    return "\n".join(parts)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
