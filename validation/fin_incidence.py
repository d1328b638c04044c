r"""The published rules for a fin's incidence in drift and in yaw rotation, measured on SUBOFF
(issue 34).

Roddy's (1990) stern-plane increment (configuration 5 - 3) answers the yaw rate about twice as
much as its drift slope and the model's lever allow, and the sail's increment (4 - 3) about half
as much (:mod:`validation.rotary_trace`). Every rule in reach that gives a lifting surface
different incidences in drift and rotation changes only the incidence column :math:`a` of each
fin panel's lift matrix :math:`L_p = u\,a^T` (:func:`stripcoef.assembly.lift._panel_terms`: u the
force column k (F_W c_f + F_B c_b), a = [e; p x e] with p the rotation's incidence point), so each
is applied here as :math:`\Delta L = \sum_p u_p (a'_p - a_p)^T` on the unchanged models of
:func:`validation.lift.suboff_model` (exact for these linear terms; u_p = L_p a_p / |a_p|^2):

- ``three_quarter``: the model, the incidence of the rotation at the 3/4 chord (thin-airfoil
  theory; Weissinger's rule, :func:`stripcoef.hull.lift.rotary_incidence_point`);
- ``lattice``: at the station a planar vortex lattice of the panel's aspect ratio gives
  (:func:`validation.lift.rotary_point_lattice`; Katz & Plotkin 2001, sec. 12.1);
- ``trailing_edge``: at the trailing edge, slender-wing theory's limit (Jones 1946, NACA Report
  835: the force per length is U d(m w)/dx, m the section's apparent mass and w its cross-flow,
  so the whole wing's lift is U m w at its trailing edge, whatever w does ahead of it);
- ``sidewash``: the option of :mod:`stripcoef.assembly.sidewash` (Pitts, Nielsen & Kaattari
  1957, NACA Report 1307) with the body's separated pair: the tail loses the sidewash
  :math:`\varepsilon\,(v + x_0 r)` of the body's vortices, shed with the body lift's impulse at
  its separation station x_0 (and the appendages' vortices);
- ``static_downwash``: the aircraft tail's rule, the downwash factor on the static terms only
  (:math:`a' = [(1 - \varepsilon) e;\ p \times e]`: in the standard approximations a tail's
  M_q is its lift slope times its lever alone, while M_w goes through the static margin, whose
  neutral point holds the tail's :math:`1 - d\varepsilon/d\alpha`; read second-hand in
  Matthews 2002, *Aeronautical Engineer's Data Book*, p. 249) with the same
  :math:`\varepsilon` as ``sidewash``'s body pair. Its premise is a wing near the centre
  of rotation, whose lift and so whose downwash do not answer the rotation; the body lift here
  acts at x_0, near the stern, so on this body the rule contradicts the body's own model and is
  shown for its size only;
- ``mmg_planes`` and ``mmg_rudder``: the ship manoeuvring standard's rudder inflow (MMG:
  Yasukawa & Yoshimura 2015, J. Mar. Sci. Technol. 20, 37-52, sec. 2, the rudder force model:
  :math:`v_R = U \gamma_R \beta_R`, :math:`\beta_R = \beta - \ell'_R r'`, with
  :math:`\beta = -v/U`, :math:`r' = r L/U` and x from midship, so the rudder sees
  :math:`\gamma_R (v + \ell'_R L r)`: :math:`a' = \gamma_R [e;\ p_R \times e]`, p_R at
  :math:`\ell'_R L_{BP}` from midship) on all four stern appendages (the horizontal planes by
  the body's symmetry, in pitch) or on the two rudders only, with the KVLCC2 constants that
  paper tabulates (:data:`MMG_GAMMA_R`, :data:`MMG_L_R`). These are captive-test values of a
  single-screw tanker hull behind its propeller (C_b 0.81, B/L 0.18), far outside any range for
  a body of revolution (SUBOFF's B/L 0.116, no propeller): a what-if measurement of the form,
  never the model.

Nothing is fitted to Roddy's data. ``python -m benchmarks.rotary_trace --candidates``.
"""

from __future__ import annotations

import dataclasses
import functools

import numpy as np

from validation.lift import (FT, SUBOFF_COMPARED, _drift_rows, _issue_ok, _moment_point,
                             _roddy_derivatives, parse_vehicle_quiet, rotary_point_lattice,
                             sidewash_model, sidewash_terms, suboff_comparisons, suboff_model,
                             suboff_vehicle_data, val)
from validation.rotary_trace import TERMS, measured_increment

#: The incidence rules compared, in order (module docstring).
CANDIDATES = ("three_quarter", "lattice", "trailing_edge", "sidewash", "static_downwash",
              "mmg_planes", "mmg_rudder")
#: The MMG flow-straightening coefficient gamma_R [-]: the mean of the two KVLCC2 values of
#: Yasukawa & Yoshimura (2015), J. Mar. Sci. Technol. 20, 37-52, their table of the KVLCC2
#: model's rudder interaction coefficients (0.395 for beta_R < 0, 0.640 for beta_R > 0: the
#: propeller's swirl makes them differ; a linear derivative at beta_R = 0 takes their mean).
#: The values were read second-hand, from the KVLCC2 L7 model's parameters of the ShipMMG.jl
#: package (GitHub ShipMMG/ShipMMG.jl, src/data.jl; with x'_R = -0.500, so l'_R / x'_R = 1.42),
#: not from the paper's page; Kijima et al.'s (1990) regression of gamma_R on C_b B/L was not
#: found in a readable form and is not used. A ship's value with its propeller, outside its range on a body of revolution (module
#: docstring); a what-if constant, not the model's.
MMG_GAMMA_R = 0.5 * (0.395 + 0.640)
#: The MMG effective longitudinal coordinate of the rudder position l'_R [-, from midship, x
#: forward, over L_pp]: the KVLCC2 value -0.710 of the same table (Yasukawa & Yoshimura 2015).
MMG_L_R = -0.710
#: The body-lift rules they are measured under (the default's and the closest option).
RULES = ("datcom", "stratford_panel")
#: Drift angles of Appendix B's checks [deg] (validation.lift.drift_curve_comparisons).
ANGLES = (4.0, 8.0, 12.0, 16.0, 18.0)
#: Drift-curve configurations (the issue's 2-5; 2 with ring wing No. 1).
DRIFT_CONFIGS = (2, 3, 4, 5)


def _panels(built: int, method: str):
    """(vehicle, [(record name, panel, force column u (6,), incidence column a (6,), lift axis e
    (3,), quarter-chord point from the moment point (3,) [m])]) of a built SUBOFF
    configuration's lifting fin panels, in the order and with the record names of
    :func:`stripcoef.assembly.sidewash._panels` and ``_panel_record``."""
    from stripcoef.assembly.lift import _body_lift, _panel_terms, _round, _stern_flow
    from stripcoef.assembly.sidewash import _panel_record, _panels as sidewash_panels
    from stripcoef.hull.lift import lift_column, rotary_incidence_point

    vehicle = parse_vehicle_quiet(suboff_vehicle_data(built, method))
    rho = float(vehicle.fluid.density)
    point = _moment_point()
    hull = vehicle.hull
    body = _body_lift(vehicle, rho, point, point)
    slender = _stern_flow(vehicle, body, None, None)
    out = []
    for name, p in sidewash_panels(vehicle):
        m, _, _ = _panel_terms(p, point, rho, _round(hull), slender)
        e = np.zeros(3)
        e["xyz".index(p.normal)] = 1.0
        x_q = np.asarray(p.center, float) + np.array([0.25 * p.chord, 0.0, 0.0]) - point
        a = lift_column(e, rotary_incidence_point(x_q, p.chord))
        u = m @ a / float(a @ a)
        rec = _panel_record(name, p, hull, point, rho, _round(hull), slender)
        out.append((rec["name"], p, u, a, e, x_q))
    return vehicle, out


def _epsilon(built: int, method: str, ring: bool) -> dict:
    """{tail panel name: epsilon}: the mean sidewash of the body's separated pair at each tail
    panel per unit cross-flow at the separation station, sign turned (positive: against the
    cross-flow) (:func:`stripcoef.assembly.sidewash.appendage_sidewash`'s pairs)."""
    _, info = sidewash_terms(built, method, ring, True)
    out: dict = {}
    for p in info["pairs"]:
        if p["source"].startswith("body"):
            out[p["tail"]] = out.get(p["tail"], 0.0) - p["sidewash"]
    return out


@functools.lru_cache(maxsize=None)
def candidate_lift(built: int, method: str, candidate: str, ring: bool = False) -> np.ndarray:
    r""":math:`\Delta L` [kg/m, kg, kg m] of incidence rule ``candidate`` on a built SUBOFF
    configuration's fins against the model's 3/4-chord rule (module docstring); ``sidewash``'s
    is the option's own dL (:func:`validation.lift.sidewash_terms`)."""
    from stripcoef.hull.lift import effective_aspect_ratio, lift_column

    if candidate not in CANDIDATES:
        raise ValueError(f"incidence candidate {candidate!r}: expected one of "
                         f"{', '.join(CANDIDATES)}")
    if candidate == "sidewash":
        return np.asarray(sidewash_terms(built, method, ring, True)[0])
    _, panels = _panels(built, method)
    eps = _epsilon(built, method, ring) if candidate == "static_downwash" else {}
    out = np.zeros((6, 6))
    for name, p, u, a, e, x_q in panels:
        if candidate == "three_quarter":
            new = a
        elif candidate == "static_downwash":
            new = a.copy()
            new[:3] *= 1.0 - eps.get(name, 0.0)
        elif candidate.startswith("mmg"):
            if not name.startswith("rudder" if candidate == "mmg_rudder" else ("rudder",
                                                                                 "sternplane")):
                continue
            new = MMG_GAMMA_R * lift_column(e, np.array([mmg_station(), x_q[1], x_q[2]]))
        else:
            aft = (rotary_point_lattice(float(effective_aspect_ratio(p.span, p.area)))
                   if candidate == "lattice" else 0.75)      # chords aft of the 1/4 chord
            new = lift_column(e, x_q - np.array([aft * p.chord, 0.0, 0.0]))
        out += np.outer(u, new - a)
    return out


def mmg_station() -> float:
    r"""The MMG rudder's effective station :math:`x_R = \ell'_R L_{BP} + x_{mid}` from Roddy's
    moment point [m, x forward]: :data:`MMG_L_R` from midship (half L_BP aft of the nose,
    Yasukawa & Yoshimura 2015's origin), the moment point 6.6042 ft aft of the nose."""
    return FT * (MMG_L_R * val("t1.L_BP") + val("moment_point.x") - 0.5 * val("t1.L_BP"))


def candidate_model(built: int, method: str, candidate: str, ring: bool = False):
    """:func:`validation.lift.suboff_model` with ``candidate``'s dL added to its lift (the
    ``sidewash`` candidate: :func:`validation.lift.sidewash_model` with the body pair)."""
    if candidate == "sidewash":
        return sidewash_model(built, method, ring, True)
    model = suboff_model(built, method, ring)
    return dataclasses.replace(model, lift=model.lift + candidate_lift(built, method, candidate,
                                                                       ring))


def component_rows(method: str) -> list[dict]:
    """Each candidate's stern planes (configuration 5 less 3) and sail (4 less 3) against
    Roddy's increments: rows {'component', 'candidate', 'Yv', 'Nv', 'Yr', 'Nr' (ratios to the
    measured increment), 'lever' Y'_r/Y'_v [L_BP, x forward], 'measured_lever'}."""
    out = []
    for comp, (built, base) in {"stern planes": (5, 3), "sail": (4, 3)}.items():
        inc = measured_increment(built, base)
        bare = _roddy_derivatives(suboff_model(base, method))
        for cand in CANDIDATES:
            d = _roddy_derivatives(candidate_model(built, method, cand))
            delta = {k: d[k] - bare[k] for k in TERMS}
            out.append({"component": comp, "candidate": cand, "method": method,
                        **{k: delta[k] / inc[k] for k in TERMS},
                        "lever": delta["Yr"] / delta["Yv"],
                        "measured_lever": inc["Yr"] / inc["Yv"]})
    return out


def checks(method: str, candidate: str) -> dict:
    """The issue's counts with ``candidate``: {'table4': (met, counted) of the Table 4 checks of
    :func:`validation.lift.issue_checks` (the control terms as the model's: no candidate
    changes a deflection column), 'drift': (inside 20 %, total) of Appendix B's drift points of
    configurations 2-5 (:func:`validation.lift.drift_curve_comparisons`), 'band': the lift
    terms' sd(ln(model/measured)) as :func:`validation.lift.lift_band` takes it}."""
    from stripcoef.study.calibration import Z95, quantile95

    met = counted = 0
    cache: dict = {}
    band = []
    for c in suboff_comparisons():
        if c["kind"] == "control":
            value = c[method]
        else:
            key = (c["built"], c["ring"])
            if key not in cache:
                cache[key] = _roddy_derivatives(candidate_model(*key[:1], method, candidate,
                                                                key[1]))
            value = cache[key][c["name"]]
            ratio = value / c["measured"]
            if ratio > 0 and abs(c["measured"]) >= 0.05 * 0.01:   # as validation.lift.lift_band
                band.append(abs(np.log(ratio)))
        if c["ok"] is None:
            continue
        counted += 1
        met += bool(_issue_ok(c["config"], c["name"], value / c["measured"], c["tolerance"]))
    inside = total = 0
    for config in DRIFT_CONFIGS:
        built, ring = SUBOFF_COMPARED[config]
        for r in _drift_rows(candidate_model(built, method, candidate, ring), config, ANGLES):
            total += 1
            inside += abs(r["model"] / r["measured"] - 1) <= 0.20
    return {"table4": (met, counted), "drift": (int(inside), total),
            "band": float(quantile95(np.array(band)) / Z95)}


def term_ratio(method: str, candidate: str, config: int, name: str) -> float:
    """Model / measured of one Table 4 term of ``config`` with ``candidate`` [-]."""
    from validation import reference as ref
    from validation.lift import SUBOFF

    built, ring = SUBOFF_COMPARED[config]
    value = _roddy_derivatives(candidate_model(built, method, candidate, ring))[name]
    return float(value / ref.reference_value(SUBOFF, f"c{config}.{name}")["value"])


def chord_over_length(built: int = 5, prefix: str = "rudder") -> float:
    """A fin panel's chord over L_BP (the shift of a rule's incidence point in lever units)."""
    _, panels = _panels(built, "datcom")
    for name, p, *_ in panels:
        if name.startswith(prefix):
            return float(p.chord / (FT * val("t1.L_BP")))
    raise ValueError(f"no panel named {prefix}* on SUBOFF configuration {built}")


def epsilon_at(built: int, method: str, prefix: str = "rudder") -> float:
    """The body pair's mean sidewash at the panels named ``prefix``* of a built configuration,
    per unit cross-flow at the separation station, sign turned (:func:`_epsilon`) [-]."""
    eps = [v for k, v in _epsilon(built, method, False).items() if k.startswith(prefix)]
    return float(np.mean(eps)) if eps else 0.0


def sail_diagnosis(method: str = "stratford_panel") -> dict:
    r"""What Roddy's sail increment (4 - 3) says if it is two lifting elements (a diagnosis read
    from the measured data, used by no model): the sail, acting at the model's force station
    x_s (its quarter chord with the carry-over) with an unknown incidence station x_i and
    strength K_s, and a change K_b of the hull's own lift at the measured body's lever x_b
    (bare hull: (Y'_r less the model's Munk part) / Y'_v; its force and incidence station, a
    lifting element at its own station). Y'_v, N'_v give K_s and K_b, Y'_r gives x_i, and N'_r
    is left to check: {'x_s', 'x_b', 'x_i', 'x_i_model' (3/4 chord), 'x_te' (the trailing edge),
    'k_s', 'k_b' the two strengths [-], 'strength_ratio' K_s over the model's sail lift, 'body_ratio' K_b over the bare hull's
    measured |Y'_v|, 'Nr_ratio' the two elements' N'_r over the measured increment's} [L_BP, x
    forward; -]."""
    from validation.rotary_trace import component, measured, yaw_rate_split

    split = yaw_rate_split(4, method)
    fin = next(f for f in split["fins"] if f["name"].startswith("sail"))
    x_s, x_i_model = fin["force_station"], fin["incidence_station"]
    bare = measured(3)
    x_b = (bare["Yr"] - yaw_rate_split(3, method)["munk"]["Yr"]) / bare["Yv"]
    inc = measured_increment(4, 3)
    # -Y'_v = K_s + K_b, -N'_v = K_s x_s + K_b x_b
    k_s, k_b = np.linalg.solve([[1.0, 1.0], [x_s, x_b]], [-inc["Yv"], -inc["Nv"]])
    x_i = (-inc["Yr"] - k_b * x_b) / k_s
    nr = -(k_s * x_s * x_i + k_b * x_b ** 2)
    return {"x_s": x_s, "x_b": x_b, "x_i": float(x_i), "x_i_model": x_i_model,
            "k_s": float(k_s), "k_b": float(k_b),
            "x_te": x_s - 0.75 * 2.0 * (x_s - x_i_model),
            "strength_ratio": float(k_s / -component(split, "sail")["Yv"]),
            "body_ratio": float(k_b / -bare["Yv"]), "Nr_ratio": float(nr / inc["Nr"])}


#: What each candidate is called in the document.
LABEL = {"three_quarter": "3/4 chord (the model)", "lattice": "vortex lattice",
         "trailing_edge": "trailing edge (slender wing)",
         "sidewash": "sidewash option with the body pair",
         "static_downwash": "downwash on the static terms only",
         "mmg_planes": "MMG gamma_R (v + l_R r), four stern planes (what-if)",
         "mmg_rudder": "MMG gamma_R (v + l_R r), rudders only (what-if)"}


def section() -> str:
    """The section of docs/validation.md (validation.SECTIONS, after the rotary trace)."""
    from validation import markdown_table

    comp = {m: component_rows(m) for m in RULES}
    rows = []
    for m in RULES:
        for r in comp[m]:
            rows.append((m, r["component"], LABEL[r["candidate"]],
                         *(f"{r[k]:.2f}" for k in TERMS), f"{r['lever']:+.3f}"))
    meas = {r["component"]: r["measured_lever"] for r in comp[RULES[0]]}
    count = {(m, c): checks(m, c) for m in RULES for c in CANDIDATES}
    crows = [(m, LABEL[c], f"{count[(m, c)]['table4'][0]}/{count[(m, c)]['table4'][1]}",
              f"{count[(m, c)]['drift'][0]}/{count[(m, c)]['drift'][1]}",
              f"{count[(m, c)]['band']:.3f}")
             for m in RULES for c in CANDIDATES]
    by = {(r["method"], r["component"], r["candidate"]): r for m in RULES for r in comp[m]}
    eps = {m: epsilon_at(5, m) for m in RULES}
    chord = chord_over_length()
    ref_length = FT * val("t1.L_BP")
    lattice_aft = rotary_point_lattice(1.5)
    base = {m: count[(m, "three_quarter")] for m in RULES}
    sd = sail_diagnosis()
    return "\n".join([
        "## SUBOFF: published rules for a fin's incidence in drift and in rotation (issue 34)",
        "",
        "Roddy's stern-plane increment (configuration 5 - 3) answers the yaw rate about twice "
        "as much as a lifting element with its drift slope would, and the sail's (4 - 3) about "
        "half as much (the section above). The rules in reach that give a lifting surface "
        "different incidences in drift and in rotation change only each fin panel's incidence "
        "column a of its lift u a^T; `validation.fin_incidence` applies each to the unchanged "
        "models (dL = sum u (a' - a)^T, exact for the linear terms): the model's 3/4 chord "
        "(thin-airfoil theory, Weissinger's rule); the station a planar vortex lattice of the "
        "panel's aspect ratio gives (Katz & Plotkin 2001, sec. 12.1; "
        f"{lattice_aft:.2f} chords aft of the quarter chord at A = 1.5); the trailing edge, "
        "slender-wing theory's limit (Jones 1946, NACA Report 835: the force per length is "
        "U d(m w)/dx, so a slender wing's whole lift is U m w at its trailing edge); the "
        "sidewash option "
        "(`stripcoef.assembly.sidewash`, Pitts, Nielsen & Kaattari 1957) with the body's "
        "separated pair, whose strength is the body lift's impulse at its separation station "
        "x_0 and so answers v + x_0 r; and the aircraft tail's rule, the downwash factor on the "
        "static terms only (in the standard approximations a tail's M_q is its lift slope times "
        "its lever alone, while M_w goes through the static margin, whose neutral point holds "
        "the tail's 1 - d epsilon/d alpha; read second-hand in Matthews 2002, Aeronautical "
        "Engineer's Data Book, p. 249), with the body pair's epsilon at the "
        f"rudders ({eps['datcom']:.3f} under `datcom`, {eps['stratford_panel']:.3f} under "
        "`stratford_panel`, whose station is further aft and whose vortices lie inside the "
        "planes' roots). That rule assumes a wing near the centre of rotation, whose lift does "
        "not answer the rotation; here the source is the body lift at x_0 near the stern, which "
        "does, so on this body the rule contradicts the model's own body lift and is shown for "
        f"its size only. One chord of the rudders is {chord:.4f} L_BP. Each increment, model / "
        "measured, and its lever Y'_r / Y'_v [L_BP, x forward] "
        f"(measured: stern planes {meas['stern planes']:+.3f}, sail {meas['sail']:+.3f}); "
        "the model's increments hold the fins' lift, added mass and Munk compensation "
        "(`python -m benchmarks.rotary_trace --candidates`):", "",
        markdown_table(["rule", "increment", "incidence", "Y'_v", "N'_v", "Y'_r", "N'_r",
                        "lever"], rows), "",
        "The issue's checks with each (Table 4: the counts of `benchmarks.lift_band`; "
        "Appendix B: drift points of configurations 2-5 within 20 %; the lift band as "
        "`benchmarks.lift_band` measures it):", "",
        markdown_table(["rule", "incidence", "Table 4 checks", "drift points",
                        "lift band sd(ln)"], crows), "",
        "None reaches the measured increments. The lifting-surface rules move the incidence "
        "point by a fraction of a chord: the stern planes' lever from "
        f"{by[('stratford_panel', 'stern planes', 'three_quarter')]['lever']:+.3f} to "
        f"{by[('stratford_panel', 'stern planes', 'trailing_edge')]['lever']:+.3f} at most "
        f"(measured {meas['stern planes']:+.3f}, half a hull length behind the planes), the "
        f"sail's from {by[('stratford_panel', 'sail', 'three_quarter')]['lever']:+.3f} to "
        f"{by[('stratford_panel', 'sail', 'trailing_edge')]['lever']:+.3f} "
        f"(measured {meas['sail']:+.3f}: its Y'_r "
        f"{by[('stratford_panel', 'sail', 'trailing_edge')]['Yr']:.2f} times the increment at "
        "best), and no Table 4 check or drift point changes; under `stratford_panel` they "
        "narrow the lift band (configuration 2's Y'_r, which sets it, "
        + ", ".join(f"{term_ratio('stratford_panel', c, 2, 'Yr'):.2f}"
                    for c in ("three_quarter", "lattice", "trailing_edge"))
        + " of the measured with the 3/4 chord, the lattice and the trailing edge: the sail's "
        "negative Y'_r shrinks), but no check is met that was not. The body pair takes "
        f"{eps['datcom']:.2f} of the rudders' cross-flow under `datcom` but from both terms, "
        "since its impulse answers the cross-flow at x_0: the planes' Y'_v falls to "
        f"{by[('datcom', 'stern planes', 'sidewash')]['Yv']:.2f} and their Y'_r to "
        f"{by[('datcom', 'stern planes', 'sidewash')]['Yr']:.2f} of the increment. Only the "
        "downwash on the static terms alone moves the planes towards the measured "
        f"(under `datcom` Y'_v {by[('datcom', 'stern planes', 'static_downwash')]['Yv']:.2f}, "
        f"Y'_r {by[('datcom', 'stern planes', 'static_downwash')]['Yr']:.2f}, lever "
        f"{by[('datcom', 'stern planes', 'static_downwash')]['lever']:+.3f}; drift points "
        f"{base['datcom']['drift'][0]} -> {count[('datcom', 'static_downwash')]['drift'][0]}, "
        "Table 4 unchanged), and it is the rule whose premise fails on this body; under "
        "`stratford_panel` it changes nothing. Not in reach in a readable form: the "
        "submarine methods with flow-straightening factors for the appendages (Renilson 2018, "
        "Submarine Hydrodynamics, 2nd ed., defines gamma_B, gamma_R, gamma_S for bow planes, "
        "rudder and stern planes; Jones et al. 2002, DSTO-TR-1329; Feldman 1979, "
        "DTNSRDC/SPD-0393-09; Peterson 1980; only their titles, abstracts or nomenclature were "
        "found). The ship standard (MMG: Yasukawa & Yoshimura 2015, J. Mar. Sci. Technol. 20, "
        "37-52) writes a rudder's lateral inflow as gamma_R (v + l_R r), a flow-straightening "
        "coefficient and an effective lever longer than the rudder's own, the form of Roddy's "
        "stern planes, but its constants are captive-test values of single ships or regressions "
        "on a ship's block coefficient, beam and draught behind a propeller, defined for no body "
        "of revolution (SUBOFF's B/L is 0.116, with no propeller). Measured as a what-if only, "
        f"with that paper's KVLCC2 constants (gamma_R {MMG_GAMMA_R:.4f}, the mean of its 0.395 "
        f"and 0.640; l'_R {MMG_L_R:+.3f} from midship, {mmg_station() / ref_length:+.3f} L_BP "
        "from the moment point) on the four stern appendages or on the rudders alone (the same "
        "yaw-plane rows): the planes' Y'_v falls to "
        f"{by[('datcom', 'stern planes', 'mmg_planes')]['Yv']:.2f} of the increment under "
        f"`datcom` ({by[('stratford_panel', 'stern planes', 'mmg_planes')]['Yv']:.2f} under "
        f"`stratford_panel`), their Y'_r to "
        f"{by[('datcom', 'stern planes', 'mmg_planes')]['Yr']:.2f} "
        f"({by[('stratford_panel', 'stern planes', 'mmg_planes')]['Yr']:.2f}), the lever "
        f"moves to {by[('stratford_panel', 'stern planes', 'mmg_planes')]['lever']:+.3f}, "
        "and the drift points go "
        f"{base['datcom']['drift'][0]} -> {count[('datcom', 'mmg_planes')]['drift'][0]} "
        f"(`datcom`), {base['stratford_panel']['drift'][0]} -> "
        f"{count[('stratford_panel', 'mmg_planes')]['drift'][0]} (`stratford_panel`): the "
        "ship's constants reach neither the measured lever nor the measured size, and are not "
        "used. So the model is not changed and the default keeps the 3/4 "
        "chord; the stern planes' yaw-rate force stays "
        f"{by[('stratford_panel', 'stern planes', 'three_quarter')]['Yr']:.2f} of Roddy's "
        f"increment under `stratford_panel` ("
        f"{by[('datcom', 'stern planes', 'three_quarter')]['Yr']:.2f} under `datcom`) and the "
        f"sail's {by[('stratford_panel', 'sail', 'three_quarter')]['Yr']:.2f} times it: a "
        "yaw-rate force beyond its drift force's (planes) and short of it (sail), which no "
        "lifting element answering its local cross-flow gives.", "",
        "What the sail's increment says if it is two lifting elements (a diagnosis read from "
        "the measured data, used by no model; `validation.fin_incidence.sail_diagnosis`): the "
        f"sail acting at the model's force station ({sd['x_s']:+.3f}) and a change of the "
        "hull's own lift at the measured bare hull's lever "
        f"({sd['x_b']:+.3f}, its force and incidence station). Y'_v and N'_v give the sail "
        f"{sd['strength_ratio']:.2f} of the model's sail lift and the hull's lift raised by "
        f"{sd['body_ratio']:.2f} of the bare hull's |Y'_v|; Y'_r then puts the sail's "
        f"incidence at {sd['x_i']:+.3f} (the model's 3/4 chord {sd['x_i_model']:+.3f}, its "
        f"trailing edge {sd['x_te']:+.3f}), and the two elements' N'_r is "
        f"{sd['Nr_ratio']:.2f} of the measured. Read so, the sail answers the yaw rate near "
        "its trailing edge, as slender-wing theory has it, and what the model lacks is a "
        "larger lift of the afterbody behind the sail (its separation moved by the sail's "
        "wake, a candidate) and a weaker sail; the stations are the model's and the split "
        "is not unique, so nothing is changed.", ""])
