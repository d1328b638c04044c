"""Draw the MARES turning-circle figures of docs/limits.md (Ferreira et al. 2009, Figs. 6-8 reproduced)
and the REMUS 100 steering figure (docs/figures/remus100_limits.png).

Run from the repository root:  python -m scripts.make_limits_figures
Writes docs/figures/mares_limits.png (Munk moment off, as the paper finally uses, with the
Munk-on result dashed) and docs/figures/mares_limits_munk.png (Munk on alone: Fig. 6's
paradox).
"""

from pathlib import Path

import stripcoef
from stripcoef.cli.limits import parse_radii
from stripcoef.limits.plots import plot_limits
from stripcoef.limits.solver import solve_limits

ROOT = Path(__file__).resolve().parent.parent

if __name__ == "__main__":
    model = stripcoef.estimate(stripcoef.load_vehicle(ROOT / "geometry" / "mares.yaml"))
    radii = parse_radii("0.5:40:80")
    off = solve_limits(model, radii=radii, munk=False)
    on = solve_limits(model, radii=radii, munk=True)
    out = ROOT / "docs" / "figures"
    out.mkdir(parents=True, exist_ok=True)
    plot_limits(off, out / "mares_limits.png", compare=on,
                title="MARES (geometry/mares.yaml): steady starboard turns at the thrust limit")
    plot_limits(on, out / "mares_limits_munk.png",
                title="MARES with the Munk moment: the thrusters' moment opposes the turn")
    print(f"wrote {out / 'mares_limits.png'} and {out / 'mares_limits_munk.png'}")
    import warnings
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")          # REMUS is 7 % buoyant: trimmed, not refused
        remus = stripcoef.estimate(stripcoef.load_vehicle(ROOT / "geometry" / "remus100.yaml"))
    plot_limits(solve_limits(remus), out / "remus100_limits.png",
                title="REMUS 100 (geometry/remus100.yaml): steady flight with rudders and elevators")
    print(f"wrote {out / 'remus100_limits.png'}")
