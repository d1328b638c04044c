"""The appendages' trailing-vortex sidewash (hull.vortex, assembly.sidewash; issue 34): exact
properties of a line vortex with its image in a circular body, the ring's first harmonic, and the
lift matrix's structure (a tail behind a source only)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

from stripcoef.assembly.sidewash import appendage_sidewash
from stripcoef.geometry.vehicle import load_vehicle, parse_vehicle
from stripcoef.hull.vortex import (ROLLED_UP_CENTROID, circulation_per_crossflow,
                                   induced_velocity, panel_sidewash, ring_sidewash,
                                   vortex_position)

GEOMETRY = Path(__file__).resolve().parents[1] / "geometry"


def test_image_keeps_the_body_impermeable():
    """Circle theorem: with the image at a^2/f the radial velocity on the body's circle is 0."""
    a = 0.3
    theta = np.linspace(0.0, 2.0 * math.pi, 37)
    rim = a * np.column_stack([np.cos(theta), np.sin(theta)])
    for vortex in ([0.0, 0.7], [0.5, -0.45]):
        v = np.asarray(vortex)
        e = np.array([v[1], -v[0]]) / np.linalg.norm(v)
        u = induced_velocity(rim, v, e, a)
        radial = np.einsum("ij,ij->i", u, rim / a)
        assert np.max(np.abs(radial)) < 1e-12 * np.max(np.abs(u))
        assert np.max(np.abs(u)) > 0.1


def test_free_vortex_speed_and_the_downwash_of_its_own_span():
    """Without a body: |u| = 1/(2 pi d), normal to the radius; between the root and the vortex
    the velocity is against the panel's lift (its own downwash), outboard of the vortex with
    it (upwash)."""
    v, e = np.array([0.0, 1.0]), np.array([1.0, 0.0])
    pts = np.array([[0.0, 0.5], [0.0, 1.5], [0.3, 2.0]])
    u = induced_velocity(pts, v, e, 0.0)
    d = pts - v
    dist = np.linalg.norm(d, axis=1)
    assert np.linalg.norm(u, axis=1) == pytest.approx(1.0 / (2 * math.pi * dist))
    assert np.einsum("ij,ij->i", u, d) == pytest.approx(0.0, abs=1e-15)
    assert u[0] @ e < 0.0 < u[1] @ e
    with_body = induced_velocity(pts[:1], v, e, 0.3)     # the image adds to the downwash
    assert with_body[0] @ e < u[0] @ e


def test_strength_and_position():
    """f = r + pi/4 b; Gamma/w = k / rho (f - a^2/f) (Kutta-Joukowski with the image)."""
    assert vortex_position(0.2, 0.4) == pytest.approx(0.2 + math.pi / 10.0)
    assert ROLLED_UP_CENTROID == pytest.approx(0.7853981634)
    assert circulation_per_crossflow(3.0, 0.5, 0.0, rho=1000.0) == pytest.approx(3.0 / 500.0)
    assert circulation_per_crossflow(3.0, 0.5, 0.3, rho=1000.0) == pytest.approx(
        3.0 / (1000.0 * (0.5 - 0.09 / 0.5)))
    with pytest.raises(ValueError, match="a < f"):
        circulation_per_crossflow(3.0, 0.5, 0.5, rho=1000.0)
    with pytest.raises(ValueError, match="outside the body"):
        induced_velocity([[1.0, 1.0]], [0.0, 0.2], [1.0, 0.0], 0.3)


def test_ring_answers_a_uniform_cross_flow_as_itself():
    """A vortex far away (no body) gives a nearly uniform cross-flow at the ring: its first
    harmonic is that velocity; the panel's strip mean likewise."""
    far = np.array([0.0, 1000.0])
    e = np.array([1.0, 0.0])
    uniform = induced_velocity([[0.0, 0.0]], far, e, 0.0)[0]
    assert ring_sidewash(far, e, 0.0, radius=0.4) == pytest.approx(uniform, rel=1e-5)
    h = panel_sidewash(far, e, 0.0, root=0.1, span=0.3, span_direction=[0.0, -1.0],
                       direction=e)
    assert h == pytest.approx(uniform @ e, rel=1e-3)


def _tandem(x_tail: float, z_tail: float = -0.15) -> dict:
    """A cylinder with a fin on top at x = 0.4 m and a tail fin at ``x_tail``, ``z_tail``."""
    return {"name": "tandem", "fluid": {"water": "fresh"}, "reference_speed": 2.0,
            "hull": {"name": "hull", "profile": [{"type": "cylinder", "x": [-1.0, 1.0],
                                                 "radius": 0.1}]},
            "appendages": [
                {"name": "front", "type": "fin", "span_axis": "z", "span": 0.1, "chord": 0.1,
                 "thickness": 0.01, "center": [0.4, 0.0, -0.15]},
                {"name": "back", "type": "fin", "span_axis": "z", "span": 0.1, "chord": 0.1,
                 "thickness": 0.01, "center": [x_tail, 0.0, z_tail]}]}


def test_only_a_surface_behind_another_is_changed_and_against_the_source():
    """Two fins in tandem: dL is the tail's force column times the source's incidence row,
    reducing the tail's sway lift (it sits in the source's downwash); side by side: none;
    REMUS (all fins at one station): none."""
    v = parse_vehicle(_tandem(-0.6), file="tandem")
    dl, info = appendage_sidewash(v, 1000.0, [0.0, 0.0, 0.0])
    assert [(p["source"], p["tail"]) for p in info["pairs"]] == [("front (top)", "back (top)")]
    assert info["pairs"][0]["sidewash"] < 0.0
    assert np.linalg.matrix_rank(dl, tol=1e-9 * np.abs(dl).max()) == 1
    assert dl[1, 1] < 0.0                 # less sway force (L[1, 1] > 0 is the fins' own)
    assert dl[5, 1] / dl[1, 1] == pytest.approx(-0.6 + 0.025, rel=1e-9)  # tail c/4
    same = parse_vehicle(_tandem(0.4, 0.15), file="tandem")
    assert not np.any(appendage_sidewash(same, 1000.0, [0.0, 0.0, 0.0])[0])
    remus = load_vehicle(GEOMETRY / "remus100.yaml")
    assert not np.any(appendage_sidewash(remus, 1025.0, [0.0, 0.0, 0.0])[0])


@pytest.mark.slow
def test_suboff_sail_vortex_on_the_upper_rudder():
    """Roddy's configuration 2 (validation.lift.sidewash_terms): the sail's vortex (f = 0.833 +
    pi/4 0.729 ft) lies above the upper rudder, which it washes against the sail's incidence,
    more than it washes the lower one with it; the bare hull and hull + planes have no pair."""
    from validation.lift import FT, sidewash_terms

    _, info = sidewash_terms(2, "datcom", True)
    by = {(p["source"], p["tail"]): p for p in info["pairs"]}
    upper, lower = by[("sail (top)", "rudder (top)")], by[("sail (top)", "rudder (bottom)")]
    assert upper["f"] / FT == pytest.approx(0.833333 + math.pi / 4 * 0.729, rel=1e-3)
    assert upper["sidewash"] < -abs(lower["sidewash"]) < 0.0 < lower["sidewash"]
    for config in (3, 5):
        dl, info = sidewash_terms(config, "datcom", False)
        assert not np.any(dl) and not info["pairs"]


def test_closed_forms_match_quadrature():
    """The panel's log mean and the ring's Laurent harmonic against brute-force quadrature
    (a vortex off the panel's line; inside and outside the ring)."""
    e = np.array([1.0, 0.0])
    v = np.array([0.05, 0.5])
    r = 0.15 + 0.3 * (np.arange(200000) + 0.5) / 200000
    u = induced_velocity(r[:, None] * np.array([0.0, 1.0])[None, :], v, e, 0.1)
    h = panel_sidewash(v, e, 0.1, root=0.15, span=0.3, span_direction=[0.0, 1.0], direction=e)
    assert h == pytest.approx(np.mean(u @ e), rel=1e-6)
    theta = 2 * math.pi * (np.arange(4096) + 0.5) / 4096
    rhat = np.column_stack([np.cos(theta), np.sin(theta)])
    for radius in (0.3, 0.8):
        ur = np.einsum("ij,ij->i", induced_velocity(radius * rhat, v, e, 0.1), rhat)
        quad = (2.0 / theta.size) * (ur[:, None] * rhat).sum(axis=0)
        assert ring_sidewash(v, e, 0.1, radius=radius) == pytest.approx(quad, rel=1e-6, abs=1e-9)


def test_body_pair_keeps_the_body_impulse():
    """The body's pair (assembly.sidewash._body_pair): two vortices at +-pi/4 a_0 in the plane
    normal to the cross-flow, of strength Gamma_0 = 2 k a_0 per unit cross-flow, so that their
    impulse Gamma_0 2 f is the plate's (and the circle's) k pi a_0^2."""
    from stripcoef.assembly.sidewash import _body_pair

    v = parse_vehicle(_tandem(-0.6), file="tandem")
    pair = _body_pair({"separation_x": -0.2, "munk_factor": 0.9}, v.hull, [0.0, 0.0, 0.0])
    a0 = 0.1
    assert [p["name"] for p in pair] == ["body (cross-flow y)", "body (cross-flow z)"]
    for p in pair:
        assert p["g"] * 2.0 * p["f"] == pytest.approx(0.9 * math.pi * a0 ** 2)
        for vortex in p["vortices"]:
            assert abs(vortex @ p["lift_dir"]) < 1e-15
            assert np.linalg.norm(vortex) == pytest.approx(math.pi / 4 * a0)
        assert p["incidence"][5 if p["lift_dir"][0] else 4] == pytest.approx(
            -0.2 if p["lift_dir"][0] else 0.2)
