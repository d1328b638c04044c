"""Big logs in bounded memory (issue 36): peak memory and time of reading generated CSV logs.

Three generated logs of a 6-DOF vehicle (t, u v w p q r, x y z phi theta psi, X Y Z K M N:
19 columns), each measured in a fresh process with GNU time (``/usr/bin/time -v``: "Maximum
resident set size" and the elapsed wall clock), then deleted:

- a 1 GiB CSV given to ``stripcoef diagnose``: refused before a byte is read
  (``stripcoef.files.MAX_TEXT_BYTES`` = 256 MiB), one line with the remedy, exit 2;
- a 250 MiB CSV (just under the limit) read by ``stripcoef.logfile.read_log``: numpy's C parser
  (``numpy.loadtxt``) at about 8 bytes a cell, checked (finite cells, increasing time,
  magnitudes);
- a 200,000-row log (about 32 MB) read the same way;
- a 250 MiB stream of a column map (epoch stamps, three velocities and a heading in degrees:
  5.5 M short rows, the densest kind) read and merged by ``stripcoef.ingest.read_mapped_log``.

    python -m benchmarks.big_log_memory [--dir FOLDER]

The numbers and the command are in docs/reliability.md. The files are written into ``--dir``
(default: a new temporary folder) and removed at the end, also after a failure.
"""

from __future__ import annotations

import argparse
import re
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

COLUMNS = ("t", "u", "v", "w", "p", "q", "r", "x", "y", "z", "phi", "theta", "psi",
           "X", "Y", "Z", "K", "M", "N")
RATE = 20.0           # [Hz]
BLOCK = 10_000        # rows per block of the writer


def write_log(path: Path, *, rows: int | None = None, size: int | None = None,
              seed: int = 36) -> int:
    """A log of ``rows`` rows, or of about ``size`` bytes; returns the row count. The other
    columns of a block of random but plausible values repeat from block to block (their
    formatting would dominate the time); the time advances at ``RATE``."""
    rng = np.random.default_rng(seed)
    scale = np.array([1.0, 0.2, 0.2, 0.3, 0.3, 0.3, 50.0, 50.0, 20.0, 0.3, 0.3, 3.0,
                      50.0, 30.0, 30.0, 5.0, 5.0, 5.0])
    rest = [",".join(f"{v:.6g}" for v in row)
            for row in rng.standard_normal((BLOCK, scale.size)) * scale]
    n = 0
    written = 0
    with open(path, "w") as f:
        f.write(",".join(COLUMNS) + "\n")
        while (rows is None or n < rows) and (size is None or written < size):
            m = BLOCK if rows is None else min(BLOCK, rows - n)
            text = "\n".join(f"{(n + k) / RATE:.2f},{rest[k]}" for k in range(m)) + "\n"
            f.write(text)
            written += len(text)
            n += m
    return n


def measure(argv) -> dict:
    """Peak resident memory [MiB], wall clock [s], exit code and the last stderr line of a
    command run under ``/usr/bin/time -v``."""
    proc = subprocess.run(["/usr/bin/time", "-v", *argv], capture_output=True, text=True)
    rss = re.search(r"Maximum resident set size \(kbytes\): (\d+)", proc.stderr)
    wall = re.search(r"Elapsed \(wall clock\) time.*: (?:(\d+):)?(\d+):([\d.]+)", proc.stderr)
    secs = (int(wall.group(1) or 0) * 3600 + int(wall.group(2)) * 60 + float(wall.group(3))
            if wall else float("nan"))
    lines = [ln for ln in proc.stderr.splitlines() if ln.startswith("stripcoef")]
    return {"rss_mib": int(rss.group(1)) / 1024 if rss else float("nan"), "wall_s": secs,
            "rc": proc.returncode, "said": (lines or [proc.stdout.strip()])[-1][:160]}


def write_stream(path: Path, *, size: int) -> int:
    """A navigation stream of about ``size`` bytes (stamp, vx, vy, vz, yaw in degrees) and its
    column map beside it (``map.yaml``); returns the row count."""
    n = 0
    written = 0
    with open(path, "w") as f:
        f.write("stamp,vx,vy,vz,yaw\n")
        while written < size:
            text = "".join(f"{1.7e9 + (n + k) / RATE:.3f},0.123456,0.123456,0.123456,"
                           f"{(n + k) % 3600 / 10:.2f}\n" for k in range(BLOCK))
            f.write(text)
            written += len(text)
            n += BLOCK
    (path.parent / "map.yaml").write_text(
        "streams:\n  nav: {time: {column: stamp}}\nvelocity: {columns: [vx, vy, vz]}\n"
        "attitude: {euler: [null, null, yaw], unit: deg}\n")
    return n


MAPPED = ("from stripcoef.ingest import read_mapped_log; import sys; "
          "log = read_mapped_log(sys.argv[1], sys.argv[2]); "
          "print(f'stripcoef merged {len(log)} rows of {len(log.names)} columns')")
READ = ("from stripcoef.logfile import read_log; import sys; log = read_log(sys.argv[1]); "
        "print(f'stripcoef read {len(log)} rows of {len(log.names)} columns')")


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--dir", default=None, help="folder for the generated logs (removed after)")
    args = p.parse_args(argv)
    folder = Path(tempfile.mkdtemp(prefix="big-logs-", dir=args.dir))
    rows = []
    try:
        cases = (("1 GiB, stripcoef diagnose", {"size": 2**30},
                  lambda f: [sys.executable, "-m", "stripcoef", "diagnose", str(f),
                             "--vehicle", "sample:sphere.yaml", "--dof", "surge"]),
                 ("250 MiB, read_log", {"size": 250 * 2**20},
                  lambda f: [sys.executable, "-c", READ, str(f)]),
                 ("200,000 rows, read_log", {"rows": 200_000},
                  lambda f: [sys.executable, "-c", READ, str(f)]),
                 ("250 MiB column-map stream, read_mapped_log", {"size": 250 * 2**20,
                                                                  "mapped": True},
                  lambda f: [sys.executable, "-c", MAPPED, str(f), str(f.parent / "map.yaml")]))
        for name, how, command in cases:
            f = folder / "log.csv"
            t0 = time.perf_counter()
            n = write_stream(f, size=how["size"]) if how.pop("mapped", False) \
                else write_log(f, **how)
            made = time.perf_counter() - t0
            size = f.stat().st_size
            r = measure(command(f))
            f.unlink()
            rows.append((name, size, n, made, r))
            print(f"{name}: {size / 2**20:.0f} MiB, {n} rows (written in {made:.0f} s): peak "
                  f"{r['rss_mib']:.0f} MiB, {r['wall_s']:.1f} s, exit {r['rc']}: {r['said']}",
                  flush=True)
    finally:
        shutil.rmtree(folder, ignore_errors=True)
    print("\n| log | size [MiB] | rows | peak memory [MiB] | wall [s] | exit | outcome |")
    print("|---|---|---|---|---|---|---|")
    for name, size, n, _, r in rows:
        print(f"| {name} | {size / 2**20:.0f} | {n} | {r['rss_mib']:.0f} | {r['wall_s']:.1f} "
              f"| {r['rc']} | {r['said']} |")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
