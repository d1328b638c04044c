"""The lifting fins' Munk compensation as the model's own part (HydroModel.fin_munk_lift,
stripcoef.assembly.fin_munk): the model file keeps it (an older file, which folded it into its
lift, reads as before and says so), and a study's method factors scale it with M_A, not with
the lift (an exact property of the compensation's construction)."""

from __future__ import annotations

import dataclasses
import json
import warnings

import numpy as np
import pytest

from stripcoef.assembly.fin_munk import SOURCE_ROW, scaled
from stripcoef.assembly.lift import munk_lift_matrix
from stripcoef.errors import InputError, ModelWarning
from stripcoef.model import HydroModel, rigid_body_mass_matrix
from stripcoef.modelfile import load_model
from stripcoef.study.sources import scale_matrix

ROWS = list(SOURCE_ROW)


def _compensation(share):
    """dL of a fins' share of M_A lifting along y and z: -L_M(share) in the yaw and pitch rows
    (stripcoef.assembly.lift.fin_munk_compensation)."""
    out = np.zeros((6, 6))
    out[ROWS] = -munk_lift_matrix(share, surge=False)[ROWS]
    return out


def _finned(with_fins: bool = True) -> HydroModel:
    """A torpedo-like model (2 m, 50 kg) whose tail fins' share of M_A is 3 kg in sway and heave
    at x = -0.8 m, their lift 12 kg/m there, and their compensation dL of that share: a seeded
    truth, built without an estimate."""
    rng = np.random.default_rng(34)
    body = np.diag([2.0, 45.0, 45.0, 0.05, 12.0, 12.0])
    share = np.zeros((6, 6))
    x = -0.8
    for i, r in ((1, 5), (2, 4)):
        sign = 1.0 if i == 1 else -1.0
        share[i, i] = 3.0
        share[i, r] = share[r, i] = sign * 3.0 * x
        share[r, r] = 3.0 * x * x
    lift = np.zeros((6, 6))
    lift[1, 1], lift[2, 2] = 12.0 + 20.0, 12.0 + 20.0
    lift[5, 1], lift[4, 2] = 12.0 * x + 5.0, -(12.0 * x + 5.0)
    lift[1, 5], lift[2, 4] = -12.0 * x, 12.0 * x
    lift[5, 5], lift[4, 4] = -12.0 * x * x, -12.0 * x * x
    lift += 1e-3 * rng.normal(size=(6, 6))
    m_a = body + (share if with_fins else 0.0)
    cg = np.array([0.0, 0.0, 0.01])
    return HydroModel(
        name="finned torpedo (test)", reference_point=np.zeros(3),
        rigid_body_mass=rigid_body_mass_matrix(50.0, cg, np.diag([0.2, 14.0, 14.0])),
        added_mass=m_a, linear_damping=np.diag([1.0, 2.0, 2.0, 0.1, 1.0, 1.0]),
        quadratic_damping=np.diag([10.0, 80.0, 80.0, 0.5, 10.0, 10.0]), mass=50.0,
        volume=0.05, center_of_gravity=cg, center_of_buoyancy=np.zeros(3), density=1000.0,
        lift=lift, fin_munk_lift=_compensation(share) if with_fins else np.zeros((6, 6)),
        conditions={"lift": {"fin_munk": {"y": {"fins": ["top", "bottom"], "added_mass": 3.0},
                                          "z": {"fins": ["port", "starboard"],
                                                "added_mass": 3.0}}} if with_fins else {}})


def _write(tmp_path, data, name="model.json"):
    path = tmp_path / name
    path.write_text(json.dumps(data))
    return path


def test_the_model_file_keeps_the_compensation(tmp_path):
    """``lift`` holds L + dL (what every reader of the file has always used with C_A's Munk
    moment), ``fin_munk_lift`` dL: read back, L and dL are the model's, so ``--no-munk`` drops
    dL. A model without lifting fins (MARES) writes no ``fin_munk_lift``."""
    remus, mares = _finned(), _finned(False)
    data = json.loads(json.dumps(remus.to_dict()))
    assert np.array_equal(data["lift"], remus.total_lift)
    assert np.array_equal(data["fin_munk_lift"], remus.fin_munk_lift)
    assert "fin_munk_lift" not in mares.to_dict()
    with warnings.catch_warnings():
        warnings.simplefilter("error", ModelWarning)
        back = load_model(_write(tmp_path, data))
    assert np.array_equal(back.fin_munk_lift, remus.fin_munk_lift)
    np.testing.assert_allclose(back.lift, remus.lift, rtol=0,
                               atol=1e-14 * np.abs(remus.lift).max())
    nu = np.array([1.2, 0.1, -0.05, 0.02, 0.03, 0.1])
    for munk in (True, False):
        np.testing.assert_allclose(back.velocity_forces(nu, munk=munk),
                                   remus.velocity_forces(nu, munk=munk), rtol=1e-12, atol=1e-12)


def test_an_older_model_file_reads_as_before_and_says_so(tmp_path):
    """A file written before ``fin_munk_lift`` (the compensation folded into ``lift``, its
    conditions ``lift.fin_munk`` set): the same forces with the Munk moment, no compensation to
    drop, and a warning naming the file, the key and the way out."""
    remus = _finned()
    data = json.loads(json.dumps(remus.to_dict()))
    del data["fin_munk_lift"]
    path = _write(tmp_path, data, "old.json")
    with pytest.warns(ModelWarning, match=r"old\.json: written before 'fin_munk_lift'.*twice"):
        old = load_model(path)
    assert not np.any(old.fin_munk_lift)
    assert np.array_equal(old.lift, remus.total_lift)
    nu = np.array([1.2, 0.1, -0.05, 0.02, 0.03, 0.1])
    np.testing.assert_allclose(old.velocity_forces(nu), remus.velocity_forces(nu), rtol=1e-12,
                               atol=1e-12)
    # a model without lifting fins has nothing folded: no warning
    with warnings.catch_warnings():
        warnings.simplefilter("error", ModelWarning)
        load_model(_write(tmp_path, _finned(False).to_dict(), "bare.json"))


def test_a_bad_compensation_in_a_model_file_is_named(tmp_path):
    data = json.loads(json.dumps(_finned().to_dict()))
    data["fin_munk_lift"] = data["fin_munk_lift"][:5]
    with pytest.raises(InputError, match="fin_munk_lift") as exc:
        load_model(_write(tmp_path, data))
    assert exc.value.key == "fin_munk_lift"
    data["fin_munk_lift"] = [[float("nan")] * 6] * 6
    with pytest.raises(InputError, match=r"fin_munk_lift\[0\]\[0\]"):
        load_model(_write(tmp_path, data))


def test_scaled_compensation_is_that_of_the_scaled_share():
    r"""dL of M_A scaled DOF by DOF (:math:`M'_{ij} = M_{ij}\sqrt{f_i f_j}`) is dL of the
    scaled fins' share, exactly: the fins' Munk moment stays counted once under any factors."""
    rng = np.random.default_rng(3434)
    a = rng.normal(size=(6, 6))
    share = a @ a.T
    f = rng.uniform(0.3, 3.0, size=6)
    np.testing.assert_allclose(scaled(_compensation(share), f),
                               _compensation(scale_matrix(share, f)), rtol=1e-12, atol=1e-12)


def test_a_study_scales_the_lift_alone_and_the_compensation_with_the_added_mass():
    """``study.evaluate``: the lift factor scales L only (the fins' Munk compensation is not
    lift: with the lift scaled by f the old model kept (1 - f) of the fins' Munk moment); the
    added-mass factors scale M_A and, with it, the compensation."""
    from stripcoef.geometry.vehicle import load_vehicle
    from stripcoef.study.evaluate import Job, evaluate
    from stripcoef.study.sources import method_sources

    from conftest import GEOMETRY

    remus = _finned()
    vehicle = load_vehicle(GEOMETRY / "remus100.yaml")       # its method sources only
    sources = tuple(s for s in method_sources(vehicle, lift=True) if s.kind == "method")
    names = [s.name for s in sources]
    job = Job(data={}, file="remus100.yaml", sources=sources, limits=False, model=remus)
    lift, fin = np.asarray(remus.lift), np.asarray(remus.fin_munk_lift)
    row = [0.5 if n == "lift.all" else 1.0 for n in names]
    out = evaluate(job, row)
    for name, (i, j) in {"N_uv": (5, 1), "M_uw": (4, 2), "N_ur": (5, 5), "Y_uv": (1, 1)}.items():
        assert out[name] == pytest.approx(-(0.5 * lift[i, j] + fin[i, j]), rel=1e-12)
    row = [2.0 if n == "added_mass.translation" else 1.0 for n in names]
    out = evaluate(job, row)
    assert out["N_uv"] == pytest.approx(-(lift[5, 1] + 2.0 * fin[5, 1]), rel=1e-12)
    assert out["N_ur"] == pytest.approx(-(lift[5, 5] + np.sqrt(2.0) * fin[5, 5]), rel=1e-12)


def test_without_the_munk_moment_no_fin_munk_is_left():
    """The model with fins less the one without (the same lift): with the Munk moment, the fins'
    share adds nothing to the linearised yaw and pitch moments per v and w (C_A's Munk part of
    it and dL cancel, their lift alone carries it); without it (``munk=False``, or without C),
    nothing either (neither is counted). The simulator's forces and the limits' balance agree."""
    from stripcoef.limits.balance import LimitOptions, required_force

    fins, bare = _finned(), dataclasses.replace(_finned(False), lift=_finned().lift)

    def jacobian(model, **options):
        base = np.array([1.5, 0, 0, 0, 0, 0.0])
        out = np.zeros((6, 2))
        for k, j in enumerate((1, 2)):
            e = np.zeros(6)
            e[j] = 1e-6
            out[:, k] = -(model.velocity_forces(base + e, **options)
                          - model.velocity_forces(base - e, **options)) / 2e-6
        return out

    for options in ({}, {"munk": False}, {"coriolis": False}):
        with warnings.catch_warnings():
            warnings.simplefilter("error", ModelWarning)
            d = jacobian(fins, **options) - jacobian(bare, **options)
        np.testing.assert_allclose(d[3:], 0.0, atol=1e-6)
        nu = np.array([1.5, 0.2, -0.1, 0.05, 0.1, -0.2])
        limit = required_force(fins, nu, options=LimitOptions(**options))
        np.testing.assert_allclose(limit, fins.velocity_forces(nu, **options)
                                   + fins.restoring(np.zeros(6)), rtol=1e-12, atol=1e-12)
    # dL folded into L (the model before it had a field): munk=False took it off once more
    folded = dataclasses.replace(fins, lift=fins.total_lift, fin_munk_lift=np.zeros((6, 6)))
    d = jacobian(folded, munk=False) - jacobian(bare, munk=False)
    assert d[5, 0] == pytest.approx(-1.5 * fins.fin_munk_lift[5, 1]) and d[5, 0] != 0.0
