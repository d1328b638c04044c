r"""The pipeline function: a Vehicle in, a :class:`~stripcoef.model.HydroModel` out.

geometry (the vehicle cut into strips) -> sections (2D coefficients per strip) -> hull-level
terms -> :mod:`~stripcoef.assembly.mass`, :mod:`~stripcoef.assembly.added_mass`,
:mod:`~stripcoef.assembly.damping` -> one HydroModel about the reference point asked for.
"""

from __future__ import annotations

import warnings
from dataclasses import dataclass, replace
from pathlib import Path

import numpy as np

from stripcoef.errors import InputError, ModelWarning
from stripcoef.fluid import MAX_VEHICLE_SPEED, Fluid
from stripcoef.model import Conditions, HydroModel, rigid_body_mass_matrix
from stripcoef.physical import check_physical
from stripcoef.assembly.damping import damping_matrices
from stripcoef.assembly.lift import fin_munk_compensation, vehicle_lift
from stripcoef.assembly.mass import displaced_volume, mass_properties
from stripcoef.assembly.methods import AddedMassInputs, choose_method
from stripcoef.conventions import clean_roundoff
from stripcoef.geometry.vehicle import Vehicle, load_vehicle
from stripcoef.threads import small_matrices


def _cross_extent(strips) -> dict:
    """The body's largest extents along y and z [m]: over its parts, the rings of a part
    that carries them (a mesh section), else the part's centre +- its half sizes."""
    lo, hi = np.full(2, np.inf), np.full(2, -np.inf)
    for p in strips.parts:
        if p.contours is not None:
            pts = [np.asarray(r, float) for rings in p.contours for r in rings]
            if pts:
                pts = np.vstack(pts)
                lo, hi = np.minimum(lo, pts.min(axis=0)), np.maximum(hi, pts.max(axis=0))
            continue
        c = np.column_stack([p.y, p.z])
        half = np.column_stack([p.half_breadth, p.half_height])
        lo, hi = np.minimum(lo, (c - half).min(axis=0)), np.maximum(hi, (c + half).max(axis=0))
    if not np.all(np.isfinite(hi - lo)):
        return {}
    return {"breadth": float(hi[0] - lo[0]), "height": float(hi[1] - lo[1])}


def _reference_point(ref, cb, cg):
    if isinstance(ref, str):
        return {"center_of_buoyancy": cb, "center_of_gravity": cg,
                "origin": np.zeros(3)}[ref]
    return np.asarray(ref, dtype=float)


@dataclass(frozen=True)
class EstimateOptions:
    """The options of :func:`estimate` (every field optional; ``None`` = the vehicle file's
    value or the documented default).

    Attributes
    ----------
    strips : int, optional
        Number of strips (default: the vehicle file's, else 1000).
    corrections : bool, optional
        3D end corrections (default on; ``False`` = pure strip theory).
    speed : float, optional
        Reference speed for Reynolds numbers and the damping split [m/s].
    reference_point : str or (3,), optional
        center_of_buoyancy, center_of_gravity, origin, or a point [m] (default: file's).
    regime : str
        Friction line: ``auto``, ``laminar`` or ``turbulent``.
    fluid : Fluid, optional
        Override the vehicle file's fluid.
    correction_panels : int, optional
        Meridian panels of each axisymmetric solve of the 3D corrections (default
        :data:`stripcoef.hull.corrections.DEFAULT_PANELS` = 160; cost grows as its square,
        accuracy converges at second order, docs/performance.md "Speed"). Ignored
        without corrections.
    section_panels : int, optional
        Panels per 2D section of a mesh body (default adaptive: 96 for a round section, more
        for slender ones and sharp corners, :func:`stripcoef.sections.panel.discretise`); a
        round section is within 0.01 % of its exact value with 32 (docs/meshes.md).
    added_mass_method : str
        ``auto`` (default: the 3D panel method of :mod:`stripcoef.hull.panels` for a vehicle
        that is neither a body of revolution, a finned round hull nor slender,
        strip theory and its 3D corrections otherwise,
        :func:`stripcoef.assembly.methods.choose_method`), ``strips`` (always strip
        theory) or ``panels`` (always the panel method; mesh vehicles only).  Only M_A changes: the
        damping stays from the strips.
    added_mass_panels : int, optional
        Panels of the finer of the panel method's two resolutions (default
        :data:`stripcoef.hull.panels.DEFAULT_PANELS`).
    """

    strips: int | None = None
    corrections: bool | None = None
    speed: float | None = None
    reference_point: object = None
    regime: str = "auto"
    fluid: Fluid | None = None
    correction_panels: int | None = None
    section_panels: int | None = None
    added_mass_method: str = "auto"
    added_mass_panels: int | None = None


@small_matrices           # BLAS on one thread for the many small solves (stripcoef.threads)
def estimate(vehicle, options: EstimateOptions | None = None, **keywords) -> HydroModel:
    """Strip theory: a vehicle in, a HydroModel out.

    Parameters
    ----------
    vehicle : Vehicle, str, Path, MeshBody or trimesh.Trimesh
        A :class:`~stripcoef.geometry.vehicle.Vehicle`, a vehicle file (YAML) or a mesh file
        (read by :func:`~stripcoef.geometry.vehicle.load_vehicle`), or an in-memory mesh
        (:meth:`~stripcoef.geometry.vehicle.Vehicle.from_mesh`, default options).
    options : EstimateOptions, optional
        The options (see :class:`EstimateOptions` for each one).
    **keywords
        The same options by name (``strips=``, ``corrections=``, ``speed=``,
        ``reference_point=``, ``regime=``, ``fluid=``, ``correction_panels=``,
        ``section_panels=``, ``added_mass_method=``, ``added_mass_panels=``); with
        ``options`` too, they replace its fields.

    Returns
    -------
    HydroModel
        The model of :mod:`stripcoef.model` (Fossen 2011, eq. 7.190): M_A from
        :func:`added_mass`, D_L and D_Q from
        :func:`~stripcoef.assembly.damping.damping_matrices`, M_RB from
        :func:`mass_properties` (Fossen 2011, eqs. 3.44-3.45), the lift matrix and control
        surfaces from :func:`~stripcoef.assembly.lift.vehicle_lift` (Prestero 2001, secs.
        3.6-3.7), the lifting fins' Munk compensation (``fin_munk_lift``) from
        :func:`~stripcoef.assembly.lift.fin_munk_compensation` by the same added-mass
        method. See the module docstring.
    """
    if options is None:
        options = EstimateOptions(**keywords)
    elif not isinstance(options, EstimateOptions):
        raise TypeError(f"options must be EstimateOptions, not {type(options).__name__}")
    elif keywords:
        options = replace(options, **keywords)
    return _estimate(vehicle, options)


def _estimate(vehicle, options: EstimateOptions) -> HydroModel:
    """:func:`estimate` with its options resolved (see there)."""
    strips, corrections, speed = options.strips, options.corrections, options.speed
    reference_point, regime, fluid = options.reference_point, options.regime, options.fluid
    correction_panels, section_panels = options.correction_panels, options.section_panels
    if isinstance(vehicle, (str, Path)):
        vehicle = load_vehicle(vehicle)
    elif not isinstance(vehicle, Vehicle):
        vehicle = Vehicle.from_mesh(vehicle)
    if regime not in ("auto", "laminar", "turbulent"):
        raise InputError("unknown regime", key="regime", value=regime,
                         expected="auto, laminar or turbulent")
    fluid = fluid or vehicle.fluid
    rho, nu = fluid.density, fluid.kinematic_viscosity
    from_file = speed is None
    speed = float(speed if speed is not None else vehicle.reference_speed)
    if not np.isfinite(speed) or speed <= 0 or speed > MAX_VEHICLE_SPEED:
        raise InputError("invalid reference speed", file=vehicle.source if from_file else None,
                         key="reference_speed" if from_file else "speed", value=speed,
                         expected=f"a speed > 0 and <= {MAX_VEHICLE_SPEED:g} m/s (more is "
                                  "faster than any underwater vehicle)")
    corrections = vehicle.corrections if corrections is None else bool(corrections)
    st = vehicle.cut(strips)
    volume, cb = displaced_volume(st)
    mass, cg, inertia = mass_properties(st, vehicle, rho, volume, cb)
    ref = _reference_point(reference_point if reference_point is not None else vehicle.reference,
                           cb, cg)
    method = choose_method(options.added_mass_method, vehicle, st)
    inputs = AddedMassInputs(
        vehicle=vehicle, strips=st, rho=rho, about=ref, volume=volume, center=cb,
        corrections=corrections, correction_panels=correction_panels,
        section_panels=section_panels, added_mass_panels=options.added_mass_panels)
    m_a, am_info, m_a_error = method.compute(inputs)
    d_l, d_q, cond = damping_matrices(st, vehicle, rho, nu, speed, ref, regime)
    m_rb = rigid_body_mass_matrix(mass, cg - ref, inertia)
    lift, surfaces, lift_info = vehicle_lift(vehicle, rho, ref, center=cb, speed=speed,
                                             viscosity=nu)
    fin_munk, munk_info = fin_munk_compensation(   # the fins' Munk moment once (in their lift)
        m_a, lambda v: method.compute(replace(inputs, vehicle=v, strips=v.cut(strips)))[0],
        vehicle)
    if munk_info:
        lift_info["fin_munk"] = munk_info
    m_a, m_rb = clean_roundoff(m_a), clean_roundoff(m_rb)
    conditions = Conditions(**cond, **am_info, lift=lift_info or None, strips=st.n,
                            corrections=corrections, density=rho, kinematic_viscosity=nu,
                            fluid=fluid.source, length=st.length,
                            **_cross_extent(st))
    if abs(mass - rho * volume) > 0.05 * rho * volume:
        warnings.warn(f"{vehicle.name}: weight and buoyancy differ by "
                      f"{100 * (mass - rho * volume) / (rho * volume):+.1f} % "
                      f"(m = {mass:.3g} kg, rho V = {rho * volume:.3g} kg)", ModelWarning,
                      stacklevel=2)
    model = HydroModel(
        name=vehicle.name, reference_point=ref, rigid_body_mass=m_rb, added_mass=m_a,
        linear_damping=d_l, quadratic_damping=d_q, mass=mass, volume=volume,
        center_of_gravity=cg, center_of_buoyancy=cb, density=rho, kinematic_viscosity=nu,
        thrusters=vehicle.thrusters, conditions=conditions, lift=lift, fin_munk_lift=fin_munk,
        control_surfaces=surfaces, added_mass_error=m_a_error,
        provenance={"method": method.provenance, "source": vehicle.source,
                    "corrections": corrections, "strips": st.n},
    )
    check_physical(model, file=vehicle.source)   # no NaN or impossible model leaves here
                                                  # (a NaN matrix: a geometry the strips
                                                  # cannot resolve)
    return model
