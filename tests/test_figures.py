"""Pictures: Figures built without pyplot (no backend switching in the library), returned,
written on request, every axis labelled with a quantity and its unit."""

import json
import re
import subprocess
import sys

from importlib.util import find_spec

import numpy as np
import pytest

if find_spec("matplotlib") is None:          # found, not imported, while collecting
    pytest.skip("matplotlib not installed", allow_module_level=True)

from stripcoef.cli import main  # noqa: E402

from conftest import ROOT  # noqa: E402

UNIT = re.compile(r"\[[^\]]+\]")


def _axes_labelled(fig):
    """Every axis that shows data has an x and a y label with a unit in [ ]."""
    from matplotlib.figure import Figure

    assert isinstance(fig, Figure)
    checked = 0
    for ax in fig.axes:
        if not (ax.lines or ax.patches or ax.collections):
            continue
        for label in (ax.get_xlabel(), ax.get_ylabel()):
            if ax.get_shared_x_axes().get_siblings(ax) != [ax] and label == "":
                continue                       # a shared x axis labelled on its last panel
            assert UNIT.search(label), f"axis label without a unit: {label!r} in {ax.get_title()!r}"
        checked += 1
    assert checked


def test_no_backend_switching_or_pyplot_in_the_library():
    for path in (ROOT / "src" / "stripcoef").rglob("*.py"):
        text = path.read_text()
        assert "matplotlib.use(" not in text, path
        assert "import matplotlib.pyplot" not in text and "from matplotlib import pyplot" \
            not in text, path


def test_figures_leave_pyplot_and_the_backend_alone(tmp_path):
    code = f"""
import sys, matplotlib
before = matplotlib.get_backend() if 'matplotlib.pyplot' in sys.modules else None
from stripcoef import estimate
from stripcoef.limits import solve_limits
from stripcoef.limits.plots import limits_figure
from stripcoef.geometry.plots import body_figure
from stripcoef.geometry.vehicle import load_vehicle
from stripcoef.simulate import simulate
from stripcoef.figures import motion_figure
import numpy as np
v = load_vehicle({str(ROOT / 'geometry' / 'videoray_pro3.yaml')!r})
# MARES's model: strips only (the VideoRay's panel solve, 1.5 s of CPU, draws nothing)
m = estimate(load_vehicle({str(ROOT / 'geometry' / 'mares.yaml')!r}))
figs = [body_figure(v.cut(200)), limits_figure(solve_limits(m, radii=[1.0, 2.0])),
        motion_figure(simulate(m, np.linspace(0, 2, 21), commands={{'P1': 5.0}}))]
assert 'matplotlib.pyplot' not in sys.modules, 'pyplot imported'
print('ok', len(figs))
"""
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True,
                         timeout=300)
    assert out.returncode == 0, out.stderr[-2000:]
    assert out.stdout.startswith("ok 3")


def test_body_figure_and_coefficients_plot(tmp_path, capsys, geometry_dir):
    from stripcoef.geometry.plots import body_figure
    from stripcoef.geometry.vehicle import load_vehicle

    strips = load_vehicle(geometry_dir / "mares.yaml").cut(120)
    fig = body_figure(strips, name="MARES", points={"CB": (0.0, 0.0, 0.0)}, sections=3)
    _axes_labelled(fig)
    assert len(fig.axes) == 2 + 3
    assert "120 strips" in fig.axes[0].get_title()
    png = tmp_path / "body.png"
    assert main(["coefficients", str(geometry_dir / "mares.yaml"), "--strips", "80",
                 "--plot", str(png)]) == 0
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert main(["coefficients", str(geometry_dir / "mares.yaml"), "--plot",
                 str(tmp_path / "body.gif")]) == 2
    err = capsys.readouterr().err
    assert "--plot" in err and ".png, .pdf or .svg" in err


def test_simulate_plot(tmp_path, capsys, geometry_dir):
    f = tmp_path / "in.csv"
    f.write_text("t,X,N\n0,20,0.5\n10,20,0.5\n")
    svg = tmp_path / "run.svg"
    assert main(["simulate", str(geometry_dir / "spheroid.yaml"), "--inputs", str(f),
                 "--out", str(tmp_path / "log.csv"), "--plot", str(svg)]) == 0
    text = svg.read_text()
    assert text.lstrip().startswith("<?xml") and "north x [m]" in text
    from stripcoef.figures import motion_figure
    from stripcoef.logfile import read_log
    _axes_labelled(motion_figure(read_log(tmp_path / "log.csv")))


def test_limits_legends_outside_and_limit_lines_named(geometry_dir):
    from stripcoef.limits import solve_limits
    from stripcoef.limits.plots import limits_figure
    from conftest import shipped_model     # load_model of the file, shared with other tests

    fig = limits_figure(solve_limits(shipped_model("videoray_pro3.yaml"),
                                     radii=np.linspace(0.5, 3.0, 6)))
    _axes_labelled(fig)
    fig.canvas.draw()
    for ax in fig.axes:
        legend = ax.get_legend()
        box = legend.get_window_extent()
        assert box.x0 >= ax.get_window_extent().x1 - 1.0    # right of the axes, off the curves
    labels = [t.get_text() for t in fig.axes[2].get_legend().get_texts()]
    named = [s for s in labels if s.startswith("limit ")]
    assert named and all(re.search(r"(port|starboard|vertical) (forward|backward)", s)
                         for s in named)
    assert any("12.6 N" in s and "port forward" in s and "starboard forward" in s for s in named)


def test_identify_plot_quantities(tmp_path):
    from validation.experiments import videoray_yaw_log

    from stripcoef.identify.api import identify_log
    from stripcoef.identify.plots import fit_figure

    fit, _ = identify_log(videoray_yaw_log(0), "one-step", dof="yaw")
    fig = fit_figure(fit)
    _axes_labelled(fig)
    labels = [ax.get_ylabel() for ax in fig.axes]
    assert labels[0] == "yaw velocity r [rad/s]"
    assert labels[1] == "one-step residual of r [rad/s]"


def test_compare_plot(tmp_path, capsys):
    pytest.importorskip("capytaine")
    png = tmp_path / "cmp.png"
    assert main(["compare", "sample:capsule.stl", "--strips", "80", "--plot", str(png),
                 "--json"]) == 0
    data = json.loads(capsys.readouterr().out)
    assert png.stat().st_size > 10_000
    terms = {t["term"]: t["diff_percent"] for t in data["terms"]}
    assert abs(terms["Y_vdot"]) < 3 and abs(terms["M_qdot"]) < 3
    from stripcoef.bem import comparison_figure
    a = np.diag([1.0, 2.0, 2.0, 0.1, 0.5, 0.5])
    _axes_labelled(comparison_figure(a, a * 1.01))
