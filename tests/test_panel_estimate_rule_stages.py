"""benchmarks.panel_estimate_rule maps the estimate's formal orders to its stages: one
``edge_order`` call per refinement stage, the first for the initial levels (three remeshed,
four on the base install's input ladder, whose single call made the benchmark fail)."""

from __future__ import annotations

from benchmarks.panel_estimate_rule import stage_orders


def test_remeshed_family_three_initial_levels_and_two_stages_more():
    orders = stage_orders([2.0, 4.0 / 3.0, 1.0], 5)
    assert orders[3] == 2.0 and orders[4] == 4.0 / 3.0 and orders[5] == 1.0
    assert orders[1] == orders[2] == 2.0


def test_input_ladder_one_call_for_four_levels():
    orders = stage_orders([4.0 / 3.0], 4)
    assert orders == {1: 4.0 / 3.0, 2: 4.0 / 3.0, 3: 4.0 / 3.0, 4: 4.0 / 3.0}


def test_a_stage_that_added_no_level():
    """The loop computes the order, then finds no finer level and stops: one call more than
    the levels added (the same count as a stage that stopped converged)."""
    orders = stage_orders([2.0, 1.0], 4)
    assert orders[3] == 2.0 and orders[4] == 1.0
