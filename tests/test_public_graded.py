"""validation.public_graded: the public meshes' stored model rows against the edge-graded
Capytaine references, moved from the body origin to each run's reference point."""

import csv

import numpy as np
import pytest

from stripcoef.conventions import transform_matrix
from validation import public_graded as G


def _skew(c):
    x, y, z = c
    return np.array([[0.0, -z, y], [z, 0.0, -x], [-y, x, 0.0]])


def _sphere_about(point, ma):
    r"""The exact added mass [kg, kg m, kg m^2] of a sphere centred on the origin, about
    ``point`` P: only the centre's velocity moves the fluid (its added mass ``ma`` = rho V / 2,
    no rotational term about the centre: Newman 1977, sec. 4.13), and the centre moves at
    v_P + omega x (O - P) = v_P - S(c) omega, c = O - P, so the kinetic energy
    ma |v_P - S(c) omega|^2 / 2 gives A_P = ma [[I, -S(c)], [S(c), -S(c)^2]]."""
    s = _skew(-np.asarray(point, float))
    return ma * np.block([[np.eye(3), -s], [s, -s @ s]])


def test_the_moved_reference_is_a_translated_spheres_added_mass():
    """The rigid transfer of moved_reference (the library's transform_matrix) gives a sphere
    seen from another point exactly, and a zero band stays zero."""
    ma, point = 2.5, np.array([0.3, -0.2, 0.45])
    ref_p, band_p = G.moved_reference(np.diag([ma] * 3 + [0.0] * 3), np.zeros((6, 6)), point)
    np.testing.assert_allclose(ref_p, _sphere_about(point, ma), rtol=0, atol=1e-13)
    assert not band_p.any()


def test_the_moved_reference_keeps_the_kinetic_energy_of_any_body():
    """Any added mass A_O (symmetric, positive) about O and the same body's about P: for every
    rigid motion the fluid's kinetic energy nu^T A nu / 2 is the same, the velocity of O being
    v_P + omega x (O - P) (rigid-body kinematics): exact to round-off."""
    rng = np.random.default_rng(7)
    b = rng.normal(size=(6, 6))
    a_o = b @ b.T + np.eye(6)
    point = np.array([-0.4, 0.25, 0.1])
    a_p, _ = G.moved_reference(a_o, np.zeros((6, 6)), point)
    for nu_p in rng.normal(size=(5, 6)):
        v, w = nu_p[:3], nu_p[3:]
        nu_o = np.concatenate([v + np.cross(w, -point), w])
        assert nu_p @ a_p @ nu_p == pytest.approx(nu_o @ a_o @ nu_o, rel=1e-12)


def test_graded_terms_move_the_reference_to_the_run_point(tmp_path):
    """Four exact 1/N levels of a sphere about the origin (the Eça & Hoekstra limit is the
    sphere's), a stored run about P whose model is 3 % above the sphere there: every
    diagonal error is +3 % of the graded reference at P, the fitted point is P."""
    ma, point = 2.5, np.array([0.05, -0.02, 0.03])
    limit = np.diag([ma] * 3 + [0.0] * 3) + np.diag([0.0] * 3 + [0.01] * 3)
    counts = [1000, 2000, 4000, 8000]
    with open(tmp_path / "graded.csv", "w", newline="") as fh:
        fh.write("# cmd\n")
        w = csv.writer(fh)
        w.writerow(["shape", "what", "level", "m", "faces", "i", "j", "added_mass", "seconds"])
        for lev, n in enumerate(counts):
            a = limit * (1.0 + 40.0 / n)
            w.writerows(["ball", "sphere", lev, 0.1, n, i, j, f"{a[i, j]:.15g}", 1.0]
                        for i in range(6) for j in range(i, 6))
    ref_p = transform_matrix(limit, to_point=point)
    model = ref_p * np.where(np.eye(6, dtype=bool), 1.03, 1.0)
    with open(tmp_path / "run.csv", "w", newline="") as fh:
        fh.write("# cmd\n")
        w = csv.writer(fh)
        w.writerow(["mesh", "run", "i", "j", "model", "bem", "error_rel", "estimated_error_rel",
                    "significant", "ref_x", "ref_y", "ref_z"])
        for i in range(6):
            for j in range(i, 6):
                sig = int(i == j or abs(ref_p[i, j]) >= 0.01 * np.sqrt(ref_p[i, i] * ref_p[j, j]))
                w.writerow(["ball", "auto", i, j, f"{model[i, j]:.15g}", f"{ref_p[i, j]:.15g}",
                            0.03 if i == j else 0.0, 0.04, sig, *(repr(float(x)) for x in point)])
    terms = G.graded_terms(tmp_path / "graded.csv", tmp_path / "run.csv")
    diag = [t for t in terms if t["i"] == t["j"]]
    assert len(diag) == 6 and len(terms) > 6          # the couplings the move makes
    for t in terms:
        assert t["error_graded"] == pytest.approx(0.03 if t["i"] == t["j"] else 0.0, abs=1e-6)
        assert t["graded"] == pytest.approx(ref_p[t["i"], t["j"]], rel=1e-6, abs=1e-9)
        assert t["covered"]
        assert t["fit"] < 1e-6
    assert "ball" in G.section(tmp_path / "graded.csv", tmp_path / "run.csv")
