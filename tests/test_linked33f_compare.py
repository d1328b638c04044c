"""benchmarks.linked33f_compare: the identified mode's rows composed from the default's and
``linked_gains=True``'s by the link decision (linked33f)."""

from benchmarks.linked33f_compare import compose, read_decisions


def _row(seed, first, cut):
    return {"vehicle": "bluerov2_heavy", "category": "deadband", "seed": seed, "mode": "all",
            "first": first, "cut": cut, "magnitude_error": 0.01, "step_effects": {},
            "step_effects_kept": {}, "truth_has": {}}


def test_rows_follow_the_decision_and_a_log_without_one_is_reported(tmp_path):
    links = tmp_path / "links.txt"
    links.write_text("bluerov2_heavy deadband 11: t1+t2 vs t3+t4 via roll,pitch: ratio 1.643 "
                     "(spread 3.788) linked (12.1 s CPU)\n"
                     "bluerov2_heavy deadband 12: t1+t2 vs t3+t4 via roll,pitch: ratio 0.638 "
                     "(spread 2.012) (12.1 s CPU)\n")
    decisions = read_decisions([str(links)])
    assert decisions == {11: (1.643, 3.788), 12: (0.638, 2.012)}
    default = {s: _row(s, "deadband", 1.1) for s in (11, 12, 13, 14)}
    linked = {s: _row(s, "deadband", 18.7) for s in (11, 12, 13)}
    linked[14] = _row(14, "deadband", 1.2)      # the same status as the default's
    rows, missing = compose(default, linked, decisions, 0)
    assert rows[11] is linked[11] and rows[12] is default[12] and rows[14] is default[14]
    assert missing == [13]                      # rows differ (cut 1.1 vs 18.7), no decision
    rows, _ = compose(default, linked, decisions, 1)       # the spread's ratio: both link
    assert rows[12] is linked[12]
