"""Run the documentation's commands as separate processes without paying for a fresh
interpreter each time (tests/test_docs_examples.py).

A page's bash block runs in bash as written; each ``stripcoef`` and ``python`` command in it
is its own process, with the block's arguments, working folder, environment, stdin, stdout
and stderr, and its exit status goes back to bash.  What is shared is the start: a server
process imports Python, numpy, scipy, matplotlib and every module of the package once (and
draws one small figure: matplotlib loads its fonts on first use), and forks a copy of itself
for each command (``os.fork``: the copy's memory is the server's,
copied on write), so a command costs what it computes, not 0.5-1.5 s of imports.

- ``stripcoef ARGS`` (the shim :func:`write_shims` writes) runs ``python -m stripcoef ARGS``
  in the fork: ``sys.argv`` as ``-m`` sets it, ``SystemExit`` its exit status, an uncaught
  exception a traceback and status 1.
- ``python -c CODE ARGS`` and ``python SCRIPT ARGS`` (a script in the working folder) run the
  code or script as ``__main__`` in the fork; any other form of ``python`` execs the real
  interpreter.
- The server runs as ``python -c``: the first entry of its module path is ``''``, the working
  folder, which in a fork is the command's (the folder that ``-m``, ``-c`` and a script in
  the working folder put first).

The shim is a small client (``python -I -S``, about 20 ms): it passes its argv, working
folder and environment and its three file descriptors (SCM_RIGHTS) over a Unix socket, and
exits with the status it gets back.  The server forks a handler per connection, the handler
forks the command and waits for it (``pidfd``): a client that goes away (bash killed on a
timeout) takes its command with it.  Every process is waited for by its parent, so the
commands' CPU time adds up in the test's (``RUSAGE_CHILDREN``, ``time -v``).

Nothing is cached between commands in the server: each fork starts from its state, which
holds imported modules only (no computed results).  The hull's memoised pure functions (panel
levels, ...) read and write the test run's shared folder (tests/_shared_memo.py, installed in
the server before it imports the package), as the test processes do: a command gets the bits
its function computes, once per run.  So does ``diagnose()`` (``_shared_memo.share_diagnose``):
the tutorial's and diagnose.md's held-out diagnoses of the shipped sample are those of
tests/test_diagnose_written.py, computed once per run (its warnings issued again).  tests/test_docs_examples.py keeps one page on
fresh interpreters and checks that forks print what fresh interpreters and the installed
console script print.
"""

from __future__ import annotations

import json
import os
import select
import signal
import socket
import struct
import subprocess
import sys
import time
from pathlib import Path

#: imported by the server before it forks, besides every module of the package (what most
#: of the pages' commands import).  matplotlib.pyplot is not among them: a fork starts without
#: it, as a fresh interpreter does; nor are the heavy optional ones that one or two commands
#: import (capytaine, pandas): each test worker starts a server, and they would cost more there.
PRELOAD = ("numpy", "scipy.linalg", "scipy.integrate", "scipy.optimize", "scipy.interpolate",
           "scipy.stats", "scipy.special", "scipy.spatial", "yaml", "matplotlib",
           "matplotlib.figure", "matplotlib.backends.backend_agg", "concurrent.futures")

_HEADER = struct.Struct("!I")

CLIENT = '''\
import os, socket, struct, sys
if {kind!r} == "python" and not (
        (sys.argv[1:2] == ["-c"] and len(sys.argv) > 2)
        or (len(sys.argv) > 1 and not sys.argv[1].startswith("-")
            and os.path.dirname(os.path.abspath(sys.argv[1])) == os.getcwd())):
    os.execv(sys.executable, [sys.executable, *sys.argv[1:]])   # not a form the server runs
try:
    import json
    s = socket.socket(socket.AF_UNIX, socket.SOCK_STREAM)
    s.connect({sock!r})
    msg = json.dumps({{"kind": {kind!r}, "argv": sys.argv[1:], "cwd": os.getcwd(),
                      "env": dict(os.environ)}}).encode()
    socket.send_fds(s, [struct.pack("!I", len(msg)) + msg], [0, 1, 2])
    reply = b""
    while True:
        chunk = s.recv(64)
        if not chunk:
            break
        reply += chunk
    status = int(reply or b"1")
except KeyboardInterrupt:
    status = 130
sys.stdout.flush()
os._exit(status)
'''


def write_shims(folder: Path, sock: str) -> None:
    """``folder/stripcoef`` and ``folder/python``: clients of the server listening on ``sock``."""
    for kind in ("stripcoef", "python"):
        exe = folder / kind
        exe.write_text(f"#!{sys.executable} -IS\n" + CLIENT.format(sock=sock, kind=kind))
        exe.chmod(0o755)


def start(folder: Path, env: dict, timeout: float = 600.0):
    """Start the server in ``folder`` (its socket ``folder/s``) with ``env``; write the shims
    into ``folder``; return the server's ``Popen`` once it listens."""
    sock = str(folder / "s")
    for stale in (sock, sock + ".tmp", sock + ".cpu"):
        if os.path.exists(stale):
            os.unlink(stale)
    boot = f"import runpy, sys; sys.argv = ['-c', {sock!r}]; runpy.run_path({__file__!r}, run_name='__main__')"
    proc = subprocess.Popen([sys.executable, "-c", boot], env=env, cwd=folder,
                            stdin=subprocess.DEVNULL, stdout=subprocess.DEVNULL,
                            stderr=subprocess.PIPE, text=True)
    deadline = time.monotonic() + timeout
    while not os.path.exists(sock):
        if proc.poll() is not None:
            raise RuntimeError(f"the command server stopped: {proc.stderr.read()[-3000:]}")
        if time.monotonic() > deadline:
            proc.kill()
            raise RuntimeError("the command server did not start")
        time.sleep(0.05)
    write_shims(folder, sock)
    return proc


def commands_cpu(folder: Path) -> tuple:
    """(user, system) CPU seconds of the commands the server in ``folder`` has run so far
    (its finished handlers and their commands; measurement only)."""
    with socket.socket(socket.AF_UNIX, socket.SOCK_STREAM) as s:
        s.connect(str(folder / "s.cpu"))
        reply = b""
        while chunk := s.recv(256):
            reply += chunk
    user, system = reply.split()
    return float(user), float(system)


def stop(proc) -> None:
    proc.terminate()
    try:
        proc.wait(timeout=10)
    except subprocess.TimeoutExpired:
        proc.kill()
        proc.wait()
    proc.stderr.close()


# ---------------------------------------------------------------------------
# the server (run as ``python -c``, see :func:`start`)
# ---------------------------------------------------------------------------

def _receive(conn):
    """The request (a dict) and the client's three file descriptors."""
    data, fds, _, _ = socket.recv_fds(conn, 1 << 20, 3)
    while len(data) < _HEADER.size or len(data) < _HEADER.size + _HEADER.unpack_from(data)[0]:
        more = conn.recv(1 << 20)
        if not more:
            raise EOFError("the client went away")
        data += more
    n = _HEADER.unpack_from(data)[0]
    return json.loads(data[_HEADER.size:_HEADER.size + n]), fds


def _run_command(request: dict) -> int:
    """In the forked command process: run the request as its interpreter would; the exit
    status."""
    import runpy
    import traceback
    import types

    kind, argv = request["kind"], request["argv"]
    try:
        if kind == "stripcoef":
            sys.argv = [str(Path(__import__("stripcoef").__file__).parent / "__main__.py"),
                        *argv]
            runpy.run_module("stripcoef", run_name="__main__", alter_sys=True)
        elif argv[:1] == ["-c"] and len(argv) >= 2:
            sys.argv = ["-c", *argv[2:]]
            main = types.ModuleType("__main__")
            sys.modules["__main__"] = main
            exec(compile(argv[1], "<string>", "exec"), main.__dict__)
        else:
            script = argv[0]
            sys.argv = list(argv)
            runpy.run_path(script, run_name="__main__")
        return 0
    except SystemExit as exc:
        code = exc.code
        if code is None:
            return 0
        if isinstance(code, int):
            return code & 0xFF
        print(code, file=sys.stderr)
        return 1
    except KeyboardInterrupt:
        return 130
    except BaseException as exc:                     # as the interpreter: without this frame
        traceback.print_exception(type(exc), exc, exc.__traceback__.tb_next)
        return 1


def _command_process(request: dict, fds: list) -> None:
    """Become the command: its folder, environment and descriptors; never returns."""
    status = 1
    try:
        os.chdir(request["cwd"])
        os.environ.clear()
        os.environ.update(request["env"])
        for target, fd in enumerate(fds):
            os.dup2(fd, target)
            os.close(fd)
        # sys.stdin, stdout and stderr are the server's objects on descriptors 0, 1, 2, now
        # the client's (empty buffers: the server flushed them before forking; stdout block-
        # and stderr line-buffered, as a fresh interpreter's on pipes and files)
        status = _run_command(request)
        import atexit
        atexit._run_exitfuncs()
        try:
            sys.stdout.flush()
        except BrokenPipeError:
            pass
        sys.stderr.flush()
    finally:
        os._exit(status)


def _handle(conn) -> None:
    """In the handler process: fork the command, wait for it, send its status; never
    returns.  A client that hangs up kills the command."""
    try:
        signal.signal(signal.SIGCHLD, signal.SIG_DFL)
        signal.signal(signal.SIGTERM, signal.SIG_DFL)
        request, fds = _receive(conn)
        pid = os.fork()
        if pid == 0:
            conn.close()
            _command_process(request, fds)
        for fd in fds:
            os.close(fd)
        # wake when the command ends (a pidfd; else look every 50 ms) or the client hangs up
        pidfd = os.pidfd_open(pid) if hasattr(os, "pidfd_open") else None
        while True:
            watch = [conn] if pidfd is None else [pidfd, conn]
            ready, _, _ = select.select(watch, [], [], None if pidfd is not None else 0.05)
            done, wait = os.waitpid(pid, os.WNOHANG)
            if done:
                break
            if conn in ready and not conn.recv(1, socket.MSG_PEEK):
                os.kill(pid, signal.SIGKILL)           # the client is gone
                done, wait = os.waitpid(pid, 0)
                break
        status = os.waitstatus_to_exitcode(wait)
        status = 128 - status if status < 0 else status
        conn.sendall(str(status).encode())
    finally:
        os._exit(0)


def serve(sock: str) -> None:
    import importlib
    import importlib.util

    # the hull's memoised results shared with the test run's other processes (the run's own
    # folder, tests/_shared_memo.py), installed before the package's modules are imported
    spec = importlib.util.spec_from_file_location("_shared_memo",
                                                  Path(__file__).with_name("_shared_memo.py"))
    shared = importlib.util.module_from_spec(spec)
    sys.modules[spec.name] = shared             # what a shared value's pickle names
    spec.loader.exec_module(shared)
    shared.install()
    for name in PRELOAD:
        try:
            importlib.import_module(name)
        except ImportError:
            pass
    import pkgutil

    import stripcoef
    for info in pkgutil.walk_packages(stripcoef.__path__, "stripcoef.",
                                      onerror=lambda name: None):
        if info.name != "stripcoef.__main__":
            try:
                importlib.import_module(info.name)
            except ImportError:                      # an optional dependency missing
                pass
    # the diagnoses of the shipped sample that tests/test_diagnose_written.py runs too
    shared.share_diagnose()
    try:                        # load the fonts a figure draws with (once, not per --plot)
        import io

        from matplotlib.figure import Figure
        fig = Figure()
        ax = fig.add_subplot()
        ax.plot([0.0, 1.0])
        ax.set(xlabel="x [m]", title="t")
        fig.savefig(io.BytesIO(), format="png")
    except ImportError:
        pass
    # Every process is waited for by its parent (command by handler, handler by server, server
    # by the test): an ignored SIGCHLD would reap the handlers with their CPU time uncounted.
    signal.signal(signal.SIGCHLD, lambda *_: _reap(os.WNOHANG))
    signal.signal(signal.SIGTERM, lambda *_: sys.exit(0))
    import resource

    server, query = (socket.socket(socket.AF_UNIX, socket.SOCK_STREAM) for _ in range(2))
    query.bind(sock + ".cpu")
    query.listen(4)
    server.bind(sock + ".tmp")
    server.listen(16)
    os.rename(sock + ".tmp", sock)                   # the path exists once it listens
    try:
        while True:
            ready, _, _ = select.select([server, query], [], [])
            if query in ready:                       # the CPU of the commands so far
                conn, _ = query.accept()
                _reap(os.WNOHANG)
                used = resource.getrusage(resource.RUSAGE_CHILDREN)
                conn.sendall(f"{used.ru_utime} {used.ru_stime}".encode())
                conn.close()
            if server not in ready:
                continue
            conn, _ = server.accept()
            sys.stdout.flush()
            sys.stderr.flush()
            if os.fork() == 0:
                server.close()
                query.close()
                _handle(conn)
            conn.close()
    finally:
        signal.signal(signal.SIGCHLD, signal.SIG_DFL)
        server.close()
        query.close()
        _reap(0)


def _reap(flags: int) -> None:
    """Wait for the finished handlers (all of them with ``flags`` 0)."""
    while True:
        try:
            pid, _ = os.waitpid(-1, flags)
        except ChildProcessError:
            return
        if pid == 0:
            return


if __name__ == "__main__":
    serve(sys.argv[1])
