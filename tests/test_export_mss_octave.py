"""The MSS export run in GNU Octave: it must return the model's matrices and equations of motion.

Skipped when ``octave-cli`` is absent, unless STRIPCOEF_REQUIRE_OCTAVE=1 (as in CI), where
a missing Octave is a failure.
"""

from __future__ import annotations

import subprocess
import warnings

import numpy as np
import pytest
from _export_models import octave_or_skip, torpedo

from stripcoef.conventions import kinematics, rotation_matrix
from stripcoef.errors import InputError
from stripcoef.export import export_model, write_export

OUTPUTS = ("xdot", "U", "M", "MRB", "MA", "D", "g", "DL", "DQ", "Bthr")


@pytest.fixture(scope="module")
def octave():
    return octave_or_skip()


def run_octave(exe, folder, script):
    proc = subprocess.run([exe, "--no-gui", "--quiet", "--norc", "--no-window-system",
                           "--eval", script], cwd=folder, capture_output=True, text=True,
                          timeout=120)
    assert proc.returncode == 0, proc.stderr
    return proc.stdout


def call(exe, folder, fname, cases):
    """Call the exported function for each (x, tau, Vc) in one Octave process."""
    parts = []
    for x, tau, vc in cases:
        vec = lambda a: "[" + " ".join(repr(float(v)) for v in a) + "]'"  # noqa: E731
        parts.append(f"[{', '.join(OUTPUTS)}] = {fname}({vec(x)}, {vec(tau)}, {vec(vc)});")
        for name in OUTPUTS:
            parts.append(f"fprintf('%s %d %d', '{name}', size({name}, 1), size({name}, 2)); "
                         f"fprintf(' %.17g', {name}(:)); fprintf('\\n');")
    out = run_octave(exe, folder, " ".join(parts))
    results, current = [], {}
    for line in out.splitlines():
        tok = line.split()
        if not tok or tok[0] not in OUTPUTS:
            continue
        name, rows, cols = tok[0], int(tok[1]), int(tok[2])
        current[name] = np.array([float(v) for v in tok[3:]]).reshape((rows, cols), order="F")
        if name == OUTPUTS[-1]:
            results.append(current)
            current = {}
    assert len(results) == len(cases)
    return results


def expected(model, x, tau, vc):
    """Fossen's equations with irrotational current, from the HydroModel's own methods."""
    nu, eta = np.asarray(x[:6], float), np.asarray(x[6:], float)
    r = rotation_matrix(*eta[3:])
    nu_c = np.concatenate([r.T @ vc, np.zeros(3)])
    nu_c_dot = np.concatenate([-np.cross(nu[3:], nu_c[:3]), np.zeros(3)])
    nu_r = nu - nu_c
    rhs = (tau - model.coriolis(nu, added_mass=False) @ nu
           - model.coriolis(nu_r, rigid_body=False) @ nu_r
           - model.damping(nu_r) @ nu_r - model.restoring(eta) + model.added_mass @ nu_c_dot)
    nu_dot = np.linalg.solve(model.mass_matrix, rhs)
    return {"xdot": np.concatenate([nu_dot, kinematics(eta) @ nu]),
            "U": np.linalg.norm(nu[:3]), "M": model.mass_matrix, "MRB": model.rigid_body_mass,
            "MA": model.added_mass, "D": model.damping(nu_r), "g": model.restoring(eta),
            "DL": model.linear_damping, "DQ": model.quadratic_damping,
            "Bthr": model.allocation()}


CASES = [
    (np.zeros(12), np.zeros(6), np.zeros(3)),
    (np.array([1.2, 0.1, -0.05, 0.02, 0.03, -0.1, 10.0, -3.0, 5.0, 0.1, -0.2, 2.5]),
     np.array([20.0, 1.0, -2.0, 0.1, 0.4, -0.3]), np.zeros(3)),
    (np.array([0.5, -0.2, 0.1, -0.05, 0.08, 0.2, 0.0, 0.0, 2.0, -0.3, 0.25, -1.0]),
     np.array([5.0, 0.0, 3.0, 0.0, -0.2, 0.1]), np.array([0.3, -0.2, 0.05])),
]


@pytest.mark.parametrize("point", ["CO", "CB"])
def test_octave_returns_the_model(octave, tmp_path, point):
    model = torpedo()
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        path = write_export(model, "mss", tmp_path / "torpedo_model.m", point=point)
        ref = model.about({"CO": model.reference_point, "CB": model.center_of_buoyancy}[point])
    assert path.read_text().startswith("function [xdot, U, M, MRB, MA, D, g, DL, DQ, Bthr, L, Bdelta] = "
                                       "torpedo_model(x, tau, Vc, delta)")
    for case, got in zip(CASES, call(octave, tmp_path, "torpedo_model", CASES)):
        want = expected(ref, *case)
        for name in OUTPUTS:
            np.testing.assert_allclose(np.squeeze(got[name]), np.squeeze(want[name]),
                                       rtol=1e-10, atol=1e-12, err_msg=name)


def test_empty_call_returns_the_constant_matrices(octave, tmp_path):
    model = torpedo()
    write_export(model, "mss", tmp_path / "veh.m")
    out = run_octave(octave, tmp_path, "[~, ~, M, MRB, MA] = veh(); fprintf(' %.17g', M(:));")
    m = np.array([float(v) for v in out.split()]).reshape((6, 6), order="F")
    np.testing.assert_allclose(m, model.mass_matrix, rtol=1e-15)


def test_function_name_must_be_an_identifier(tmp_path):
    with pytest.raises(InputError, match="function name"):
        write_export(torpedo(), "mss", tmp_path / "2-bad name.m")
    assert not list(tmp_path.iterdir())
    assert export_model(torpedo(name="my vehicle (v2)"), "mss").startswith(
        "function [xdot, U, M, MRB, MA, D, g, DL, DQ, Bthr, L, Bdelta] = my_vehicle__v2_(")


def test_mss_is_frd_only():
    with pytest.raises(InputError, match="FRD"):
        export_model(torpedo(), "mss", axes="FLU")
