"""Each fin's Munk moment counted once, in its lift (stripcoef.assembly.lift.fin_munk_compensation).

Kinds: an exact case (thin-airfoil theory's flat plate, whose moment about the mid chord is its
Munk moment (m22 - m11) U^2 alpha: the lift at the quarter chord and C_A together must give it
once, not twice); an exact linearisation (munk_lift_matrix against the Munk part of
-C_A(nu) nu by central differences); a property of a finned vehicle (the fins' sway force and
yaw moment, the model with fins less the model without, act at the fins' quarter chord: their
added mass adds no moment of its own).
"""

from __future__ import annotations

import copy
import dataclasses
import math
import warnings
from pathlib import Path

import numpy as np
import pytest
import yaml

from stripcoef import estimate
from stripcoef.assembly.lift import fin_munk_compensation, lifting_fins, munk_lift_matrix
from stripcoef.conventions import shift_operator, transform_matrix
from stripcoef.errors import ModelWarning
from stripcoef.geometry.vehicle import parse_vehicle
from stripcoef.hull.lift import fin_lift_matrix, rotary_incidence_point
from stripcoef.model import coriolis_from_mass
from stripcoef.sections.added_mass import flat_plate
from validation.lift import total_linear

ROOT = Path(__file__).resolve().parents[1]
RHO = 1000.0


def _munk_force(mass, nu):
    """The Munk part of -C_A(nu) nu: the moments of C_A's lower-left block [N, N m]."""
    c = coriolis_from_mass(mass, nu)
    out = np.zeros(6)
    out[3:] = -c[3:, :3] @ nu[:3]
    return out


def _plate(chord: float = 0.3, span: float = 1.0):
    """A flat plate of chord c along x, span s along z, normal y, its mid chord at the origin:
    M_A from the 2D plate per unit span (Newman 1977 table 4.2: m22 = rho pi (c/2)^2, the
    rotation rho pi (c/2)^4 / 8) times s, and thin-airfoil lift c_l = 2 pi at the quarter
    chord with the rotation's incidence at the three-quarter chord."""
    m22, m66 = flat_plate(0.5 * chord, rho=RHO)
    mass = np.zeros((6, 6))
    mass[1, 1], mass[5, 5] = m22 * span, m66 * span
    qc = np.array([0.25 * chord, 0.0, 0.0])
    lift = fin_lift_matrix(chord * span, 2.0 * math.pi, [0.0, 1.0, 0.0], qc, rho=RHO,
                           incidence_point=rotary_incidence_point(qc, chord))
    return mass, lift


def _jacobian(mass, lift, u: float = 1.0):
    def force(nu):
        return _munk_force(mass, nu) - nu[0] * lift @ nu
    base = np.array([u, 0, 0, 0, 0, 0.0])
    jac = np.zeros((6, 6))
    for j in range(6):
        e = np.zeros(6)
        e[j] = 1e-6
        jac[:, j] = (force(base + e) - force(base - e)) / 2e-6 / u
    return jac


def test_flat_plate_lift_carries_its_munk_moment():
    """Thin-airfoil theory: the moment about the mid chord, L' c/4 = pi rho U^2 c^2 alpha / 4,
    is the plate's Munk moment (m22 - m11) U^2 alpha (m11 = 0): the lift at the quarter chord
    with C_A's Munk part taken off gives it once; C_A on top of the lift gives it twice."""
    chord = 0.3
    mass, lift = _plate(chord)
    thin_airfoil = -0.5 * RHO * chord ** 2 * (math.pi / 2.0)   # N_v, c_m,mid = pi alpha / 2
    assert mass[1, 1] == pytest.approx(-thin_airfoil, rel=1e-12)   # the identity itself
    once = _jacobian(mass, lift - munk_lift_matrix(mass, surge=False))
    assert np.array_equal(munk_lift_matrix(mass, surge=False), munk_lift_matrix(mass))
    twice = _jacobian(mass, lift)
    assert once[5, 1] == pytest.approx(thin_airfoil, rel=1e-6)
    assert once[1, 1] == pytest.approx(-RHO * math.pi * chord, rel=1e-6)  # 2 pi q c per alpha
    assert twice[5, 1] == pytest.approx(2.0 * thin_airfoil, rel=1e-6)
    # the yaw rate: the lift of the 3/4-chord incidence at the quarter chord, no Munk part
    assert once[5, 5] == pytest.approx(-lift[5, 5], rel=1e-6)


def test_munk_lift_matrix_is_the_linearised_munk_moment():
    rng = np.random.default_rng(34)
    a = rng.normal(size=(6, 6))
    mass = a @ a.T + 6.0 * np.eye(6)
    lm = munk_lift_matrix(mass)
    u = 1.7
    jac = _jacobian(mass, np.zeros((6, 6)), u)       # d(Munk)/d(nu) / u at nu = u e1
    assert np.allclose(lm[:3], 0.0)
    assert np.allclose(-lm[:, 1:], jac[:, 1:], rtol=1e-6, atol=1e-6 * np.abs(mass).max())
    # the surge column: exact at pure surge, -u^2 L_M e1 = the Munk part at nu = u e1
    nu = np.array([u, 0, 0, 0, 0, 0.0])
    assert np.allclose(-u * lm @ nu, _munk_force(mass, nu), atol=1e-9 * np.abs(mass).max())
    # without the surge added mass's part: the same couple about every point
    r = np.array([0.3, -0.2, 0.1])
    moved = transform_matrix(mass, from_point=np.zeros(3), to_point=r)
    nu = rng.normal(size=6)
    nu_b = np.linalg.solve(shift_operator(-r), nu)    # the same motion's velocity at r
    assert np.allclose(munk_lift_matrix(mass, surge=False) @ nu,
                       munk_lift_matrix(moved, surge=False) @ nu_b, rtol=1e-10, atol=1e-10)


def _tail_vehicle(fins: bool):
    data = yaml.safe_load((ROOT / "geometry" / "remus100.yaml").read_text())
    data = copy.deepcopy(data)
    data.update({"reference_point": [-0.1, 0.0, 0.0], "body_lift": "off", "strips": 200})
    if not fins:
        data.pop("appendages")
        data.pop("control_surfaces")
    return parse_vehicle(data, file="remus100 (test)")


@pytest.fixture(scope="module")
def tail_models():          # two estimates of REMUS's hull: about 5 s of CPU
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ModelWarning)
        return estimate(_tail_vehicle(True)), estimate(_tail_vehicle(False))


@pytest.mark.slow
def test_fin_force_acts_at_its_quarter_chord(tail_models):
    """REMUS's hull with and without its four tail fins (no body lift, the same reference
    point): what the fins add to the linearised sway force and yaw moment (lift + the Munk
    part of C_A) acts at their quarter chord, where their lift is; before the fins' Munk
    moment was counted once it sat about a chord ahead of it."""
    finned, bare = tail_models
    vehicle = _tail_vehicle(True)
    fin = next(b for b in vehicle.bodies if b.name == "fin_top")
    x_qc = fin.center[0] + 0.25 * fin.chord - (-0.1)
    d = total_linear(finned) - total_linear(bare)
    # what keeps its Munk moment -(m22 - m11) u v in C_A: the fins' added mass that makes no
    # lift along y (the horizontal fins' edgewise share of m22) and their surge added mass m11
    # (both second order in the fins' thickness); the rest is the lift's
    share = finned.added_mass - bare.added_mass
    lifting = finned.conditions.lift["fin_munk"]["y"]["added_mass"]
    kept = -(share[1, 1] - lifting) + share[0, 0]
    assert d[1, 1] < 0.0 and abs(kept) < 0.05 * lifting
    assert (d[5, 1] - kept) / d[1, 1] == pytest.approx(x_qc, abs=1e-3 * fin.chord)
    assert (d[4, 2] + kept) / d[2, 2] == pytest.approx(-x_qc, abs=1e-3 * fin.chord)
    info = finned.conditions.lift["fin_munk"]
    assert set(info) == {"y", "z"} and info["y"]["fins"] == ["fin_top", "fin_bottom"]
    assert info["y"]["added_mass"] > 0.0


def test_compensation_is_per_lift_axis():
    """A fin makes no lift along its span, so its added mass there keeps its Munk moment:
    a lone vertical fin takes off the yaw row only."""
    vehicle = _tail_vehicle(True)
    data = yaml.safe_load((ROOT / "geometry" / "remus100.yaml").read_text())
    data["appendages"] = [a for a in data["appendages"] if a["name"] == "fin_top"]
    data.pop("control_surfaces")
    one = parse_vehicle(data, file="one fin")
    assert lifting_fins(one) == {"y": ["fin_top"]}
    assert lifting_fins(vehicle) == {"y": ["fin_top", "fin_bottom"],
                                     "z": ["fin_port", "fin_starboard"]}
    mass = np.diag([1.0, 5.0, 3.0, 0.1, 2.0, 2.0])
    mass[1, 5] = mass[5, 1] = -1.5
    mass[2, 4] = mass[4, 2] = 0.7
    delta, info = fin_munk_compensation(mass, lambda v: 0.5 * mass, one)
    assert np.allclose(delta[[0, 1, 2, 3, 4]], 0.0)
    assert delta[5, 1] == pytest.approx(-0.5 * 5.0)     # m22 only: the m11 stays in C_A
    assert delta[5, 5] == pytest.approx(-0.5 * -1.5)
    assert info == {"y": {"fins": ["fin_top"], "added_mass": 2.5}}


@pytest.mark.slow
def test_without_the_munk_moment_the_fins_lift_alone_acts_at_the_quarter_chord(tail_models):
    """``munk=False`` drops C_A's Munk block and the lifting fins' compensation with it: what
    the fins add to the linearised sway force and yaw moment is then their lift alone (their
    Munk moment counted zero times, in C_A and in the compensation), at the quarter chord with
    nothing kept; while the compensation stayed in L it was taken off once with nothing to take
    it from (about a chord behind the quarter chord)."""
    finned, bare = tail_models
    vehicle = _tail_vehicle(True)
    fin = next(b for b in vehicle.bodies if b.name == "fin_top")
    x_qc = fin.center[0] + 0.25 * fin.chord - (-0.1)

    def no_munk(model, u=1.0):
        """d(force)/d(v, w) / u at nu = [u, 0...] without the Munk moment, less D_L: C_A's
        other blocks hold no v or w column there, so it is the lift's [kg/m, kg]."""
        base = np.array([u, 0, 0, 0, 0, 0.0])
        jac = np.zeros((6, 6))
        for j in (1, 2):
            e = np.zeros(6)
            e[j] = 1e-6
            jac[:, j] = -(model.velocity_forces(base + e, munk=False, rigid_body=False)
                          - model.velocity_forces(base - e, munk=False, rigid_body=False)
                          ) / 2e-6 / u + np.asarray(model.linear_damping)[:, j] / u
        return jac

    with warnings.catch_warnings():
        warnings.simplefilter("error", ModelWarning)     # the old warning is gone
        d = no_munk(finned) - no_munk(bare)
    assert np.any(finned.fin_munk_lift) and not np.any(bare.fin_munk_lift)
    assert d[5, 1] / d[1, 1] == pytest.approx(x_qc, abs=1e-3 * fin.chord)
    assert d[4, 2] / d[2, 2] == pytest.approx(-x_qc, abs=1e-3 * fin.chord)
    np.testing.assert_allclose(d[:, 1:3], -(finned.lift - bare.lift)[:, 1:3], rtol=1e-6,
                               atol=1e-6 * np.abs(finned.lift).max())
    # the old model (the compensation folded into L) put it a chord aft of it
    folded = dataclasses.replace(finned, lift=finned.total_lift,
                                 fin_munk_lift=np.zeros((6, 6)))
    old = no_munk(folded) - no_munk(bare)
    assert old[5, 1] / old[1, 1] - x_qc < -0.5 * fin.chord       # measured: -0.99 chord


@pytest.mark.slow        # the shipped REMUS and MARES estimates: about 10 s of CPU
def test_the_compensation_is_counted_with_the_munk_moment_and_dropped_with_it():
    """REMUS (lifting fins) and MARES (none): with the Munk moment the forces are C_A's and
    L + dL's (the model's forces before dL had a field of its own); without it, or without C,
    neither C_A's Munk block nor dL; ``limits``' balance and the simulator's forces agree in
    each case; MARES has no compensation. No warning either way."""
    from conftest import shipped_model
    from stripcoef.limits.balance import LimitOptions, required_force

    rng = np.random.default_rng(341)
    for name in ("remus100.yaml", "mares.yaml"):
        model = shipped_model(name)
        fin = np.asarray(model.fin_munk_lift)
        assert np.any(fin) == (name == "remus100.yaml")
        assert np.array_equal(model.total_lift, model.lift + fin)
        for nu in rng.normal(scale=[1.0, 0.2, 0.2, 0.1, 0.1, 0.2], size=(4, 6)):
            u = nu[0]
            c_a = model.coriolis(nu, rigid_body=False)
            c_a_no = model.coriolis(nu, rigid_body=False, munk=False)
            c_rb = model.coriolis(nu, added_mass=False)
            drag = (model.linear_damping + model.quadratic_damping * np.abs(nu)) @ nu
            with warnings.catch_warnings():
                warnings.simplefilter("error", ModelWarning)
                on = model.velocity_forces(nu)
                off = model.velocity_forces(nu, munk=False)
                no_c = model.velocity_forces(nu, coriolis=False)
                limits_off = required_force(model, nu, options=LimitOptions(munk=False))
                limits_no_c = required_force(model, nu, options=LimitOptions(coriolis=False))
            scale = 1e-12 * (1.0 + np.abs(on).max())
            np.testing.assert_allclose(on, (c_rb + c_a) @ nu + drag + u * model.total_lift @ nu,
                                       atol=scale)
            np.testing.assert_allclose(off, (c_rb + c_a_no) @ nu + drag + u * model.lift @ nu,
                                       atol=scale)
            np.testing.assert_allclose(no_c, drag + u * model.lift @ nu, atol=scale)
            g = model.restoring(np.zeros(6))
            np.testing.assert_allclose(limits_off, off + g, atol=scale)
            np.testing.assert_allclose(limits_no_c, no_c + g, atol=scale)
            np.testing.assert_allclose(model.damping(nu) @ nu, drag + u * model.total_lift @ nu,
                                       atol=scale)

def _toy_method(monkeypatch, factor: float, *, fins_only: bool = False):
    """Register an added-mass method ``toy``: strip theory's M_A times ``factor`` (a seeded
    truth: the fins' share, and so their compensation, is ``factor`` times the strips');
    ``fins_only``: it does not apply to a vehicle without fins (no solve without them)."""
    from stripcoef.assembly import methods
    from stripcoef.geometry.bodies import Fin

    strips = methods.ADDED_MASS_METHODS["strips"]

    def compute(inp):
        m_a = strips.compute(dataclasses.replace(inp, strips=inp.vehicle.cut(None)))[0]
        return factor * m_a, {"toy_factor": factor}, None

    def applies_to(vehicle):
        if fins_only and not any(isinstance(b, Fin) for b in vehicle.bodies):
            return "the toy method needs fins", "a vehicle with fins"
        return None

    monkeypatch.setitem(methods.ADDED_MASS_METHODS, "toy", methods.AddedMassMethod(
        name="toy", description="strips times a factor (test)", applies_to=applies_to,
        compute=compute, error_estimate="none", provenance="toy", in_estimate=False))


@pytest.mark.slow
def test_an_added_mass_swapped_in_gets_its_own_fins_compensation(tail_models, monkeypatch):
    """``with_added_mass_of``: the compensation is the swapped method's own fins' share (a
    method giving twice the strips' M_A gives twice their compensation, the lift unchanged);
    where that method cannot solve the vehicle without its fins, the estimate's compensation
    is kept and a warning says so."""
    from stripcoef.assembly.methods import with_added_mass_of

    finned, _ = tail_models
    vehicle = _tail_vehicle(True)
    _toy_method(monkeypatch, 2.0)
    with warnings.catch_warnings():
        warnings.simplefilter("error", ModelWarning)
        got = with_added_mass_of(finned, vehicle, "toy")
    np.testing.assert_allclose(got.added_mass, 2.0 * finned.added_mass, rtol=1e-12, atol=1e-12)
    np.testing.assert_allclose(got.fin_munk_lift, 2.0 * finned.fin_munk_lift, rtol=1e-9,
                               atol=1e-12 * np.abs(finned.fin_munk_lift).max())
    assert np.array_equal(got.lift, finned.lift)
    info = got.conditions.lift["fin_munk"]
    assert info["method"] == "toy"
    assert info["y"]["added_mass"] == pytest.approx(
        2.0 * finned.conditions.lift["fin_munk"]["y"]["added_mass"], rel=1e-9)
    _toy_method(monkeypatch, 2.0, fins_only=True)
    with pytest.warns(ModelWarning, match="kept from the estimate's added-mass method"):
        kept = with_added_mass_of(finned, vehicle, "toy")
    assert np.array_equal(kept.fin_munk_lift, finned.fin_munk_lift)
    np.testing.assert_allclose(kept.added_mass, 2.0 * finned.added_mass, rtol=1e-12, atol=1e-12)


@pytest.mark.slow        # two REMUS estimates and a panel swap: about 9 s
def test_panels_swapped_in_give_the_panel_estimates_compensation():
    """REMUS: strip theory's model with the panel method's M_A swapped in has the same
    compensation as the panel estimate itself (the panels' fins' share: 1.294 kg in sway, the
    strips' 1.408 kg, which the swapped model kept before)."""
    from stripcoef.assembly.methods import with_added_mass_of
    from stripcoef.geometry.vehicle import load_vehicle

    vehicle = load_vehicle(ROOT / "geometry" / "remus100.yaml")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore", ModelWarning)
        strips = estimate(vehicle)
        panels = estimate(vehicle, added_mass_method="panels")
        got = with_added_mass_of(strips, vehicle, "panels")
    scale = np.abs(panels.fin_munk_lift).max()
    np.testing.assert_allclose(got.fin_munk_lift, panels.fin_munk_lift, rtol=0, atol=1e-9 * scale)
    assert got.conditions.lift["fin_munk"]["method"] == "panels"
    share = {k: got.conditions.lift["fin_munk"][k]["added_mass"] for k in "yz"}
    assert share == pytest.approx({k: panels.conditions.lift["fin_munk"][k]["added_mass"]
                                   for k in "yz"}, rel=1e-9)
    # the strips' share differs (by +9 %): the swap changed the compensation
    assert abs(strips.fin_munk_lift[5, 1] / got.fin_munk_lift[5, 1] - 1.0) > 0.03
