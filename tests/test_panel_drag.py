"""Cross-flow drag of arbitrary sections (polygon_drag): rule consistency and properties."""

import numpy as np
import pytest

from stripcoef.sections import drag
from stripcoef.sections.polygon_drag import TANDEM_SHIELDING, section_cross_flow_drag


def circle(r, n=200, y0=0.0, z0=0.0):
    t = np.linspace(0, 2 * np.pi, n, endpoint=False)
    return np.column_stack([y0 + r * np.cos(t), z0 + r * np.sin(t)])


def rect(b, h, y0=0.0, z0=0.0):
    return np.array([[-b, -h], [b, -h], [b, h], [-b, h]]) + [y0, z0]


def test_circle_is_the_dnv_cylinder():
    res = section_cross_flow_drag([circle(0.1)], reynolds_y=1e5, reynolds_z=3e5)
    assert res["rounded"] == [True]
    assert res["cd_y"] == pytest.approx(float(drag.circle_cd(1e5)), rel=1e-9)
    assert res["cd_z"] == pytest.approx(float(drag.circle_cd(3e5)), rel=1e-9)
    assert res["height_y"] == pytest.approx(0.2, rel=1e-3)


def test_square_and_rectangle_use_the_sharp_edge_table():
    res = section_cross_flow_drag([rect(0.2, 0.1)])     # 0.4 wide (y), 0.2 high (z)
    assert res["rounded"] == [False]
    # flow along y: depth 0.4 along the flow, height 0.2 across -> d/h = 2
    assert res["cd_y"] == pytest.approx(float(drag.rectangle_cd(2.0)))
    assert res["cd_z"] == pytest.approx(float(drag.rectangle_cd(0.5)))


def test_side_by_side_parts_count_only_their_heights():
    """Two squares stacked in z with a gap: flow along y sees 2 heights of 0.2 out of 0.6."""
    res = section_cross_flow_drag([rect(0.1, 0.1, z0=-0.2), rect(0.1, 0.1, z0=0.2)])
    assert res["parts"] == 2
    assert res["height_y"] == pytest.approx(0.6)
    assert res["cd_y"] == pytest.approx(float(drag.rectangle_cd(1.0)) * 0.4 / 0.6)


def test_tandem_parts_are_shielded():
    """Two squares one behind the other along y: the shadowed one counts with the shielding factor."""
    res = section_cross_flow_drag([rect(0.1, 0.1, y0=-0.5), rect(0.1, 0.1, y0=0.5)])
    cd = float(drag.rectangle_cd(1.0))
    # each part is shadowed in one of the two flow senses: w = h (1 - (1 - k)/2)
    expected = 2 * cd * 0.2 * (1 - 0.5 * (1 - TANDEM_SHIELDING)) / 0.2
    assert res["cd_y"] == pytest.approx(expected)
    # across z they are side by side: no shielding
    assert res["cd_z"] == pytest.approx(cd * 0.4 / 1.2)


def test_hole_does_not_change_the_outline():
    ring = [circle(0.2), circle(0.15)]
    a = section_cross_flow_drag(ring)
    b = section_cross_flow_drag([circle(0.2)])
    assert a["cd_y"] == pytest.approx(b["cd_y"]) and a["parts"] == 1
