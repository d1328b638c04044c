"""Figures of a fit: data vs model, residuals vs time (or sample) and vs velocity.

matplotlib is optional (``pip install stripcoef[plot]``); the Agg backend is used and the file
is written atomically (a failed plot leaves any earlier file untouched).
"""

from __future__ import annotations

import numpy as np

from stripcoef.errors import InputError
from stripcoef.files import atomic_path
from stripcoef.identify.estimators import FitResult


def _pyplot(key: str):
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        raise InputError("plotting needs matplotlib", key=key,
                         expected="pip install 'stripcoef[plot]'") from None
    return plt


def plot_fit(fit: FitResult, path, *, title: str | None = None, key: str = "path") -> None:
    """Three panels: data vs fit, residuals vs time/sample, residuals vs velocity (PNG/PDF/SVG)."""
    plt = _pyplot(key)
    d = fit.data
    fig, ax = plt.subplots(1, 3, figsize=(15, 4.2))
    res = np.asarray(fit.residuals)
    if fit.method.startswith("steady"):
        w, f = d["velocity"], d["force"]
        ax[0].plot(w, f, "o", label="measured")
        order = np.argsort(w)
        ax[0].plot(w[order], d["predicted"][order], "-", label=f"{fit.model} model")
        ax[0].set_xlabel("steady velocity")
        ax[0].set_ylabel("applied force")
        xr = np.arange(res.size)
        ax[1].set_xlabel("point")
        vel = w
    elif "t" in d:
        t = d["t"]
        ax[0].plot(t, d["y"], ".", ms=2, label="measured")
        ax[0].plot(t, d["simulated"], "-", label="re-simulated")
        if "one_step" in d:
            ax[0].plot(t[1:], d["one_step"], "-", lw=0.8, label="one-step prediction")
        ax[0].set_xlabel("t [s]")
        ax[0].set_ylabel("measured signal")
        xr = t[-res.size:]
        ax[1].set_xlabel("t [s]")
        vel = np.asarray(d["velocity"])[-res.size:]
    else:
        ax[0].plot(d["y"], ".", label="y")
        ax[0].plot(d["fitted"], "-", label="fit")
        xr = np.arange(res.size)
        vel = d.get("velocity", xr)
    ax[0].legend()
    ax[0].set_title(title or f"{fit.method} / {fit.model} {fit.dof}".strip())
    ax[1].plot(xr, res, ".", ms=3)
    ax[1].axhline(0.0, color="k", lw=0.5)
    ax[1].set_ylabel("residual")
    ax[1].set_title(f"residuals (J_LS = {fit.cost:.4g}, nu = {fit.degrees_of_freedom})")
    ax[2].plot(vel, res, ".", ms=3)
    ax[2].axhline(0.0, color="k", lw=0.5)
    ax[2].set_xlabel("velocity")
    ax[2].set_ylabel("residual")
    ax[2].set_title("residuals vs velocity")
    fig.tight_layout()
    fmt = str(path).rsplit(".", 1)[-1].lower() if "." in str(path) else "png"
    if fmt not in ("png", "pdf", "svg"):
        plt.close(fig)
        raise InputError("unknown plot format", key=key, value=str(path),
                         expected="a file name ending in .png, .pdf or .svg")
    try:
        with atomic_path(path, key=key) as tmp:
            fig.savefig(tmp, format=fmt, dpi=110)
    finally:
        plt.close(fig)
