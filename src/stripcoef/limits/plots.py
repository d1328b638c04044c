"""Figures of the manoeuvre limits (needs the ``plot`` extra, matplotlib)."""

from __future__ import annotations
import math
import numpy as np
from stripcoef.errors import InputError, UnreachableError
from stripcoef.limits.solver import LimitsResult


def plot_limits(result: LimitsResult, path, *, compare: LimitsResult | None = None,
                compare_label: str | None = None, title: str | None = None,
                key: str = "path") -> None:
    """Write the turning-circle figure (PNG, atomically): u_max(R), drift angle(R), thrusts(R).

    The three panels reproduce Ferreira et al. 2009 Figs. 7, 8 and 6.  ``compare`` (e.g. the same
    vehicle with the Munk moment on) is drawn dashed.  Needs the ``plot`` extra
    (matplotlib); raises InputError if it is missing.
    """
    try:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
    except ImportError:
        raise InputError("plotting needs matplotlib", key=key, value=str(path),
                         expected="pip install 'stripcoef[plot]'") from None
    from stripcoef.files import atomic_path

    if result.steering is not None:
        return plot_steering(result, path, title=title, key=key, plt=plt)
    if not result.turning:
        reason = "; ".join(n for n in result.notes if n.startswith("unreachable")) or "no radii"
        raise UnreachableError(f"nothing to plot: no steady turn ({reason})")

    def label(res):
        return ("Munk moment " + ("on" if res.options.munk else "off")
                + ("" if res.options.coriolis else ", no Coriolis"))

    fig, axes = plt.subplots(3, 1, figsize=(7.0, 9.0), sharex=True, constrained_layout=True)
    runs = [(result, "-", label(result))]
    if compare is not None:
        runs.append((compare, "--", compare_label or label(compare)))
    colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for res, style, lab in runs:
        radii = [p.radius for p in res.turning]
        axes[0].plot(radii, [p.u_max for p in res.turning], style, color="C0",
                     label=f"$u_{{max}}(R)$, {lab}")
        axes[1].plot(radii, [math.degrees(p.drift_angle) for p in res.turning], style,
                     color="C0", label=lab)
        names = list(res.turning[0].thrust) if res.turning else []
        for k, name in enumerate(names):
            forces = np.array([p.thrust[name] for p in res.turning])
            if np.abs(forces).max(initial=0.0) < 1e-6 * max(1.0, np.abs(forces).max(initial=0)):
                continue
            colour = colours[k % len(colours)]
            axes[2].plot(radii, forces, style, color=colour, label=f"{name}, {lab}")
    axes[0].axhline(result.surge_speed_max, color="0.4", lw=0.8, ls=":",
                    label=f"straight line {result.surge_speed_max:.3g} m/s")
    if compare is not None:
        axes[0].axhline(compare.surge_speed_max, color="0.6", lw=0.8, ls=":")
    shown = sorted({v for name in (result.turning[0].thrust if result.turning else {})
                     for v in (result.thrust_limits.get(name, (None, None))[0],
                               -result.thrust_limits.get(name, (0, 0))[1]) if v is not None})
    for k, lim in enumerate(shown):
        axes[2].axhline(lim, color="0.3", lw=0.8, ls=":", label="thrust limits" if k == 0 else None)
    axes[0].set_ylabel("max. forward speed $u_{max}$ [m/s]")
    axes[0].set_ylim(bottom=0.0)
    axes[1].set_ylabel("drift angle $\\psi-\\chi$ [deg]\n(nose into the circle > 0)")
    axes[2].set_ylabel("thrust at $u_{max}$ [N]")
    axes[2].axhline(0.0, color="0.5", lw=0.6)
    axes[2].set_xlabel("turning radius $R$ [m]")
    for k, ax in enumerate(axes):
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7 if k == 2 else 8, loc="best", ncol=2 if k == 2 else 1)
    fig.suptitle(title or f"{result.name}: steady starboard turns at the thrust limit")
    with atomic_path(path, key=key) as tmp:
        fig.savefig(tmp, format="png", dpi=150)
    plt.close(fig)


def plot_steering(result: LimitsResult, path, *, title: str | None = None, key: str = "path",
                  plt=None) -> None:
    """Figure of a rudder/elevator-steered vehicle (PNG, atomically) against surge speed u:
    full-rudder turning radius and drift angle; level-trim pitch and elevator; steepest dive
    and climb depth rates (the tables of :mod:`stripcoef.limits.steering`)."""
    from stripcoef.files import atomic_path

    steer = result.steering
    fig, axes = plt.subplots(3, 1, figsize=(7.0, 9.0), sharex=True, constrained_layout=True)
    if steer.turning:
        u = [f.u for f in steer.turning]
        axes[0].plot(u, [f.radius for f in steer.turning], "-o", ms=3, label="radius R [m]")
        axes[0].plot(u, [abs(math.degrees(f.drift_angle)) for f in steer.turning], "--s", ms=3,
                     label="|drift angle| [deg]")
    if steer.trim:
        u = [f.u for f in steer.trim]
        axes[1].plot(u, [math.degrees(f.pitch) for f in steer.trim], "-o", ms=3,
                     label="pitch [deg]")
        for name in steer.trim[0].deflections:
            vals = [math.degrees(f.deflections[name]) for f in steer.trim]
            if any(abs(v) > 1e-9 for v in vals):
                axes[1].plot(u, vals, "--s", ms=3, label=f"{name} [deg]")
        if steer.level_speed_min:
            axes[1].axvline(steer.level_speed_min, color="0.4", lw=0.8, ls=":",
                            label=f"slowest level flight {steer.level_speed_min:.3g} m/s")
    for rows, lab in ((steer.dive, "steepest dive"), (steer.climb, "steepest climb")):
        if rows:
            axes[2].plot([f.u for f in rows], [f.depth_rate for f in rows], "-o", ms=3,
                         label=f"{lab}: dz/dt [m/s] (down > 0)")
    axes[2].axhline(0.0, color="0.5", lw=0.6)
    axes[0].set_ylabel("full-rudder turn")
    axes[1].set_ylabel("level trim")
    axes[2].set_ylabel("depth rate [m/s]")
    axes[2].set_xlabel("surge speed u [m/s]")
    for ax in axes:
        ax.axvline(steer.surge_speed_max, color="0.6", lw=0.8, ls=":")
        ax.grid(True, alpha=0.3)
        if ax.get_legend_handles_labels()[0]:
            ax.legend(fontsize=8, loc="best")
    fig.suptitle(title or f"{result.name}: steady flight with rudders and elevators")
    with atomic_path(path, key=key) as tmp:
        fig.savefig(tmp, format="png", dpi=150)
    plt.close(fig)
