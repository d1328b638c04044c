"""Figures of a fit: data vs model, residuals vs time (or point) and vs velocity, each axis
with its quantity and unit.

:func:`fit_figure` builds and returns a :class:`matplotlib.figure.Figure` (no pyplot, no
backend switching, :mod:`stripcoef.figures`); :func:`plot_fit` writes it (PNG/PDF/SVG,
atomically: a failed plot leaves any earlier file untouched). matplotlib is optional
(``pip install stripcoef[plot]``).
"""

from __future__ import annotations

import numpy as np

from stripcoef.conventions import DOF, FORCES, VELOCITIES
from stripcoef.figures import check_plot_path, new_figure, save_figure
from stripcoef.identify.estimators import FitResult


def quantities(fit: FitResult) -> dict:
    """Axis labels of a fit (quantity [unit]): ``signal``, ``velocity``, ``force``,
    ``residual``. Steady fits: velocity and force of the DOF, residuals in force units
    (Indiveri 1998, eq. 4.12); one-step fits: the DOF's velocity, residual of the one-step
    prediction in velocity units (Wang & Clark 2006, eq. 9); pendulum and torsion: the angle,
    its rate, and residuals of the angular acceleration (the regression of Eng et al. 2009,
    eq. 4) or of the angle (output error)."""
    i = DOF.index(fit.dof) if fit.dof in DOF else None
    lin = i is not None and i < 3
    vel = f"{VELOCITIES[i]} [{'m/s' if lin else 'rad/s'}]" if i is not None else None
    force = f"{FORCES[i]} [{'N' if lin else 'N m'}]" if i is not None else None
    if fit.method.startswith("steady"):
        return {"velocity": f"steady velocity {vel}", "force": f"applied force {force}",
                "residual": f"force residual [{'N' if lin else 'N m'}]"}
    if fit.method.startswith(("pendulum", "torsion")):
        what = "pendulum angle θ" if fit.method.startswith("pendulum") else "torsion angle ψ"
        output = "output-error" in fit.method
        return {"signal": f"{what} [rad]", "velocity": "angular rate [rad/s]",
                "residual": "angle residual [rad]" if output
                else "angular acceleration residual [rad/s^2]"}
    if i is not None:
        return {"signal": f"{fit.dof} velocity {vel}", "velocity": f"{fit.dof} velocity {vel}",
                "residual": f"one-step residual of {VELOCITIES[i]} "
                            f"[{'m/s' if lin else 'rad/s'}]"}
    return {"signal": "measured signal y", "velocity": "velocity", "residual": "residual"}


def fit_figure(fit: FitResult, *, title: str | None = None, key: str = "plot"):
    """Three panels: data vs fit, residuals vs time (or point), residuals vs velocity."""
    q = quantities(fit)
    d = fit.data
    fig = new_figure(figsize=(15, 4.4), key=key)
    ax = fig.subplots(1, 3)
    res = np.asarray(fit.residuals)
    if fit.method.startswith("steady"):
        w, f = d["velocity"], d["force"]
        ax[0].plot(w, f, "o", label="measured")
        order = np.argsort(w)
        ax[0].plot(w[order], d["predicted"][order], "-", label=f"{fit.model} model")
        ax[0].set_xlabel(q["velocity"])
        ax[0].set_ylabel(q["force"])
        xr = np.arange(res.size)
        ax[1].set_xlabel("steady point [index]")
        vel = w
    elif "t" in d:
        t = d["t"]
        ax[0].plot(t, d["y"], ".", ms=2, label="measured")
        ax[0].plot(t, d["simulated"], "-", label="re-simulated")
        if "one_step" in d:
            ax[0].plot(t[1:], d["one_step"], "-", lw=0.8, label="one-step prediction")
        ax[0].set_xlabel("time t [s]")
        ax[0].set_ylabel(q["signal"])
        xr = t[-res.size:]
        ax[1].set_xlabel("time t [s]")
        vel = np.asarray(d["velocity"])[-res.size:]
    else:
        ax[0].plot(d["y"], ".", label="y")
        ax[0].plot(d["fitted"], "-", label="fit")
        ax[0].set_xlabel("sample [index]")
        ax[0].set_ylabel(q["signal"])
        xr = np.arange(res.size)
        ax[1].set_xlabel("sample [index]")
        vel = d.get("velocity", xr)
    ax[0].legend(fontsize=8)
    ax[0].set_title(title or f"{fit.method} / {fit.model} {fit.dof}".strip())
    ax[1].plot(xr, res, ".", ms=3)
    ax[1].axhline(0.0, color="k", lw=0.5)
    ax[1].set_ylabel(q["residual"])
    ax[1].set_title(f"residuals (J_LS = {fit.cost:.4g}, ν = {fit.degrees_of_freedom})")
    ax[2].plot(vel, res, ".", ms=3)
    ax[2].axhline(0.0, color="k", lw=0.5)
    ax[2].set_xlabel(q["velocity"])
    ax[2].set_ylabel(q["residual"])
    ax[2].set_title("residuals vs velocity")
    for a in ax:
        a.grid(True, alpha=0.3)
    return fig


def plot_fit(fit: FitResult, path, *, title: str | None = None, key: str = "path"):
    """Write :func:`fit_figure` to ``path`` (.png, .pdf or .svg); returns the Figure."""
    check_plot_path(path, key=key)
    fig = fit_figure(fit, title=title, key=key)
    save_figure(fig, path, key=key, dpi=110)
    return fig
