"""stripcoef.hull.panels.edge_order: the formal order of the panel method's grid convergence
index on a body with edges, 2 lambda with lambda = pi / (pi + theta) (von Petersdorff &
Stephan 1990), and the sharpest convex edge it is read from."""

import numpy as np
import pytest
import trimesh

from stripcoef.hull.panels import SMOOTH_ORDER, edge_order, max_convex_turning


def test_orders_of_the_wedge_singularity():
    assert edge_order(0.0) == SMOOTH_ORDER == 2.0
    assert edge_order(np.pi / 2) == pytest.approx(4.0 / 3.0, rel=1e-12)     # right angle
    assert edge_order(np.pi) == pytest.approx(1.0, rel=1e-12)              # knife edge
    assert edge_order(np.radians(45.0)) == pytest.approx(1.6, rel=1e-12)   # a chamfer
    # orders fall as the edge sharpens
    th = np.linspace(0.0, np.pi, 19)
    assert np.all(np.diff([edge_order(t) for t in th]) < 0)


def test_a_member_thinner_than_the_panels_is_a_knife_edge():
    """A plate's two right-angled rims within one panel: the normal turns by pi across a
    panel; once the panels are finer than the plate, its own right angles count."""
    assert edge_order(np.pi / 2, edge=0.02, thickness=0.01) == pytest.approx(1.0)
    assert edge_order(np.pi / 2, edge=0.005, thickness=0.01) == pytest.approx(4.0 / 3.0)
    assert edge_order(0.0, edge=0.02, thickness=0.01) == pytest.approx(1.0)


def test_sharpest_convex_edge_of_a_box_a_chamfer_and_a_sphere():
    box = trimesh.creation.box([0.4, 0.3, 0.2])
    assert max_convex_turning(box.vertices, box.faces) == pytest.approx(np.pi / 2, rel=1e-9)
    sphere = trimesh.creation.icosphere(subdivisions=3)
    assert max_convex_turning(sphere.vertices, sphere.faces) < np.radians(15.0)
    # a box with chamfered vertical edges: the chamfers turn by 45 degrees, the caps' rims
    # still by 90
    poly = np.array([[0.2, 0.1], [0.1, 0.2], [-0.1, 0.2], [-0.2, 0.1], [-0.2, -0.1],
                     [-0.1, -0.2], [0.1, -0.2], [0.2, -0.1]])
    prism = trimesh.creation.extrude_polygon(__import__("shapely").Polygon(poly), 0.3)
    assert max_convex_turning(prism.vertices, prism.faces) == pytest.approx(np.pi / 2, rel=1e-9)
