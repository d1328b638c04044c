"""Progress bars: shown on a terminal, quiet in pipes and with --quiet, forced by --verbose;
transient (the output is the same with and without them); no bars stacked inside others."""

import fcntl
import os
import pty
import struct
import subprocess
import sys
import termios

import pytest

from stripcoef import progress
from stripcoef.cli import main

from conftest import ROOT

INPUTS = "t,X,Y\n0,20,0.05\n60,20,0.05\n"      # 601 samples, a few seconds of integration


@pytest.fixture
def inputs(tmp_path):
    f = tmp_path / "in.csv"
    f.write_text(INPUTS)
    return f


def _run_with_terminal_stderr(argv, cwd):
    """Run the CLI with stderr on a pseudo-terminal; return (exit code, what stderr showed)."""
    master, slave = pty.openpty()
    fcntl.ioctl(slave, termios.TIOCSWINSZ, struct.pack("HHHH", 24, 100, 0, 0))  # 100 columns
    # a bar shows after DELAY of work; on a fast machine the run may be shorter: no delay here
    env = {**os.environ, "PYTHONPATH": os.pathsep.join([str(ROOT / "src"), str(ROOT)]),
           "STRIPCOEF_PROGRESS_DELAY": "0"}
    proc = subprocess.Popen([sys.executable, "-m", "stripcoef", *argv], cwd=cwd, env=env,
                            stdout=subprocess.DEVNULL, stderr=slave, stdin=subprocess.DEVNULL)
    os.close(slave)
    chunks = []
    while True:
        try:
            data = os.read(master, 4096)
        except OSError:          # the child closed the terminal
            break
        if not data:
            break
        chunks.append(data)
    os.close(master)
    return proc.wait(timeout=300), b"".join(chunks).decode(errors="replace")


def test_bar_on_a_terminal_and_not_with_quiet(tmp_path, inputs, geometry_dir):
    argv = ["simulate", str(geometry_dir / "spheroid.yaml"), "--inputs", str(inputs),
            "-o", str(tmp_path / "log.csv")]
    code, shown = _run_with_terminal_stderr(argv, tmp_path)
    assert code == 0
    assert "simulate spheroid" in shown and "/60 s" in shown
    code, shown = _run_with_terminal_stderr(argv + ["--quiet"], tmp_path)
    assert code == 0 and "simulate spheroid" not in shown
    assert "heading runs away" in shown        # warnings are not progress: still shown


def test_quiet_in_a_pipe_and_verbose_forces_it(tmp_path, inputs, geometry_dir, capsys,
                                               monkeypatch):
    monkeypatch.setattr(progress, "DELAY", 0.0)  # a fast run may end before the usual delay
    argv = ["simulate", str(geometry_dir / "spheroid.yaml"), "--inputs", str(inputs),
            "-o", "-"]
    assert main(argv) == 0                     # pytest's captured stderr is not a terminal
    quiet_out, quiet_err = capsys.readouterr()
    assert "simulate spheroid" not in quiet_err
    assert main(argv + ["--verbose"]) == 0
    out, err = capsys.readouterr()
    assert "simulate spheroid" in err and "/60 s" in err
    assert out == quiet_out                    # the bar changes nothing else
    assert progress.depth() == 0


def test_nested_bars_are_silent_and_depth_recovers(capsys):
    with progress.bars(True):
        items = list(progress.track(range(3), desc="outer"))
        assert items == [0, 1, 2] and progress.depth() == 0

        def inner():
            assert progress.depth() == 1
            clock = progress.TimeBar(0.0, 1.0, desc="inner")
            assert clock._bar is None           # silent inside the outer bar
            clock.advance(0.5)
            clock.close()
        for _ in progress.track(range(1), desc="outer"):
            inner()

        def fails():
            progress.TimeBar(0.0, 1.0, desc="lost")
            raise ValueError
        with pytest.raises(ValueError):
            fails()
        import gc
        gc.collect()
        assert progress.depth() == 0             # a bar lost in an exception is released
    capsys.readouterr()


def test_bars_setting_is_scoped_to_its_block():
    with progress.bars(True):
        with progress.bars(False):
            assert not progress.enabled()
        assert progress.enabled()
