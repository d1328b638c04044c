"""docs/validation.md: a vehicle file and a mesh of the same parts give the same added mass
(issue 32).

Both by the 3D panel method (``auto`` on a bluff body): the vehicle file on its parts united
into one closed surface (``stripcoef.geometry.surface``), the mesh as loaded.  Two cases: a
two-part vehicle file (a box hull with a cylindrical nose) against an STL of the same parts
built independently from trimesh primitives (64-sided cylinder), and the shipped BlueROV2
Heavy vehicle file against its mesh (both written by ``scripts/make_bluerov2_heavy.py`` from
one list of parts).  Each term's difference is over the diagonal scale sqrt(M_ii M_jj).
"""

from __future__ import annotations

import tempfile
import warnings
from functools import lru_cache
from pathlib import Path

import numpy as np

from validation import ROOT, markdown_table

RHO = 1000.0
DOFS = ("surge", "sway", "heave", "roll", "pitch", "yaw")


def two_part(offset=(0.0, 0.0, 0.0)) -> dict:
    """A bluff two-part vehicle file (mapping): a 0.4 x 0.3 x 0.2 m box hull (rectangular
    sections) and a cylinder 0.12 m in diameter, 0.2 m long, along x, standing on its front
    face (touching, no overlap: a sensor nose); every part moved by ``offset`` [m]."""
    ox, oy, oz = (float(v) for v in offset)
    return {
        "name": "two_part", "fluid": {"density": RHO, "kinematic_viscosity": 1e-6},
        "hull": {"section": "rectangle", "y": oy, "z": oz,
                 "half_breadth": [{"type": "cylinder", "x": [ox - 0.2, ox + 0.2],
                                   "radius": 0.15}],
                 "half_height": [{"type": "cylinder", "x": [ox - 0.2, ox + 0.2],
                                  "radius": 0.1}]},
        "appendages": [{"name": "pod", "type": "cylinder", "axis": "x",
                        "center": [ox + 0.3, oy, oz + 0.03], "diameter": 0.12,
                        "length": 0.2}],
        "mass": {"default_density": RHO},
    }


def two_part_trimesh(sections: int = 64):
    """The parts of :func:`two_part` built independently from trimesh primitives (an
    inscribed ``sections``-gon cylinder), united by manifold3d."""
    import trimesh

    box = trimesh.creation.box([0.4, 0.3, 0.2])
    cyl = trimesh.creation.cylinder(radius=0.06, height=0.2, sections=sections)
    cyl.apply_transform(trimesh.geometry.align_vectors([0, 0, 1], [1, 0, 0]))
    cyl.apply_translation([0.3, 0.0, 0.03])
    return trimesh.boolean.union([box, cyl], engine="manifold")


def term_errors(a, b) -> np.ndarray:
    """|a - b| per term over the diagonal scale sqrt(b_ii b_jj) [-]."""
    d = np.sqrt(np.abs(np.diag(np.asarray(b, float))))
    return np.abs(np.asarray(a, float) - np.asarray(b, float)) / np.outer(d, d)


@lru_cache(maxsize=1)
def results():
    """(name, vehicle-file model, mesh model) of both cases, about the parts' common origin."""
    from stripcoef.assembly import estimate
    from stripcoef.geometry.vehicle import Vehicle, load_vehicle, parse_vehicle

    out = []
    with warnings.catch_warnings(), tempfile.TemporaryDirectory() as tmp:
        warnings.simplefilter("ignore")     # the panels' convergence, the drag tables' range
        stl = Path(tmp) / "two_part.stl"
        two_part_trimesh().export(stl)
        v = parse_vehicle(two_part(), file="two_part.yaml")
        out.append(("box with a cylindrical nose vs trimesh primitives",
                    estimate(v, reference_point=np.zeros(3)),
                    estimate(Vehicle.from_mesh(stl, origin=(0.0, 0.0, 0.0), fluid=v.fluid))))
        rov = load_vehicle(ROOT / "geometry" / "bluerov2_heavy.yaml")
        mesh = Vehicle.from_mesh(ROOT / "geometry" / "bluerov2_heavy.stl",
                                 origin=(0.0, 0.0, 0.0), fluid=rov.fluid)
        out.append(("BlueROV2 Heavy: geometry/bluerov2_heavy.yaml vs .stl",
                    estimate(rov, reference_point=np.zeros(3)), estimate(mesh)))
    return tuple(out)


def section() -> str:
    rows = []
    for name, a, b in results():
        err = term_errors(a.added_mass, b.added_mass)
        diag = ", ".join(f"{x:.4g}" for x in np.diag(a.added_mass))
        rows.append((name, diag, f"{100 * err.max():.2f} %",
                     f"{a.volume:.5g} / {b.volume:.5g}",
                     f"{100 * (a.volume / b.volume - 1):+.2f} %"))
    return "\n".join([
        "## Vehicle files and meshes of the same parts", "",
        "A bluff vehicle file's added mass is the 3D panel method's on its parts united into "
        "one closed surface (`stripcoef.geometry.surface`, manifold3d), as a mesh's is "
        "(`--added-mass-method auto`). Both by the default 1600 panels, about the parts' common "
        "origin; the largest difference of any term over the diagonal scale "
        "sqrt(M_ii M_jj). Volumes: the vehicle file's strips (they count overlapping parts "
        "twice) / the mesh's. Reproduce: `python -m scripts.make_validation` "
        "(validation/vehicle_surface.py; tests/test_vehicle_surface.py asserts 2 %).", "",
        markdown_table(("case", "vehicle file M_A diagonal [kg, kg m^2]",
                        "largest term difference", "volume file / mesh [m^3]", "volume"),
                       rows), "", shipped_against_bem()])


#: The stored run of benchmarks/panels_vehicles.py (the shipped vehicle files against
#: Capytaine on remeshes of the same surface).
SHIPPED = ROOT / "reference_tables" / "bem" / "panels_vehicles.csv"


def shipped_against_bem() -> str:
    """The shipped vehicle files' default estimate against Capytaine (stored run)."""
    if not SHIPPED.exists():
        return ""
    from validation import read_stored_run

    command, rows = read_stored_run(SHIPPED)
    script, _, rest = command.partition(" ")
    module = script.replace("/", ".").removesuffix(".py")
    table, same = [], []
    for r in rows:
        err, est = float(r["error_rel"]), float(r["estimated_error_rel"])
        same.append(float(r["same_mesh_max_diff_rel"]))
        table.append((Path(r["file"]).name, r.get("install", "remesh extra"), r["dof"],
                      r["estimate"], r["bem"],
                      f"{100 * float(r['bem_gci_rel']):.1f} %", f"{100 * err:+.1f} %",
                      f"{100 * est:.1f} %", "yes" if abs(err) <= est else "no",
                      "yes" if r.get("warned") == "1" else "no",
                      r["panel_levels"], r["bem_faces"]))
    return "\n".join([
        "### The shipped vehicle files against Capytaine on the same surface (issue 32)", "",
        # (an --update run: '; rows of FILE from COMMAND', each command in its own quotes)
        f"`OPENBLAS_NUM_THREADS=1 python -m {module} {rest}`".replace(
            "from " + script, "from `python -m " + module).replace(
            "; rows of ", "`; rows of ") +
        " (the `bem` and `remesh` extras installed). The surface the panel method solves on "
        "(the parts united, 64 sides a circle) remeshed isotropically at the BEM resolutions "
        "named, one remesh family (one crease angle and mode for every level, each level "
        "keeping the surface's area and volume: members thinner than the edge not collapsed); "
        "on each remesh Capytaine and the panel method's one-level solve agree "
        f"within {100 * max(same):.2f} % on every diagonal term (the solver and its near-field "
        "integrals are not the error); the reference is Capytaine's two finest remeshes "
        "Richardson-extrapolated, with its own grid convergence index. The estimate is the "
        "default `stripcoef coefficients FILE` (`auto`, 1600 panels), rho = 1000 kg/m^3, about "
        "the file's reference point, with the `remesh` extra (isotropic levels where the "
        "remesher can follow the members) and as a base install has it (the refined surface, "
        "two levels); warned: the not-converged warning went off.", "",
        markdown_table(("file", "install", "term", "estimate", "Capytaine (Richardson)",
                        "its GCI", "error", "estimated error", "covered", "warned",
                        "panel levels", "BEM faces"), table), ""])
