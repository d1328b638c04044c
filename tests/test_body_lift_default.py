"""What ``body_lift: stratford_panel`` as the default would do beyond SUBOFF (issue 34,
benchmarks/body_lift_default.py; benchmarks/data/body_lift_default.md): on REMUS's truncated
Myring tail Stratford's criterion finds no separation and the body keeps only its base's lift; on
an untruncated 25-deg Myring tail it separates close to the tail; on a 15-deg tail it does not.
Where it finds none, a ModelWarning says so."""

from __future__ import annotations

import pytest
import yaml

from benchmarks.body_lift_default import GEOMETRY, _vehicle, body_lift_info, myring_vehicle, with_rule


def _remus(rule):
    data = yaml.safe_load((GEOMETRY / "remus100.yaml").read_text())
    return _vehicle(with_rule(data, rule), "geometry/remus100.yaml")


def test_remus_keeps_only_its_base_lift_under_stratford_panel():
    from stripcoef.assembly.lift import _body_lift
    datcom, panel = _remus("datcom"), _remus("stratford_panel")
    assert body_lift_info(datcom)["fraction"] == pytest.approx(0.855, abs=0.001)   # Hopkins
    info = body_lift_info(panel)
    assert info["limit"] == "end" and info["fraction"] == pytest.approx(1.0)
    assert len(info["warnings"]) == 1 and "not met ahead of 0.97 l" in info["warnings"][0]
    lift = {v.body_lift: _body_lift(v, 1030.0, [0, 0, 0], [0, 0, 0])[0][1, 1] for v in (datcom, panel)}
    assert lift["stratford_panel"] < 0.06 * lift["datcom"]     # the truncated base's lift only


@pytest.mark.parametrize("theta, station", [(15.0, None), (25.0, (0.94, 0.97))])
def test_myring_tails_separate_only_near_the_tail(theta, station):
    info = body_lift_info(_vehicle(myring_vehicle(theta, 1.0, "stratford_panel"), "<myring>"),
                          speed=1.5)
    if station is None:
        assert info["limit"] == "end" and info["fraction"] == pytest.approx(1.0)
    else:
        assert info["limit"] is None and station[0] < info["fraction"] < station[1]
