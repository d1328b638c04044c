"""One entry point for every identification method: a log (and optionally a vehicle) in,
a :class:`FitResult` out.  The CLI (``stripcoef identify``) is a thin layer over it.
"""

from __future__ import annotations

import math

from stripcoef.conventions import DOF, parse_dof
from stripcoef.errors import InputError, unknown_name

METHODS = ("steady", "one-step", "pendulum", "torsion")


def identify_log(log, method: str, *, dof: str | None = None, model: str | None = None,
                 vehicle=None, direction: str = "both", settle: float = 8.0, trim: int = 0,
                 inertia: float | None = None, covariance: str | None = None,
                 mass: float | None = None, buoyancy: float | None = None,
                 length: float | None = None, stiffness: float | None = None,
                 medium: str = "water", window: int | None = None, order: int = 4,
                 refine: bool = False):
    """Identify coefficients from ``log`` (a :class:`stripcoef.logfile.Log`).

    The parameters not listed below are those of :func:`steady.steady_points`,
    :func:`onestep.one_step_log`, :func:`pendulum.pendulum` and :func:`pendulum.torsion`.

    Parameters
    ----------
    method : {"steady", "one-step", "pendulum", "torsion"}
    dof : str, optional
        Default heave (steady), yaw (one-step, torsion), "" (pendulum).
    model : str, optional
        steady: standard, eta, eta-md, LQB, LQNB, LB, LNB or ``compare``; one-step: LQB,
        LQNB, LB, LNB.
    vehicle : HydroModel, optional
        Thruster map (commands -> force), rigid-body inertia, mass and buoyancy [SI].

    Returns
    -------
    (FitResult, Comparison or None)
    """
    if method not in METHODS:
        raise unknown_name("identification method", method, METHODS, key="method")
    _check_settings(settle=settle, trim=trim, inertia=inertia, mass=mass, buoyancy=buoyancy,
                    length=length, stiffness=stiffness, window=window, order=order)
    from stripcoef.identify import onestep, pendulum, steady        # scipy.signal etc. only when used
    from stripcoef.identify.inputs import applied_force, horizontal_command
    if method in ("steady", "one-step"):
        name = DOF[parse_dof(dof if dof is not None else
                             ("heave" if method == "steady" else "yaw"))]
        i = DOF.index(name)
        force, origin = applied_force(log, name, vehicle)
        cmp = None
        if method == "steady":
            pts = steady.steady_points(log, name, force=force,
                                       n_h=horizontal_command(log, vehicle), settle=settle,
                                       trim=trim)
            if (model or "standard") == "compare":
                cmp = steady.compare_models(pts)
                fit = steady.recommended_fit(cmp)
            else:
                fit = steady.fit_steady(pts, model or "standard", direction=direction)
        else:
            if inertia is None and vehicle is not None:
                inertia = float(vehicle.rigid_body_mass[i, i])
            fit = onestep.one_step_log(log, name, model=model or "LQB", input=force,
                                       inertia=inertia, covariance=covariance)
        fit.notes.append(f"applied force from {origin}")
        return fit, cmp
    if model:
        raise InputError("a model applies to the steady and one-step methods only", key="model",
                         value=model, expected=f"no model with method {method}")
    kw = dict(window=window, order=order, refine=refine)
    if method == "pendulum":
        if mass is None and vehicle is not None:
            mass = vehicle.mass
        if medium == "air":
            buoyancy = 0.0
        elif buoyancy is None and vehicle is not None:
            buoyancy = vehicle.buoyancy
        if medium == "water" and mass is not None and buoyancy is None:
            raise InputError("buoyancy needed with the mass", key="buoyancy",
                             expected="the buoyancy B [N] or a vehicle")
        return pendulum.pendulum_log(log, mass=mass, buoyancy=buoyancy or 0.0, length=length,
                                     medium=medium, dof=dof or "", **kw), None
    name = DOF[parse_dof(dof if dof is not None else "yaw")]
    if inertia is None and vehicle is not None:
        inertia = float(vehicle.rigid_body_mass[DOF.index(name), DOF.index(name)])
    return pendulum.torsion_log(log, stiffness=stiffness, inertia=inertia, medium=medium,
                                dof=name, **kw), None


def _check_settings(**settings) -> None:
    """The numerical settings of :func:`identify_log`, each finite and in its range.

    settle [s] and buoyancy [N] >= 0; inertia [kg m^2], mass [kg], length [m] and stiffness
    [N m/rad] > 0; trim [samples] >= 0; window [samples] >= 3 and order >= 1, order < window
    (a Savitzky-Golay filter, scipy.signal.savgol_filter).
    """

    def bad(key, value, expected):
        raise InputError("invalid setting", key=key, value=value, expected=expected)

    for key in ("settle", "buoyancy", "inertia", "mass", "length", "stiffness"):
        v = settings[key]
        if v is None:
            continue
        if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
            bad(key, v, "a finite number")
        if key in ("settle", "buoyancy") and v < 0:
            bad(key, v, "a number >= 0")
        if key not in ("settle", "buoyancy") and v <= 0:
            bad(key, v, "a number > 0")
    if settings["trim"] < 0:
        bad("trim", settings["trim"], "a number of samples >= 0")
    window, order = settings["window"], settings["order"]
    if order < 1:
        bad("order", order, "a filter order >= 1")
    if window is not None and (window < 3 or window <= order):
        bad("window", window, f"a window of >= 3 samples, more than the order {order}")
