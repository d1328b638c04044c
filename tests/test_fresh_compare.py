"""Issue 33: the comparison of two runs of the independent benchmark
(benchmarks.fresh_compare) gives each rate its Wilson (1927) score interval and reads every
count from the runs' own summary text."""

from __future__ import annotations

import pytest

from benchmarks.fresh_compare import counts, table, wilson_interval


@pytest.mark.parametrize("k, n, lo, hi", [
    # Newcombe 1998, Stat. Med. 17:857-872, Table I, method 3 (Wilson score, no correction)
    (81, 263, 0.2553, 0.3662),
    (15, 148, 0.0624, 0.1605),
    (0, 20, 0.0, 0.1611),
    (1, 29, 0.0061, 0.1718),
    (29, 29, 0.8830, 1.0),
])
def test_wilson_interval_matches_newcombes_table(k, n, lo, hi):
    got = wilson_interval(k, n)
    assert got == pytest.approx((lo, hi), abs=6e-5)


def test_wilson_interval_refuses_impossible_counts():
    with pytest.raises(ValueError, match="k=5, n=4"):
        wilson_interval(5, 4)


SUMMARY = ("Seed 1, 2 logs.\nLibrary effects named first: 78/88 (89 %); named first or in "
           "the first step's ambiguous set (...): 78/88; named first after the truth's "
           "background (buoyancy, thrust gains): 80/88; magnitude within 15 %: 69/88 (of the "
           "drawn strength, magnitude_error_drawn: 62/88; within 15 % and held by the written "
           "model, not removed by its validation: 58/88); error cut >= 3x: 55/88 (the "
           "truth's own model cuts the prior's error >= 3x in 86/88 of the rows with the "
           "oracle; of those the diagnosis does in 55/86).\nWhole-log runs ...: named in "
           "3/44, kept in the written model in 2/44 (by the earlier rule, ...: named 4/44, "
           "kept 2/44).\nClean logs: an effect named in 4 of 8, kept in the written model in "
           "2 of 8; an effect other than the background named in 0 of 8 (...).\nDry friction "
           "(outside the library): 'unexplained' or held-out gains under 30 % in 7 of 8; "
           "named: None.\n")


def test_counts_are_read_from_the_summary_text():
    got = counts(SUMMARY)
    assert got["library effects named first"] == (78, 88)
    assert got["named first after the background"] == (80, 88)
    assert got["magnitude within 15 %"] == (69, 88)
    assert got["magnitude within 15 %, held by the written model"] == (58, 88)
    assert got["error cut >= 3x"] == (55, 88)
    assert got["the truth's own cut >= 3x"] == (86, 88)
    assert got["error cut >= 3x where the truth's is"] == (55, 86)
    assert got["whole-log runs with a spurious step named"] == (3, 44)
    assert got["whole-log runs with a spurious step kept"] == (2, 44)
    assert got["clean logs naming an effect other than the background"] == (0, 8)
    assert got["dry friction unexplained or held-out gains under 30 %"] == (7, 8)


def test_table_says_which_bar_is_missed():
    text = table({"a": SUMMARY})
    assert "| library effects named first | >= 95 % | 78/88 (89 %; 80-94 %) | missed " \
           "(interval beyond the bar) |" in text
    assert "| dry friction unexplained or held-out gains under 30 % | >= 100 % | 7/8 " \
           "(88 %; 53-98 %) | missed (interval beyond the bar) |" in text
    # a rate short of its bar whose interval still reaches it
    five = SUMMARY.replace("named first: 78/88", "named first: 82/88")
    assert "82/88 (93 %; 86-97 %) | missed (interval reaches the bar) |" in table({"a": five})


def test_pair_table_shows_both_counts_and_intervals():
    from benchmarks.fresh_compare import pair_table
    better = SUMMARY.replace("error cut >= 3x: 55/88", "error cut >= 3x: 70/88")
    text = pair_table({"seed 1": (SUMMARY, better)})
    # 55/88: Wilson 52-72 %; 70/88: 70-87 %
    assert "| error cut >= 3x | - | 55 -> 70 of 88 (52-72 % -> 70-87 %) |" in text
    assert "| whole-log runs with a spurious step named | <= 10 % | 3 -> 3 of 44 " in text


def test_pairs_need_an_even_number_of_files(tmp_path, capsys):
    from benchmarks.fresh_compare import main
    path = tmp_path / "a.md"
    path.write_text(SUMMARY)
    assert main(["--pairs", str(path)]) == 2
    assert "even number of files, got 1" in capsys.readouterr().out
    assert main(["--pairs", f"one={path}", str(path)]) == 0
    assert "| one: base -> other (Wilson 95 %) |" in capsys.readouterr().out


def test_pair_table_pools_the_seeds():
    from benchmarks.fresh_compare import pair_table
    better = SUMMARY.replace("error cut >= 3x: 55/88", "error cut >= 3x: 70/88")
    text = pair_table({"seed 1": (SUMMARY, better), "seed 2": (SUMMARY, SUMMARY)})
    row = next(line for line in text.splitlines() if line.startswith("| error cut >= 3x |"))
    # pooled: 55 + 55 -> 70 + 55 of 176
    assert row.endswith("| 110 -> 125 of 176 (55-69 % -> 64-77 %) |")
