"""Figures of the manoeuvre limits (needs the ``plot`` extra, matplotlib).

:func:`limits_figure` builds and returns a :class:`matplotlib.figure.Figure` (no pyplot, no
backend switching, :mod:`stripcoef.figures`); :func:`plot_limits` writes it to a file.
"""

from __future__ import annotations

import math

import numpy as np

from stripcoef.errors import UnreachableError
from stripcoef.figures import check_plot_path, new_figure, save_figure
from stripcoef.limits.solver import LimitsResult


def limits_figure(result: LimitsResult, *, compare: LimitsResult | None = None,
                  compare_label: str | None = None, title: str | None = None,
                  key: str = "plot"):
    """The turning-circle figure: u_max(R) [m/s], drift angle(R) [deg], thrusts(R) [N].

    The three panels reproduce Ferreira et al. 2009 Figs. 7, 8 and 6. ``compare`` (e.g. the
    same vehicle with the Munk moment on) is drawn dashed. Legends sit right of the axes,
    off the curves; each thrust limit line names its thrusters and direction.
    """
    if result.steering is not None:
        return steering_figure(result, title=title, key=key)
    if not result.turning:
        reason = "; ".join(n for n in result.notes if n.startswith("unreachable")) or "no radii"
        raise UnreachableError(f"nothing to plot: no steady turn ({reason})")
    fig = new_figure(figsize=(9.5, 9.0), key=key)
    axes = fig.subplots(3, 1, sharex=True)

    def label(res):
        return ("Munk moment " + ("on" if res.options.munk else "off")
                + ("" if res.options.coriolis else ", no Coriolis"))

    runs = [(result, "-", label(result))]
    if compare is not None:
        runs.append((compare, "--", compare_label or label(compare)))
    for res, style, lab in runs:
        radii = [p.radius for p in res.turning]
        axes[0].plot(radii, [p.u_max for p in res.turning], style, color="C0",
                     label=f"$u_{{max}}(R)$, {lab}")
        axes[1].plot(radii, [math.degrees(p.drift_angle) for p in res.turning], style,
                     color="C0", label=f"drift angle, {lab}")
        names = list(res.turning[0].thrust) if res.turning else []
        for k, name in enumerate(names):
            forces = np.array([p.thrust[name] for p in res.turning])
            if np.abs(forces).max(initial=0.0) < 1e-6 * max(1.0, np.abs(forces).max(initial=0)):
                continue
            axes[2].plot(radii, forces, style, color=f"C{k % 10}",
                         label=f"thrust of {name} [N], {lab}")
    axes[0].axhline(result.surge_speed_max, color="0.4", lw=0.8, ls=":",
                    label=f"straight line {result.surge_speed_max:.3g} m/s")
    if compare is not None:
        axes[0].axhline(compare.surge_speed_max, color="0.6", lw=0.8, ls=":",
                        label=f"straight line {compare.surge_speed_max:.3g} m/s, "
                              f"{compare_label or label(compare)}")
    # one line per distinct limit, naming the thrusters and the direction that have it
    limits: dict[float, list[str]] = {}
    for name in (result.turning[0].thrust if result.turning else {}):
        fwd, back = result.thrust_limits.get(name, (None, None))
        for value, what in ((fwd, "forward"), (-back if back is not None else None, "backward")):
            if value is not None and math.isfinite(value):
                limits.setdefault(round(float(value), 9), []).append(f"{name} {what}")
    for k, (value, who) in enumerate(sorted(limits.items())):
        axes[2].axhline(value, color="0.3", lw=0.8, ls=(0, (1, 2 + k)),
                        label=f"limit {value:.3g} N: {', '.join(who)}")
    axes[0].set_ylabel("max. forward speed\n$u_{max}$ [m/s]")
    axes[0].set_ylim(bottom=0.0)
    axes[1].set_ylabel("drift angle $\\psi-\\chi$ [deg]\n(nose into the circle > 0)")
    axes[2].set_ylabel("thrust at $u_{max}$ [N]")
    axes[2].axhline(0.0, color="0.5", lw=0.6)
    axes[2].set_xlabel("turning radius $R$ [m]")
    for ax in axes:
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    fig.suptitle(title or f"{result.name}: steady starboard turns at the thrust limit")
    return fig


def steering_figure(result: LimitsResult, *, title: str | None = None, key: str = "plot"):
    """Figure of a rudder/elevator-steered vehicle against surge speed u [m/s]:
    full-rudder turning radius and drift angle; level-trim pitch and elevator; steepest dive
    and climb depth rates (the tables of :mod:`stripcoef.limits.steering`)."""
    steer = result.steering
    fig = new_figure(figsize=(9.5, 9.0), key=key)
    axes = fig.subplots(3, 1, sharex=True)
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
            ax.legend(fontsize=8, loc="upper left", bbox_to_anchor=(1.01, 1.0))
    fig.suptitle(title or f"{result.name}: steady flight with rudders and elevators")
    return fig


def plot_limits(result: LimitsResult, path, *, compare: LimitsResult | None = None,
                compare_label: str | None = None, title: str | None = None,
                key: str = "path"):
    """Write :func:`limits_figure` to ``path`` (.png, .pdf or .svg, atomically); returns the
    Figure. Needs the ``plot`` extra (matplotlib); raises InputError if it is missing."""
    check_plot_path(path, key=key)
    fig = limits_figure(result, compare=compare, compare_label=compare_label, title=title,
                        key=key)
    save_figure(fig, path, key=key, dpi=150)
    return fig
