"""The diagnosis' command-line flags (``benchmarks.diagnose_flags``): one registry for the
benchmarks that run diagnose, each flag a keyword of ``DiagnoseSettings``, an option left
out diagnose's own default, and the command text a run writes parsed back to the same
options."""

import argparse
import dataclasses

import pytest

from benchmarks.diagnose_flags import FLAGS, add_flags, command_text, given
from stripcoef.diagnose.settings import DiagnoseSettings


def _parse(argv):
    ap = argparse.ArgumentParser()
    add_flags(ap)
    return given(ap.parse_args(argv))


def test_every_flag_is_a_setting_of_diagnose():
    fields = {f.name for f in dataclasses.fields(DiagnoseSettings)}
    assert {key for _, key, _ in FLAGS} <= fields


def test_no_flag_given_is_diagnose_default():
    assert _parse([]) == {}


@pytest.mark.parametrize("argv", [
    ["--linked-gains", "off", "--validation-horizon", "10", "--no-noise-with-bias",
     "--validation-others", "logged", "--validation-judge", "all",
     "--validation-reference", "trivial"],
    ["--linked-gains", "--gains-beside-current", "test", "--one-added-mass",
     "--no-dof-gains", "--validation-horizon", "correlation"],
    ["--noise-with-bias", "--dof-gains", "--no-scale-choice-unforced",
     "--gains-judge", "written_all", "--validation-choice", "best_visited"],
])
def test_command_text_parses_back_to_the_same_options(argv):
    options = _parse(argv)
    assert _parse(command_text(options).split()) == options


def test_values_are_diagnose_keywords():
    options = _parse(["--linked-gains", "off", "--validation-horizon", "12.5"])
    assert options == {"linked_gains": False, "validation_horizon": 12.5}
    assert _parse(["--no-noise-with-bias"]) == {"noise_with_bias": False}


@pytest.mark.parametrize("module", ["benchmarks.diagnose_independent", "benchmarks.real_logs",
                                    "benchmarks.real33h_trace", "benchmarks.real_logs_trace"])
def test_the_benchmarks_take_the_registry(module, capsys):
    import importlib
    main = importlib.import_module(module).main
    with pytest.raises(SystemExit) as exc:
        main(["--help"])
    assert exc.value.code == 0
    text = capsys.readouterr().out
    for flag, _, _ in FLAGS:
        assert flag in text
