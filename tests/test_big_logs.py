"""Big logs (issue 36): logs over ``stripcoef.logfile.PARSED_BYTES`` are read by numpy's C
parser at about 8 bytes a cell (a 250 MiB log: 289 MiB peak, benchmarks/big_log_memory.py),
with the same checks and one-line errors."""

import numpy as np
import pytest


def test_large_log_path_reads_and_names_bad_cells(tmp_path, monkeypatch):
    """The log reader of large files (numpy.loadtxt, exercised here on small files with the
    threshold at 0) gives the same log as the cell-by-cell reader, and a bad cell, a
    non-finite value or a short row is one InputError naming the file."""
    from stripcoef import logfile
    from stripcoef.errors import InputError

    text = "t,u,X\n" + "".join(f"{k / 10:.1f},{0.01 * k:.3f},{k % 7}\n" for k in range(50))
    f = tmp_path / "log.csv"
    f.write_text(text)
    small = logfile.read_log(f)
    monkeypatch.setattr(logfile, "PARSED_BYTES", 0)
    big = logfile.read_log(f)
    for k in small.names:
        np.testing.assert_array_equal(small[k], big[k])
    for bad, words in ((text.replace("0.020", "abc"), "could not convert string 'abc'"),
                       (text.replace("0.020", "nan"), "u: missing or non-finite value in row 4"),
                       (text.replace(",0.020,", ","), "number of columns changed")):
        f.write_text(bad)
        with pytest.raises(InputError, match=words) as e:
            logfile.read_log(f)
        assert str(f) in str(e.value) and "\n" not in str(e.value)
    f.write_text(text.replace("4.0,", "40000.0,"))     # time going backwards: still checked
    with pytest.raises(InputError, match="time goes backwards"):
        logfile.read_log(f)


def test_large_stream_path_gives_the_same_merged_log(tmp_path, monkeypatch):
    """Streams of a column map over the threshold (here 0) are read by numpy.loadtxt in
    extended precision: the merged log of chunked, offset, header-less streams is the one the
    cell-by-cell reader gives, to one unit in the last place (values parsed in extended
    precision, then rounded to float64)."""
    import warnings

    from stripcoef.ingest import read_mapped_log, streams
    from test_ingest_chunks import write_cmd, write_map, write_nav_chunks

    write_nav_chunks(tmp_path / "nav")
    write_cmd(tmp_path / "cmd.csv")
    m = write_map(tmp_path)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        small = read_mapped_log(tmp_path / "cmd.csv", m)
        monkeypatch.setattr(streams, "PARSED_BYTES", 0)
        big = read_mapped_log(tmp_path / "cmd.csv", m)
    assert small.names == big.names
    for k in small.names:
        np.testing.assert_allclose(small[k], big[k], rtol=3e-16, atol=1e-15, err_msg=k)
    for k in ("chunks", "overlap_dropped", "gaps", "samples"):
        assert big.meta["streams"]["nav"][k] == small.meta["streams"]["nav"][k]
    assert big.meta["streams"]["cmd"]["clock_offset"]["offset_s"] == pytest.approx(
        small.meta["streams"]["cmd"]["clock_offset"]["offset_s"], abs=1e-9)


def test_attitude_in_blocks_is_seamless(tmp_path, monkeypatch):
    """The attitude is turned into rotations in blocks of BLOCK_ROWS rows (bounded memory):
    blocks of 7 rows give the log of one block, a heading spinning past 360 deg unwrapped
    across the seams."""
    from stripcoef.ingest import merge, read_mapped_log

    t = np.arange(0.0, 30.0, 0.1)
    yaw = 40.0 * t                                          # 1200 deg: over three turns
    (tmp_path / "nav.csv").write_text("t,vn,ve,vd,roll,pitch,yaw\n" + "".join(
        f"{a!r},{0.3 + 0.01 * a!r},0.1,0.0,{5 * float(np.sin(a))!r},2.0,{y!r}\n"
        for a, y in zip(t.tolist(), yaw.tolist())))
    (tmp_path / "map.yaml").write_text(
        "streams:\n  nav: {time: t}\nattitude: {euler: [roll, pitch, yaw], unit: deg}\n"
        "velocity: {columns: [vn, ve, vd], frame: world}\n")
    one = read_mapped_log(tmp_path / "nav.csv", tmp_path / "map.yaml")
    monkeypatch.setattr(merge, "BLOCK_ROWS", 7)
    blocks = read_mapped_log(tmp_path / "nav.csv", tmp_path / "map.yaml")
    for k in one.names:
        np.testing.assert_array_equal(one[k], blocks[k], err_msg=k)
    np.testing.assert_allclose(one["psi"], np.radians(yaw), atol=1e-12)


def test_streams_over_the_size_limit_together_are_refused_up_front(tmp_path, monkeypatch):
    """Chunk files each under the limit but over it together: one line before any is read."""
    from stripcoef import files
    from stripcoef.errors import InputError
    from stripcoef.ingest import merge, read_mapped_log

    (tmp_path / "nav").mkdir()
    for k in range(3):
        (tmp_path / "nav" / f"c{k}.csv").write_text("t,u\n" + "".join(
            f"{k * 100 + i}.0,0.1\n" for i in range(100)))
    (tmp_path / "map.yaml").write_text("streams:\n  nav: {file: nav, time: t}\n"
                                       "velocity: {columns: [u, null, null]}\n")
    size = (tmp_path / "nav" / "c0.csv").stat().st_size
    monkeypatch.setattr(files, "MAX_TEXT_BYTES", int(2.5 * size))
    monkeypatch.setattr(merge, "MAX_TEXT_BYTES", int(2.5 * size))
    with pytest.raises(InputError, match="streams: the streams' files total .* fewer chunk"):
        read_mapped_log(tmp_path / "nav", tmp_path / "map.yaml")
