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
