r"""The registry of added-mass methods: name -> :class:`AddedMassMethod`.

:data:`ADDED_MASS_METHODS` holds the ways stripcoef gets M_A, most exact first:

- ``bem``: Capytaine's boundary-element method on the vehicle's mesh (the cross-check,
  optional extra ``stripcoef[bem]``; :mod:`stripcoef.bem`);
- ``panels``: the 3D panel method on the vehicle's mesh (:mod:`stripcoef.hull.panels`);
- ``strips``: strip theory with its 3D corrections
  (:func:`stripcoef.assembly.added_mass.added_mass`).

Each names what it applies to, computes M_A about a point from one :class:`AddedMassInputs`,
says how its error is estimated, and whether the ``added_mass_method`` option of
:class:`~stripcoef.assembly.estimate.EstimateOptions` may choose it (``in_estimate``; the BEM
is run after the estimate, ``coefficients --method bem`` and ``compare``). The ``auto`` rule
(:func:`choose_method`) and the CLI's ``--added-mass-method`` choices read this table.
"""

from __future__ import annotations

from dataclasses import dataclass, replace
from typing import Callable

import numpy as np

from stripcoef.assembly.added_mass import (SLENDER_RATIO, _mesh_of, added_mass,
                                           panel_vehicle_added_mass)
from stripcoef.assembly.fin_munk import NoFinSolve, recompute
from stripcoef.assembly.symmetry import ZERO_TOL as SYMMETRY_ZERO_TOL
from stripcoef.assembly.symmetry import (enforce_symmetry, enforce_symmetry_about,
                                         strip_sections, strips_mirror_symmetries)
from stripcoef.bem import timed_bem_added_mass
from stripcoef.errors import InputError, unknown_name
from stripcoef.geometry.shape_class import classify, strip_features
from stripcoef.strips import Strips

#: The option value that lets :func:`choose_method` pick the method.
AUTO = "auto"


@dataclass(frozen=True)
class AddedMassInputs:
    """What an added-mass method may read: the vehicle, its strips, the fluid density
    ``rho`` [kg/m^3], the point ``about`` [m], the displaced ``volume`` [m^3] and its
    ``center`` [m], and the options of the methods (``corrections``, ``correction_panels``,
    ``section_panels`` for strips; ``added_mass_panels`` for panels). The BEM reads only the
    vehicle, ``rho`` and ``about``."""

    vehicle: object
    strips: Strips | None
    rho: float
    about: np.ndarray
    volume: float | None = None
    center: np.ndarray | None = None
    corrections: bool = True
    correction_panels: int | None = None
    section_panels: int | None = None
    added_mass_panels: int | None = None


@dataclass(frozen=True)
class AddedMassMethod:
    """One added-mass method of the registry :data:`ADDED_MASS_METHODS`.

    Attributes
    ----------
    name : str
        The option's value (``added_mass_method``, ``--added-mass-method``)
    description : str
        The method and its source (docs, CLI help)
    applies_to : callable
        ``f(vehicle) -> (message, expected) or None``: None where the method applies, else
        the error's message and what it expects
    compute : callable
        ``f(AddedMassInputs) -> (M_A, info, error)``: (6, 6) M_A about ``about`` [kg, kg m,
        kg m^2], the entries it adds to the model's conditions, and the (6, 6) estimated
        error of each term (same units) or None
    error_estimate : str
        How its error is known
    provenance : str
        The model's ``provenance["method"]`` when the estimate uses it
    in_estimate : bool
        The ``added_mass_method`` option may choose it
    preferred : callable
        ``f(vehicle, strips) -> bool``: ``auto`` takes the first method in the table
        (``in_estimate``, applying) for which it holds
    """

    name: str
    description: str
    applies_to: Callable
    compute: Callable
    error_estimate: str
    provenance: str = ""
    in_estimate: bool = True
    preferred: Callable = lambda vehicle, strips: True


def _any_vehicle(vehicle):
    return None


def _one_mesh(label, expected):
    """``applies_to`` of a method on the vehicle's one closed mesh (``label`` names it)."""
    def applies_to(vehicle):
        if _mesh_of(vehicle) is None:
            return f"the {label} needs a vehicle made of one closed mesh", expected
        return None
    return applies_to


def _outside_strip_range(vehicle, strips: Strips) -> bool:
    r"""A vehicle, a mesh or a vehicle file alike, outside the range where strip theory's
    error is measured small, and not slender.  In range: the shape classes of
    :mod:`stripcoef.geometry.shape_class` read off every section of the strips (not one) --
    ``revolution`` (every section round: the strips and their axisymmetric 3D corrections are
    exact), or ``finned`` (a slender round hull over most of its length) with appendages no
    larger across x than those of the finned hulls that measured the class's error,
    span ratio :math:`S/D \le` :data:`FINNED_SPAN_MEASURED`.  Slender:
    :math:`L / \max(B, H) \ge` :data:`SLENDER_RATIO` (B, H the largest breadth and height of
    the strips [m]), strip theory's slender-body limit.  A round middle body with bulky
    appendages over most of its length (the ECA A9's collision mesh: 39 % round, ``bluff``)
    or a round hull with wings 3.2 hull diameters across (the WHOI hybrid glider's) is
    neither.  A vehicle file is panelled on its parts united into one closed surface
    (:func:`stripcoef.geometry.surface.vehicle_surface`)."""
    f = strip_features(strips)
    cls = classify(f)
    if cls == "revolution" or (cls == "finned" and f["span_ratio"] <= FINNED_SPAN_MEASURED):
        return False
    width = max(max(float(np.max(2 * p.half_breadth)), float(np.max(2 * p.half_height)))
                for p in strips.parts)
    return strips.length < SLENDER_RATIO * width


#: Largest span ratio S/D [-] (:mod:`stripcoef.geometry.shape_class`: the widest section,
#: fins included, over the round hull's diameter) of the finned hulls whose strip-theory error
#: measured the ``finned`` class's band (reference_tables/method_errors/method_errors.csv, the
#: six hulls of validation/finned.py CASES, chosen to span fin size before their errors were
#: known): the ``wide_tail`` hull, fins to a tip radius of 0.22 m on a 0.191 m hull, 2.304.
#: Within it the class's errors are a few percent (q95 1.3 % on translations, 2.9 % on
#: rotations: docs/validation.md, "Uncertainty bands"), below the panel method's (3.3 %,
#: 6.6 %); beyond it they are not measured, and ``auto`` does not extrapolate them (a panel
#: solve estimates its own error).  The ``bluff`` and ``open_frame`` classes' strip errors are
#: tens of percent (q95 28 to 490 %).
FINNED_SPAN_MEASURED = 2 * 0.22 / 0.191


def _strips(inp: AddedMassInputs):
    m_a, info = added_mass(inp.strips, inp.rho, about=inp.about, volume=inp.volume,
                           center=inp.center, corrections=inp.corrections,
                           correction_panels=inp.correction_panels,
                           section_panels=inp.section_panels)
    return m_a, info, None


def _panels(inp: AddedMassInputs):
    # the mirror planes of the body through the reference point: the couplings they
    # forbid are exactly zero (the panels of a symmetric body are not symmetric), and so is
    # their error (the convergence check looks at the terms that remain)
    # (on MIRROR_STRIPS strips of their own: with_added_mass_of passes none)
    strips = inp.strips
    if strips is None or strips.n > MIRROR_STRIPS:
        strips = inp.vehicle.cut(MIRROR_STRIPS)
    sections = strip_sections(strips)           # drawn once for both points
    mirrors = strips_mirror_symmetries(strips, inp.about, tol=SYMMETRY_ZERO_TOL,
                                       sections=sections)
    m_a, info, error = panel_vehicle_added_mass(
        inp.vehicle, inp.rho, inp.about, inp.added_mass_panels,
        symmetrise=lambda m: enforce_symmetry(m, mirrors), mirrors=mirrors)
    info["mirror_planes"] = "".join(sorted(mirrors)) or "none"
    # the body's own mirror planes, through its centre, where they miss the reference point
    # (the VideoRay: top-bottom symmetric, its centre of gravity 1 cm below the plane): the
    # couplings they forbid are zero about the centre, and X_wdot, Y_wdot, ... (the
    # translational block, the same about every point) exactly zero about any point; the
    # remeshed panels are not symmetric (X_wdot 0.4 % of the diagonal scale otherwise)
    centre = _symmetry_centre(strips, inp.center)
    if centre is not None:
        own = strips_mirror_symmetries(strips, centre, tol=SYMMETRY_ZERO_TOL,
                                       sections=sections)
        if own - mirrors:
            m_a = enforce_symmetry_about(m_a, own, centre, inp.about)
            if error is not None:
                error = np.where(m_a == 0.0, 0.0, error)
    return m_a, info, error


def _symmetry_centre(strips, center):
    """The point [m] a body's own mirror planes pass through, if it has any: the middle of its
    length (x) and its centre of buoyancy ``center`` (y, z; a reflection maps the displaced
    volume onto itself, so its centroid lies on every mirror plane); None without a centre."""
    if center is None:
        return None
    c = np.asarray(center, dtype=float).copy()
    c[0] = 0.5 * (float(strips.x_min) + float(strips.x_max))
    return c


#: Strips the panel method's mirror test cuts (:func:`stripcoef.assembly.symmetry.
#: strips_mirror_symmetries`) [-]: sections every L/200 sample the body finely enough for its
#: tolerance of 0.1 % of the volume, at a fifth of the shapely work of the estimate's 1000
#: strips (0.03-0.1 s instead of 0.15-0.5 s of CPU; the same planes on the twelve shapes of
#: benchmarks/cad_shapes.py seed 4000105165 checked).  A choice of cost, not of accuracy.
MIRROR_STRIPS = 200


def _bem(inp: AddedMassInputs):
    m_a, seconds = timed_bem_added_mass(_mesh_of(inp.vehicle), rho=inp.rho,
                                        reference_point=inp.about)
    return m_a, {"bem_faces": int(len(_mesh_of(inp.vehicle).mesh.faces)),
                 "bem_seconds": round(seconds, 3)}, None


#: The registry of added-mass methods, most exact first: name -> :class:`AddedMassMethod`.
ADDED_MASS_METHODS = {m.name: m for m in (
    AddedMassMethod(
        name="bem",
        description="Capytaine's boundary-element method on the mesh (unbounded fluid; "
                    "Ancellin & Dias 2019), the cross-check: coefficients --method bem, compare",
        applies_to=_one_mesh("BEM", "a mesh file (STL, OBJ, PLY, GLB, ...)"),
        compute=_bem,
        error_estimate="none per run; converges at second order against Lamb's exact values "
                       "on spheroid meshes (benchmarks/mesh_reference_convergence.py)",
        provenance="bem (Capytaine, free_surface=inf, direct) added mass; strip-theory damping",
        in_estimate=False),
    AddedMassMethod(
        name="panels",
        description="3D panel method on the closed surface (a mesh, or a vehicle file's parts "
                    "united; Newman 1977 eq. 4.148), levels refined "
                    "until converged, Richardson-extrapolated from the two finest",
        applies_to=_any_vehicle,
        compute=_panels,
        error_estimate="per term: Roache's grid convergence index of the panel levels "
                       "(stripcoef.hull.convergence), with a warning past its tolerance",
        provenance="strip theory, added mass by the 3D panel method",
        preferred=_outside_strip_range),
    AddedMassMethod(
        name="strips",
        description="strip theory: 2D sections per strip, 3D end corrections on equivalent "
                    "bodies of revolution",
        applies_to=_any_vehicle,
        compute=_strips,
        error_estimate="the method band of the vehicle's shape class (stripcoef.study.sources, "
                       "docs/validation.md)",
        provenance="strip theory"),
)}


def estimate_choices() -> tuple[str, ...]:
    """The values of the ``added_mass_method`` option: ``auto`` and the methods the estimate
    may use (``in_estimate``)."""
    return (AUTO,) + tuple(n for n, m in ADDED_MASS_METHODS.items() if m.in_estimate)


def get_method(name: str) -> AddedMassMethod:
    """The :class:`AddedMassMethod` of ``name``; an unknown name is an error listing the
    valid ones."""
    try:
        return ADDED_MASS_METHODS[name]
    except (KeyError, TypeError):
        raise unknown_name("added-mass method", name, ADDED_MASS_METHODS,
                           key="added_mass_method") from None


def choose_method(name, vehicle, strips: Strips) -> AddedMassMethod:
    r"""The method the estimate uses for the option ``added_mass_method`` = ``name``.

    ``auto``: the first method of :data:`ADDED_MASS_METHODS` that the estimate may use, that
    applies to ``vehicle`` and that it prefers: the 3D panel method for a vehicle (a mesh, or a
    vehicle file on its parts united into one closed surface) that is neither of the shape
    classes where strip theory's error is measured small (a body of revolution, a finned
    round hull within the measured fins' span) nor slender
    (:math:`L / \max(B, H) <` :data:`~stripcoef.assembly.added_mass.SLENDER_RATIO`), strip
    theory otherwise (:func:`_outside_strip_range`).  A method named outright must apply (the BEM needs a mesh file).
    """
    if name != AUTO:
        if name not in estimate_choices():
            raise InputError("unknown added-mass method", key="added_mass_method", value=name,
                             expected=" or ".join(estimate_choices()[1:] + (AUTO,)))
        method = ADDED_MASS_METHODS[name]
        need = method.applies_to(vehicle)
        if need is not None:
            raise InputError(need[0], file=getattr(vehicle, "source", None) or None,
                             key="added_mass_method", value=name, expected=need[1])
        return method
    for method in ADDED_MASS_METHODS.values():
        if (method.in_estimate and method.applies_to(vehicle) is None
                and method.preferred(vehicle, strips)):
            return method
    return ADDED_MASS_METHODS["strips"]


def with_added_mass_of(model, vehicle, name: str):
    """``model`` (a :class:`~stripcoef.model.HydroModel` of ``vehicle``) with its M_A from the
    method ``name`` about the same reference point (``coefficients --method bem``): damping
    and rigid-body terms kept, the provenance naming the method and what it reports (the
    BEM: faces and solver time [s]), the method's estimated error of each term (none for the
    BEM; the panels' grid convergence index, their mirror planes found on the vehicle's own
    strips), and the lifting fins' Munk compensation of the method's own fins' share
    (:func:`stripcoef.assembly.fin_munk.recompute`: one more solve of the vehicle without its
    lifting fins; kept, with a warning, where the method cannot solve it). A method that does
    not apply to ``vehicle`` is a one-line error."""
    method = get_method(name)
    need = method.applies_to(vehicle)
    if need is not None:
        raise InputError(need[0], file=getattr(vehicle, "source", None) or None,
                         key="method", value=name, expected=need[1])
    inputs = AddedMassInputs(vehicle=vehicle, strips=None, rho=model.density,
                             about=model.reference_point, volume=model.volume,
                             center=model.center_of_buoyancy)
    m_a, info, error = method.compute(inputs)
    provenance = {**model.provenance, "method": method.provenance, **info}
    model = replace(model, added_mass=m_a, provenance=provenance, added_mass_error=error)

    def without_fins(v):
        need = method.applies_to(v)
        if need is not None:
            raise NoFinSolve(need[0])
        return method.compute(replace(inputs, vehicle=v))[0]
    return recompute(model, vehicle, without_fins, method=name)


def added_mass_method(name, vehicle, strips: Strips) -> str:
    """The name of :func:`choose_method`'s method (``strips`` or ``panels``)."""
    return choose_method(name, vehicle, strips).name
