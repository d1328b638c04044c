"""Bluff shapes (issue 14): Lamb's exact triaxial ellipsoid, the stored BEM references, the
BlueROV2-Heavy-like vehicle, no NaN matrices, and the BEM panel-quality check."""

from __future__ import annotations

import importlib
import csv
from pathlib import Path

import numpy as np
import pytest
import trimesh

from stripcoef.errors import InputError
from stripcoef.hull.lamb import ellipsoid_added_mass, spheroid_added_mass

ROOT = Path(__file__).resolve().parents[1]
DATA = ROOT / "reference_tables" / "bem" / "bem_bluff.csv"
RHO = 1000.0


def _references(column="richardson"):
    lines = [ln for ln in open(DATA) if not ln.startswith("#")]
    out = {}
    for r in csv.DictReader(lines):
        m = out.setdefault(r["shape"], np.zeros((6, 6)))
        m[int(r["i"]), int(r["j"])] = m[int(r["j"]), int(r["i"])] = float(r[column])
    return out


# --- exact: Lamb's triaxial ellipsoid ------------------------------------------------------

@pytest.mark.parametrize("a,b", [(0.75, 0.1), (0.3, 0.15), (1.0, 0.999)])
def test_triaxial_reduces_to_spheroid(a, b):
    exact = spheroid_added_mass(a, b, rho=RHO)
    got = ellipsoid_added_mass(a, b, b, rho=RHO)
    np.testing.assert_allclose(got, exact, rtol=1e-10, atol=1e-12 * exact.max())


def test_triaxial_sphere_and_axis_permutation():
    r = 0.2
    got = ellipsoid_added_mass(r, r, r, rho=RHO)
    np.testing.assert_allclose(got[:3], 0.5 * RHO * 4 / 3 * np.pi * r ** 3, rtol=1e-12)
    assert np.all(got[3:] == 0.0)
    a, b, c = 0.3, 0.15, 0.08                     # relabelling the axes permutes the terms
    m = ellipsoid_added_mass(a, b, c, rho=RHO)
    p = ellipsoid_added_mass(b, c, a, rho=RHO)
    np.testing.assert_allclose(p, m[[1, 2, 0, 4, 5, 3]], rtol=1e-12)


@pytest.mark.parametrize("shape,axes", [("triaxial_wide", (0.15, 0.3, 0.08)),
                                        ("triaxial_long", (0.3, 0.15, 0.08)),
                                        ("oblate", (0.2, 0.2, 0.08)),
                                        ("sphere", (0.15, 0.15, 0.15))])
def test_stored_bem_matches_lamb(shape, axes):
    """The stored Capytaine references (Richardson of two resolutions) agree with Lamb to
    0.5 % on every diagonal term that is not zero by symmetry: checks both the formulas and the
    reference pipeline (tolerance: the uv-sphere tessellation, about 0.3 % at 4400 faces)."""
    ref = np.diag(_references()[shape])
    exact = ellipsoid_added_mass(*axes, rho=RHO)
    on = exact > 1e-6 * exact.max()
    np.testing.assert_allclose(ref[on], exact[on], rtol=5e-3)


def _benchmark():
    return importlib.import_module("benchmarks.bluff_shapes")


def test_reference_table_complete():
    """Every shape of the benchmark (24: 18 plus the six asymmetric ones) has its stored
    reference, finite, with positive translational diagonals."""
    refs = _references()
    assert set(refs) == set(_benchmark().SHAPES) and len(refs) == 24
    for name, m in refs.items():
        assert np.all(np.isfinite(m)) and np.all(np.diag(m)[:3] > 0), name


ASYMMETRIC = ("box_skid", "box_pod_top_aft", "l_block", "cyl_float", "chamfer_box", "twin_hull")


@pytest.mark.parametrize("name", ASYMMETRIC)
def test_asymmetric_shapes_are_closed_bluff_bodies_with_couplings(name):
    """The six asymmetric bluff shapes (issue 14's off-diagonal terms): one watertight body of
    positive volume, centred on its centroid, put in the bluff class by its geometry, and with
    at least one significant coupling (>= 1 % of sqrt(A_ii A_jj)) in its stored reference."""
    from stripcoef.geometry.vehicle import Vehicle
    from stripcoef.study.shapes import shape_class

    bs = _benchmark()
    m = bs.strip_mesh(name)
    assert m.is_watertight and m.is_winding_consistent and m.volume > 0
    assert m.body_count == 1
    np.testing.assert_allclose(m.center_mass, 0.0, atol=1e-9)
    assert shape_class(Vehicle.from_mesh(m, name=name)) == "bluff"
    assert any(i != j for i, j in bs.significant_terms(_references()[name]))


# --- no NaN: the frame sliced along another axis, the vehicle file ------------------------

@pytest.mark.slow
def test_frame_mesh_across_axes_is_finite():
    """The BlueROV2-like frame sliced along y used to give an all-NaN matrix (an equivalent
    body touching the axis along strips); every slicing axis now gives a finite, symmetric,
    positive-definite M_A by strip theory. (``auto`` takes the panel method for this mesh,
    which does not slice it: the strips are asked for by name, as the regression was theirs;
    the mesh's panel M_A is asserted in tests/test_vehicle_surface.py.)  60 strips: the frame
    is now cut into members (hull/members.py), whatever the strip count; the smallest
    eigenvalues at 60 strips are 0.28, 0.24, 0.41 (0.28, 0.15, 0.44 at 200), 4 instead of 14 s
    of CPU.  (The run split that cured the NaN, hull/corrections.py's ``_positive_runs``, is
    no longer reached by this mesh: replacing it by one run changes nothing at 60 or 200.)"""
    from stripcoef.assembly.estimate import estimate
    from stripcoef.geometry.vehicle import Vehicle
    for axis in "xyz":
        v = Vehicle.from_mesh(ROOT / "geometry" / "bluerov2_heavy.stl", axis=axis)
        a = np.asarray(estimate(v, strips=60, added_mass_method="strips").added_mass)
        assert np.all(np.isfinite(a)), axis
        assert np.linalg.eigvalsh(a).min() > 0, axis


def test_nonfinite_matrix_is_an_error(monkeypatch):
    import importlib
    est = importlib.import_module("stripcoef.assembly.estimate")
    methods = importlib.import_module("stripcoef.assembly.methods")   # strip theory's M_A
    real = methods.added_mass

    def nan_added_mass(*args, **kwargs):
        m, info = real(*args, **kwargs)
        return np.full_like(m, np.nan), info
    monkeypatch.setattr(methods, "added_mass", nan_added_mass)
    with pytest.raises(InputError, match="non-finite"):
        est.estimate(ROOT / "geometry" / "sphere.yaml", strips=50)


def test_bluerov2_heavy_vehicle_file():
    import warnings

    from stripcoef.assembly.estimate import estimate
    from stripcoef.errors import ModelWarning
    with warnings.catch_warnings():
        warnings.simplefilter("error", ModelWarning)        # e.g. weight and buoyancy differ
        # strip theory: the buoyancy check (the panel method's added mass of the frame warns
        # that it has not converged at the default panels: tests/test_vehicle_surface.py)
        m = estimate(ROOT / "geometry" / "bluerov2_heavy.yaml", strips=300,
                     added_mass_method="strips")
    assert m.mass == pytest.approx(11.5)
    assert abs(m.volume * m.density - m.mass) < 0.05 * m.mass       # near neutral [P]
    assert len(m.thrusters) == 8
    assert np.all(np.isfinite(m.added_mass)) and np.linalg.eigvalsh(m.added_mass).min() > 0


def test_bluerov2_mesh_dimensions():
    """The published overall size; the round parts' polygons (16 sides, of the circles' areas:
    geometry/surface.py) stand 1.3 % of their radius out at their vertices (0.65 mm)."""
    mesh = trimesh.load(ROOT / "geometry" / "bluerov2_heavy.stl", force="mesh")
    np.testing.assert_allclose(np.ptp(mesh.vertices, axis=0), [0.457, 0.5373, 0.254], atol=1.5e-3)


# --- BEM panel quality ---------------------------------------------------------------------

def test_panel_quality_flags_long_panels():
    from stripcoef.bem import panel_quality
    bad = panel_quality(trimesh.creation.capsule(height=1.2, radius=0.1))
    assert not bad["trusted"] and bad["max_aspect"] > 50
    good = panel_quality(trimesh.creation.box([1.0, 0.5, 0.3]).subdivide().subdivide())
    assert good["trusted"] and good["area_fraction"] == 0.0


def test_compare_text_says_untrusted():
    from stripcoef.cli.compare import compare_rows, format_comparison
    a = np.diag([1.0, 2.0, 2.0, 0.0, 0.5, 0.5])
    rows = compare_rows(a, 1.5 * a)
    for r in rows:
        r["diff_percent"] = None
    data = {"name": "capsule", "faces": 4096, "reference_point": [0, 0, 0], "density": 1000.0,
            "strips": 1000, "corrections": True, "repairs": [], "speedup": 10.0,
            "seconds": {"load": 0.1, "strip_theory": 0.1, "bem": 1.0}, "terms": rows,
            "panel_quality": {"trusted": False, "area_fraction": 0.86, "max_aspect": 122.0,
                              "limit": 20.0}}
    text = format_comparison(data)
    assert "NOT TRUSTED" in text and "%" not in text.split("diff %")[1].split("(values")[0]
    assert "strip theory (1000 strips" in text
    # the default (auto) sends a bluff mesh to the panel method: the text says which was compared
    data["added_mass_method"] = "3D panel method (stripcoef.hull.panels, Richardson from 360 and 1440 panels)"
    assert "stripcoef (3D panel method" in format_comparison(data)


@pytest.mark.xfail(strict=True, raises=AssertionError,
                   reason="issue 14, not fixed: the member decomposition treats the "
                   "overlapping parts of a frame differently from their boolean union (sway "
                   "+32 %, pitch +98 % at 400 strips; +11 %, +86 %, yaw +118 % at 60)")
@pytest.mark.slow
def test_frame_union_and_overlapping_parts_agree():
    """By strip theory, asked for by name: ``auto`` sends both meshes to the panel method,
    which refuses the overlapping parts' degenerate faces (an InputError, not the mismatch
    this test is about); ``raises=AssertionError``: only the mismatch is the expected
    failure.  60 strips: 2.5 s of CPU (200: 13 s, the same mismatch, pitch -44 %, yaw
    +88 %)."""
    from benchmarks.bluff_shapes import _bluerov2, former_bluerov2_parts

    from stripcoef.assembly.estimate import estimate
    from stripcoef.geometry.vehicle import Vehicle
    union = Vehicle.from_mesh(_bluerov2())
    parts = Vehicle.from_mesh(trimesh.util.concatenate(former_bluerov2_parts()))
    a = np.diag(estimate(union, strips=60, added_mass_method="strips").added_mass)
    b = np.diag(estimate(parts, strips=60, added_mass_method="strips").added_mass)
    np.testing.assert_allclose(b, a, rtol=0.05)


def test_stored_cylinder_reference_matches_axisymmetric_solver():
    """The short cylinder along x (D 0.30, L 0.25 m) is a body of revolution: the stored BEM
    (Richardson) and stripcoef's axisymmetric solver of the same body agree within 3 % on
    every term (the BEM converges slowly at the sharp edges: 2.7 % on pitch; see
    docs/validation.md) -- the check that caught the end-cap fans' +12 %."""
    from stripcoef.hull.axisymmetric import body_of_revolution_added_mass
    exact = np.diag(body_of_revolution_added_mass([-0.125, -0.125, 0.125, 0.125],
                                                  [0.0, 0.15, 0.15, 0.0], rho=RHO, panels=320))
    ref = np.diag(_references()["cyl_x_short"])
    on = exact > 0
    np.testing.assert_allclose(ref[on], exact[on], rtol=0.03)
