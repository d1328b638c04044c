"""Atomic file output: write to a temporary file in the same folder, then rename.

A failed run never leaves a partial file, and an existing file is replaced only
by a complete new one.
"""

from __future__ import annotations

import errno
import json
import math
import os
import re
import shutil
import tempfile
from contextlib import contextmanager
from pathlib import Path

from stripcoef.errors import InputError, UnreachableError

try:                        # POSIX advisory locks: the liveness of a run's staging folders
    import fcntl
except ImportError:         # (Windows): the process-id check alone, see _run_over
    fcntl = None


def _write_error(exc: OSError, path, key: str) -> InputError:
    """One line for a write that failed (a full disk, a read-only file system, a quota)."""
    return InputError(f"cannot write ({exc.strerror or exc.__class__.__name__}; the earlier "
                      "file, if any, is kept)", key=key, value=str(path),
                      expected="a path in a writable folder with free space")


def _discard(tmp) -> None:
    try:
        os.unlink(tmp)
    except OSError:
        pass


@contextmanager
def atomic_path(path, *, key: str = "output"):
    """Yield a temporary path next to ``path``; rename it onto ``path`` on success.

    A failure while writing (an ``OSError``: a full disk, a read-only file system) is one
    :class:`InputError` naming ``key`` and the path; the temporary file is removed and an
    existing ``path`` is left as it was.
    """
    path = check_output_path(path, key=key)
    tmp = _temporary(path, key)
    try:
        yield Path(tmp)
        os.chmod(tmp, _final_mode(path))
        os.replace(tmp, path)
    except OSError as exc:
        _discard(tmp)
        raise _write_error(exc, path, key) from None
    except BaseException:
        _discard(tmp)
        raise


def _temporary(path: Path, key: str) -> str:
    """A new empty temporary file next to ``path`` (same folder: the rename is atomic)."""
    folder = path.parent if str(path.parent) else Path(".")
    try:
        fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=folder)
    except OSError as exc:
        raise InputError(f"cannot write ({exc.strerror})", key=key, value=str(path),
                         expected="a path in an existing, writable folder") from None
    os.close(fd)
    return tmp


#: Name prefix of the staging folders and commit journals of :class:`OutputSet` (hidden).
STAGING_PREFIX = ".stripcoef-"
#: Name prefix of a commit journal (JSON: the renames of one committed set).
JOURNAL_PREFIX = ".stripcoef-commit-"
#: File in a staging folder naming the journal that commits it.
JOURNAL_POINTER = ".journal"


class OutputSet:
    """The outputs of one run written as a set: all new or all old, even after a kill -9.

    :meth:`path` gives, for each output, a path with the output's own name in a staging
    folder beside it (hidden, ``.stripcoef-<pid>-*.tmp``, on the same file system); the caller
    writes every output there with any writer, and files a writer adds beside its output
    (a report's plots) are staged with it. :meth:`commit` then commits the set with a
    write-ahead journal (the roll-forward recovery of database logs: Gray & Reuter,
    *Transaction Processing*, 1993, sec. 9.3):

    1. every staging folder gets a pointer to the journal's name (``.journal``, one line: a
       pointer that a kill cut short is no pointer, the set was not committed);
    2. the journal (``.stripcoef-commit-<pid>-*.json`` in the first output's folder: every
       rename, source and destination) is written to a temporary name and renamed into place:
       this one atomic rename is the commit point;
    3. the staged files are renamed onto their destinations (each an atomic rename), the
       journal deleted, the staging folders removed (then holding only the pointers).

    A kill -9 before step 2 leaves every earlier output as it was (and a staging folder); a
    kill -9 after it leaves a journal that completes the set. :func:`recover_outputs` finishes
    what a killed run left in a folder: it rolls a journal forward (the renames not yet done,
    then itself and its staging folders removed) and removes a staging folder of a run that is
    over that no journal commits. It runs before a new set is staged in a folder and
    (roll-forward only) before :func:`read_text` reads a file, so the next run and every reader
    of the outputs see the whole new set or the whole old one. A staging folder or journal of
    a process that is still running is left alone (its run is not over).

    Which run is over is told by a lock, not by the process id in the name: the writer holds
    an exclusive advisory lock (``flock``, POSIX) on each staging folder from the moment it
    makes it until the folder is removed, and the kernel drops the lock when the process ends,
    however it ends; a journal lives while the first staging folder does (it is deleted before
    that folder) and shares its lock. A process id can be reused by another process (it would
    make a dead run look alive) and a killed process that its parent has not yet reaped (a
    zombie) still answers ``kill(pid, 0)``; neither holds the lock (a child forked without exec
    while a set is open shares it: the run is over when both ended). Where locks are not
    available (no ``fcntl``: Windows; a file system that refuses ``flock`` on a folder) the
    process id is checked instead (:func:`_pid_alive`).

    A failure before the commit (an error, a full disk) removes the staging folders at once.
    As a context manager it commits on success::

        with OutputSet() as outs:
            write_export(model, "yaml", outs.path("cal.yaml", key="out"))
            markdown_report(result, outs.path("report.md", key="report"))
        # both (and the report's plots) renamed here, or none
    """

    def __init__(self):
        self._staging: dict[Path, Path] = {}        # destination folder -> staging folder
        self._locks: list[int] = []                  # descriptors holding the staging locks
        self._finals: dict[Path, tuple[Path, str]] = {}   # staged path -> (output, key)

    def path(self, path, *, key: str = "output") -> Path:
        """Where to write the output ``path`` (renamed onto it by :meth:`commit`)."""
        final = check_output_path(path, key=key)
        folder = (final.parent if str(final.parent) else Path(".")).resolve()
        if any(f.resolve() == final.resolve() for f, _ in self._finals.values()):
            raise InputError("the same file twice among a run's outputs", key=key,
                             value=str(path), expected="a different file for each output")
        if folder not in self._staging:
            recover_outputs(folder)
            try:
                self._staging[folder] = _new_staging(folder, self._locks)
            except OSError as exc:
                self.discard()
                raise _write_error(exc, final, key) from None
        staged = self._staging[folder] / final.name
        self._finals[staged] = (final, key)
        return staged

    def commit(self) -> None:
        """Commit the staged files onto their destinations (class docstring)."""
        if not self._staging:
            return
        moves = []
        for folder, staging in self._staging.items():
            final, key = next(iter(self._finals.values()), (folder, "output"))
            try:
                for f in sorted(staging.iterdir()):
                    final, key = self._finals.get(f, (folder / f.name, "output"))
                    os.chmod(f, _final_mode(folder / f.name))
                    moves.append((f, folder / f.name))
            except OSError as exc:          # also a staging folder removed under the run
                self.discard()
                raise _write_error(exc, final, key) from None
        first, staging0 = next(iter(self._staging.items()))
        # .stripcoef-<pid>-<random>.tmp -> .stripcoef-commit-<pid>-<random>.json
        journal = first / f"{JOURNAL_PREFIX}{staging0.name[len(STAGING_PREFIX):-4]}.json"
        record = {"pid": os.getpid(), "moves": [[str(a), str(b)] for a, b in moves],
                  "staging": [str(p) for p in self._staging.values()]}
        part = journal.with_name(journal.name + ".part")        # not yet a journal's name
        try:
            for staging in self._staging.values():
                (staging / JOURNAL_POINTER).write_text(str(journal) + "\n")
            part.write_text(json.dumps(record) + "\n")
            os.replace(part, journal)                            # the commit point
        except OSError as exc:
            _discard(part)
            self.discard()
            final, key = next(iter(self._finals.values()), (first, "output"))
            raise _write_error(exc, final, key) from None
        try:
            _roll_forward(journal, record)
        finally:                  # unlocked even if a rename failed: the next run finishes it
            self._staging.clear()
            self._unlock()

    def discard(self) -> None:
        """Remove the staging folders and what they hold; no output changes."""
        for staging in self._staging.values():
            shutil.rmtree(staging, ignore_errors=True)
        self._staging.clear()
        self._unlock()

    def _unlock(self) -> None:
        """Close the descriptors that hold the staging folders' locks (folders removed)."""
        while self._locks:
            os.close(self._locks.pop())

    def __enter__(self) -> "OutputSet":
        return self

    def __exit__(self, exc_type, exc, tb):
        if exc_type is None:
            self.commit()
            return False
        staged = {str(k): v for k, v in self._finals.items()}
        self.discard()
        if isinstance(exc, InputError) and str(exc.value) in staged:
            # a writer's error names the staged path: name the output instead
            final, key = staged[str(exc.value)]
            raise InputError(exc.what, file=exc.file, key=key, value=str(final),
                             expected=exc.expected) from None
        if isinstance(exc, OSError):
            final, key = staged.get(str(getattr(exc, "filename", "")),
                                    next(reversed(self._finals.values()), ("output", "output")))
            raise _write_error(exc, final, key) from None
        return False


def _roll_forward(journal: Path, record: dict) -> None:
    """Do the renames of a committed set that are not done yet (a staged file that is gone was
    moved), delete the journal, then remove its staging folders: idempotent, so a kill during
    it is finished by the next :func:`recover_outputs` (a staging folder left after its journal
    was deleted holds only its pointer, to a journal that is gone: it is removed)."""
    for src, dst in record["moves"]:
        try:
            os.replace(src, dst)
        except FileNotFoundError:
            pass                                  # moved before the kill
    _discard(journal)
    for staging in record["staging"]:
        shutil.rmtree(staging, ignore_errors=True)


#: Tries at making a staging folder that a recovery did not remove before it was locked.
STAGING_TRIES = 100


def _open_folder(path) -> int:
    """A read-only descriptor of the folder ``path`` (what its lock is taken on)."""
    return os.open(path, os.O_RDONLY | getattr(os, "O_DIRECTORY", 0))


def _lock(fd: int, *, wait: bool):
    """Take the exclusive advisory lock (``flock``) of the open folder ``fd``: True when taken,
    False when another open descriptor holds it (a running writer, or a recovery removing
    it), None when locks are not available here (no ``fcntl``; a file system that refuses
    ``flock``: ENOLCK, EOPNOTSUPP, EBADF for a folder on NFS)."""
    if fcntl is None:
        return None
    try:
        fcntl.flock(fd, fcntl.LOCK_EX | (0 if wait else fcntl.LOCK_NB))
    except BlockingIOError:
        return False
    except OSError:
        return None
    return True


def _new_staging(folder: Path, locks: list) -> Path:
    """A new staging folder in ``folder``, locked (its descriptor appended to ``locks``).

    Made by ``mkdtemp`` then locked: in between, a recovery in another process may find it
    unlocked and remove it (a recovery removes a folder only while it holds its lock). So the
    lock is taken waiting (a recovery holds it for the time of a removal), then the folder is
    checked to be still the one locked; if it is gone, another is made.
    """
    for _ in range(STAGING_TRIES):
        staging = Path(tempfile.mkdtemp(prefix=f"{STAGING_PREFIX}{os.getpid()}-",
                                        suffix=".tmp", dir=folder))
        try:
            fd = _open_folder(staging)
        except FileNotFoundError:
            continue                                # removed before it was opened
        if _lock(fd, wait=True) is None:
            os.close(fd)
            return staging                          # no locks here: the process id tells
        try:
            st, now = os.fstat(fd), os.stat(staging)
            kept = (st.st_dev, st.st_ino) == (now.st_dev, now.st_ino)
        except FileNotFoundError:
            kept = False
        if kept:
            locks.append(fd)
            return staging
        os.close(fd)
    raise OSError(errno.EAGAIN, "staging folders removed as they were made")


def _run_over(staging: Path, pid):
    """Whether the run that made the staging folder ``staging`` is over, and the descriptor
    that holds its lock (None if none; the caller closes it once it has recovered the folder,
    so that no other recovery works on it meanwhile).

    Over: the folder is gone (a journal outlives nothing of a running set), or its lock can be
    taken (the writer's process has ended: the kernel dropped its lock). Where locks are not
    available, the process id ``pid`` of its name is checked (:func:`_pid_alive`).
    """
    try:
        fd = _open_folder(staging)
    except FileNotFoundError:
        return True, None
    except OSError:
        return pid is not None and not _pid_alive(pid), None
    locked = _lock(fd, wait=False)
    if locked:
        return True, fd
    os.close(fd)
    if locked is None:
        return pid is not None and not _pid_alive(pid), None
    return False, None


def _release(fd) -> None:
    if fd is not None:
        os.close(fd)


def _journal_named(staging: Path):
    """The journal a staging folder's pointer names, or None: no pointer, or one that a kill
    cut short (empty, or without its final newline). The pointers are written before the
    commit point, so a set whose pointer is incomplete was not committed: it is rolled back.
    (An empty pointer read as ``Path("")`` is the current folder, which "exists": a staging
    folder was then never removed.)"""
    try:
        text = (staging / JOURNAL_POINTER).read_text()
    except (OSError, UnicodeDecodeError):
        return None
    journal = Path(text[:-1]) if text.endswith("\n") else None
    if journal is None or not (journal.is_absolute() and journal.name.startswith(JOURNAL_PREFIX)
                               and journal.name.endswith(".json")):
        return None
    return journal


def _pid_alive(pid: int) -> bool:
    """Whether process ``pid`` runs (this process counts as running): the check where locks
    are not available (:func:`_run_over`). A zombie (ended, not yet reaped by its parent) is
    not running (state Z in ``/proc/<pid>/stat``, Linux; proc(5)). A pid reused by another
    process still fools it: the folder is then recovered once that process ends. On Windows
    ``os.kill(pid, 0)`` is a Ctrl-C event, not a probe: every process counts as running there
    (nothing of a run is recovered, nothing of a running one removed)."""
    if pid == os.getpid() or os.name == "nt":
        return True
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except OSError:                               # another user's process: it exists
        return True
    try:
        with open(f"/proc/{pid}/stat", "rb") as f:
            stat = f.read()
        return stat[stat.rindex(b")") + 2:][:1] not in (b"Z", b"X")     # after "(comm) "
    except (OSError, ValueError):
        return True


def _owner(name: str, prefix: str):
    """The process id in a staging folder's or journal's name (None if it has none)."""
    head = name[len(prefix):].split("-", 1)[0]
    return int(head) if head.isdigit() else None


def _staging_of(journal_name: str, folder) -> Path:
    """The first staging folder of a journal (or ``.part``) named ``journal_name``: the same
    ``<pid>-<random>`` in the same folder (:meth:`OutputSet.commit`); its lock is the
    journal's."""
    stem = journal_name[len(JOURNAL_PREFIX):].split(".", 1)[0]
    return Path(folder) / f"{STAGING_PREFIX}{stem}.tmp"


def recover_outputs(folder, *, roll_back: bool = True) -> None:
    """Finish what a killed :class:`OutputSet` left in ``folder``: roll every journal of a
    run that is over forward (its set was committed), and (``roll_back``) remove every staging
    folder of a run that is over that no journal commits (its set was not). A run is over when
    its staging folder's lock is free (its process ended; :class:`OutputSet`), not when no
    process has its id. Best effort: a folder that cannot be read or written is left as it is
    (the reader or writer then reports it)."""
    try:
        entries = [e for e in os.scandir(folder) if e.name.startswith(STAGING_PREFIX)]
    except OSError:
        return
    for e in entries:
        pid = _owner(e.name, JOURNAL_PREFIX)
        if pid is None or not e.name.endswith(".json"):     # not a journal OutputSet names
            continue
        over, fd = _run_over(_staging_of(e.name, folder), pid)
        try:
            if over:
                _roll_forward(Path(e.path), json.loads(Path(e.path).read_text()))
        except (OSError, ValueError, KeyError, TypeError):
            pass
        finally:
            _release(fd)
    if not roll_back:
        return
    for e in entries:
        if e.name.startswith(JOURNAL_PREFIX):
            pid = _owner(e.name, JOURNAL_PREFIX)
            if pid is not None and e.name.endswith(".part"):    # a journal not yet committed
                over, fd = _run_over(_staging_of(e.name, folder), pid)
                if over:
                    _discard(e.path)
                _release(fd)
            continue
        pid = _owner(e.name, STAGING_PREFIX)
        if pid is None or not (e.name.endswith(".tmp") and e.is_dir()):
            continue
        over, fd = _run_over(Path(e.path), pid)
        try:
            if not over:
                continue
            journal = _journal_named(Path(e.path))
            if journal is not None and journal.is_file():
                try:
                    _roll_forward(journal, json.loads(journal.read_text()))
                except (OSError, ValueError, KeyError, TypeError):
                    pass
                continue
            shutil.rmtree(e.path, ignore_errors=True)
        finally:
            _release(fd)


def _final_mode(path: Path) -> int:
    """Permissions of the new file: those of the file it replaces, else 0o666 minus the umask
    (mkstemp's temporary files are 0o600, which would hide exports from other users)."""
    try:
        return path.stat().st_mode & 0o7777
    except OSError:
        mask = os.umask(0)
        os.umask(mask)
        return 0o666 & ~mask


def write_text(path, text: str, *, key: str = "output") -> None:
    """Write ``text`` to ``path`` atomically."""
    with atomic_path(path, key=key) as tmp:
        tmp.write_text(text)


def write_bytes(path, data: bytes, *, key: str = "output") -> None:
    """Write ``data`` to ``path`` atomically."""
    with atomic_path(path, key=key) as tmp:
        tmp.write_bytes(data)


#: Largest text file read [bytes] (256 MiB). Files are read whole and parsed in memory, at
#: about ten times their size (a 1 GB CSV log took 11.2 GB): a larger one is refused before
#: any byte is read, with the remedy. A one-hour 6-DOF log at 20 Hz is about 20 MB.
MAX_TEXT_BYTES = 256 * 2**20


def check_size(path, *, kind: str) -> None:
    """Refuse a file over :data:`MAX_TEXT_BYTES` before a byte of it is read (its size, the
    limit and the remedy); first finish a killed run's output set in its folder
    (:func:`recover_outputs`, roll-forward only)."""
    path = Path(path)
    recover_outputs(path.parent if str(path.parent) else ".", roll_back=False)
    try:
        size = path.stat().st_size
    except OSError:
        return                            # reported by the read that fails
    if size > MAX_TEXT_BYTES and path.is_file():
        raise InputError(f"too large to read ({size / 2**20:.0f} MiB)", file=str(path),
                         expected=f"a {kind} of at most {MAX_TEXT_BYTES // 2**20} MiB: split it "
                                  "into shorter logs (chunk files of a column map are read one "
                                  "at a time) or decimate it")


def read_text(path, *, kind: str) -> str:
    """Read a UTF-8 text file; a missing or unreadable file is an InputError naming it.

    ``kind`` says what the file should be ("vehicle file", "CSV log", ...). A file over
    :data:`MAX_TEXT_BYTES` is refused up front (:func:`check_size`).
    """
    path = Path(path)
    check_size(path, kind=kind)
    try:
        return path.read_text()
    except FileNotFoundError:
        raise InputError("file not found", file=str(path), expected=f"an existing {kind}") from None
    except IsADirectoryError:
        raise InputError("is a folder", file=str(path), expected=f"a {kind}") from None
    except UnicodeDecodeError as exc:
        data = path.read_bytes()
        line = data.count(b"\n", 0, exc.start) + 1
        raise InputError(f"not UTF-8 text (byte 0x{data[exc.start]:02x} at offset {exc.start})",
                         file=str(path), key=f"line {line}",
                         expected=f"a UTF-8 {kind}") from None
    except OSError as exc:
        raise InputError(f"cannot read ({exc.strerror or exc.__class__.__name__})",
                         file=str(path), expected=f"a readable {kind}") from None


def strict_json(value):
    """``value`` with every non-finite float (``inf``, ``nan``) replaced by ``None``.

    The one encoding of non-finite values in stripcoef's JSON (docs/conventions.md): ``null``.
    A thruster without a limit (``max_forward = inf``) is written ``null`` and read back as
    ``inf``; Python's ``Infinity``/``NaN`` literals are not JSON (RFC 8259, sec. 6) and strict
    parsers (JavaScript's ``JSON.parse``) reject them. numpy scalars and arrays become plain
    Python numbers and lists.
    """
    if isinstance(value, dict):
        return {str(k): strict_json(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [strict_json(v) for v in value]
    if hasattr(value, "tolist") and not isinstance(value, (str, bytes)):  # numpy array/scalar
        return strict_json(value.tolist())
    if isinstance(value, float) and not math.isfinite(value):
        return None
    return value


def json_text(value, *, indent: int | None = 2) -> str:
    """Strict JSON text of ``value`` (non-finite numbers as ``null``, see :func:`strict_json`),
    ending with a newline."""
    return json.dumps(strict_json(value), indent=indent, allow_nan=False) + "\n"


# ---------------------------------------------------------------------------
# Bounded parsing: the one place where YAML and JSON text becomes Python data
# ---------------------------------------------------------------------------

#: Deepest nesting of mappings/lists accepted in a YAML or JSON input file (a vehicle file
#: nests 4 levels; a 10,000-deep file would exhaust Python's recursion limit).
MAX_NESTING = 64
#: Most nodes a YAML file may expand to once its aliases are followed (an "alias bomb" of a
#: few lines expands to 1e8 nodes and more); a vehicle file has a few hundred.
MAX_EXPANDED_NODES = 100_000
#: Largest input text read as YAML or JSON [characters] (a vehicle file is a few kB).
MAX_TEXT = 50_000_000


def _yaml_loader(file: str):
    """A safe loader class that refuses duplicate keys, nesting deeper than
    :data:`MAX_NESTING` and documents expanding past :data:`MAX_EXPANDED_NODES` nodes.

    The scanner and parser are libyaml's (PyYAML's ``CParser``) when PyYAML was built with
    it, else PyYAML's pure-Python ones (``yaml.SafeLoader``); the composer, the resolver and
    the safe constructor stay PyYAML's Python classes in both cases, so the checks below and
    the line numbers of the marks are the same. The C parser makes a vehicle file's parse
    several times faster (docs/performance.md, "YAML parsing").
    """
    import yaml

    if getattr(yaml, "__with_libyaml__", False):
        from yaml.composer import Composer
        from yaml.constructor import SafeConstructor
        from yaml.cyaml import CParser
        from yaml.resolver import Resolver

        class Base(Composer, CParser, SafeConstructor, Resolver):
            """libyaml's events, PyYAML's Python composer (first in the MRO: its
            ``compose_node`` is the one overridden below) and safe constructor."""

            def __init__(self, stream):
                bad = yaml.reader.Reader.NON_PRINTABLE.search(stream)  # as the Python reader
                if bad:
                    raise yaml.reader.ReaderError("<unicode string>", bad.start(),
                                                  ord(bad.group()), "unicode",
                                                  "special characters are not allowed")
                CParser.__init__(self, stream)
                Composer.__init__(self)
                SafeConstructor.__init__(self)
                Resolver.__init__(self)
    else:                                                   # pragma: no cover
        Base = yaml.SafeLoader

    class Loader(Base):
        depth = 0

        def __init__(self, stream):
            self.anchor_of: dict[int, str] = {}
            super().__init__(stream)

        def compose_node(self, parent, index):
            if self.check_event(yaml.AliasEvent):
                return super().compose_node(parent, index)
            anchor = self.peek_event().anchor
            self.depth += 1
            if self.depth > MAX_NESTING:
                mark = self.peek_event().start_mark
                raise InputError("nesting too deep", file=file, key=f"line {mark.line + 1}",
                                 value=self.depth, expected=f"at most {MAX_NESTING} levels "
                                 "of mappings and lists")
            try:
                node = super().compose_node(parent, index)
            finally:
                self.depth -= 1
            if anchor is not None:
                self.anchor_of[id(node)] = anchor       # named in a recursive-alias error
            return node

        def construct_mapping(self, node, deep=False):
            seen = {}
            for key_node, _ in node.value:
                if isinstance(key_node, yaml.ScalarNode):
                    k = key_node.value
                    if k in seen:
                        raise InputError("duplicate key", file=file,
                                         key=f"line {key_node.start_mark.line + 1}", value=k,
                                         expected=f"each key once in a mapping (first on line "
                                                  f"{seen[k]})")
                    seen[k] = key_node.start_mark.line + 1
            return super().construct_mapping(node, deep=deep)

    return Loader


def _node_children(node) -> list:
    """The child nodes of a composed YAML node (keys and values of a mapping)."""
    import yaml

    if isinstance(node, yaml.SequenceNode):
        return list(node.value)
    if isinstance(node, yaml.MappingNode):
        return [c for kv in node.value for c in kv]
    return []


def _expanded_size(node, limit: int, file: str, anchors=None) -> int:
    """Nodes of a composed YAML document with every alias followed, without building it.

    A depth-first walk of the node graph (iterative, so a deep graph cannot exhaust the
    stack) in true post-order: a node's size is known before any node that refers to it, a
    shared node is walked once and counted each time it is referenced. A node reached again
    while it is still being walked is a recursive alias (``&a [*a]``): an error, since its
    expansion is infinite (and building it would make every later walk recurse forever).
    The walk stops at the first node whose expansion passes ``limit``, so a "wide" alias
    bomb (thousands of references to one large anchor, or merge keys ``<<: *a``) costs the
    size of its text, not of its expansion.
    """
    sizes: dict[int, int] = {}
    open_: set[int] = set()                       # nodes on the current path of the walk
    stack: list = [(node, False)]
    while stack:
        n, done = stack.pop()
        key = id(n)
        if done:
            open_.discard(key)
            total = 1 + sum(sizes[id(c)] for c in _node_children(n))
            if total > limit:
                raise InputError("document too large once its aliases are expanded",
                                 file=file, key=f"line {n.start_mark.line + 1}",
                                 value=f"> {limit} nodes",
                                 expected=f"at most {limit} nodes (few or no YAML aliases)")
            sizes[key] = total
            continue
        if key in sizes:
            continue
        if key in open_:
            raise InputError("recursive alias (a node that contains itself)", file=file,
                             key=f"line {n.start_mark.line + 1}",
                             value=f"&{(anchors or {}).get(key, '?')}",
                             expected="aliases that refer to nodes defined before, outside "
                                      "themselves")
        open_.add(key)
        stack.append((n, True))
        stack.extend((c, False) for c in _node_children(n) if id(c) not in sizes)
    return sizes[id(node)]


def load_yaml(text: str, *, file: str):
    """Parse YAML text safely: no duplicate keys, bounded nesting and alias expansion.

    Raises an :class:`InputError` naming ``file`` and the line for invalid YAML, a duplicate
    key, nesting deeper than :data:`MAX_NESTING` or more than :data:`MAX_EXPANDED_NODES`
    nodes once aliases are followed.
    """
    import yaml

    if len(text) > MAX_TEXT:
        raise InputError("file too large", file=file, value=f"{len(text)} characters",
                         expected=f"at most {MAX_TEXT} characters")
    loader = None
    try:
        loader = _yaml_loader(file)(text)      # the reader refuses unprintable characters here
        node = loader.get_single_node()
        if node is None:
            return None
        _expanded_size(node, MAX_EXPANDED_NODES, file, loader.anchor_of)
        return loader.construct_document(node)
    except yaml.reader.ReaderError as exc:
        # a NUL byte or another character YAML does not allow (YAML 1.1, sec. 5.1)
        line = text.count("\n", 0, exc.position) + 1
        raise InputError("invalid YAML (a character YAML does not allow)", file=file,
                         key=f"line {line}", value=chr(exc.character) if isinstance(
                             exc.character, int) else exc.character,
                         expected="printable text (no NUL or control characters)") from None
    except yaml.YAMLError as exc:
        mark = getattr(exc, "problem_mark", None)
        problem = getattr(exc, "problem", None) or "syntax error"
        if "maximum nesting depth" in problem:      # libyaml's own limit (1000 levels)
            raise InputError("nesting too deep", file=file,
                             key=f"line {mark.line + 1}" if mark is not None else None,
                             value=f"> {MAX_NESTING}", expected=f"at most {MAX_NESTING} "
                             "levels of mappings and lists") from None
        raise InputError(f"invalid YAML ({problem})", file=file,
                         key=f"line {mark.line + 1}" if mark is not None else None,
                         expected="a YAML mapping") from None
    finally:
        if loader is not None:
            loader.dispose()


def load_json(text: str, *, file: str):
    """Parse JSON text with nesting bounded by :data:`MAX_NESTING`; errors name the line."""

    if len(text) > MAX_TEXT:
        raise InputError("file too large", file=file, value=f"{len(text)} characters",
                         expected=f"at most {MAX_TEXT} characters")
    depth = _json_depth(text)
    if depth > MAX_NESTING:
        raise InputError("nesting too deep", file=file, value=depth,
                         expected=f"at most {MAX_NESTING} levels of objects and arrays")
    try:
        return json.loads(text)   # Infinity is kept (an unlimited thrust); schemas check finiteness
    except json.JSONDecodeError as exc:
        raise InputError(f"invalid JSON ({exc.msg})", file=file,
                         key=f"line {exc.lineno}", expected="a JSON object") from None


def _json_depth(text: str) -> int:
    """Deepest bracket nesting of JSON text, brackets inside strings ignored."""

    # strings (with their escapes) removed, then the running count of [{ minus ]}
    stripped = re.sub(r'"(?:[^"\\]|\\.)*"', '""', text)
    depth = best = 0
    for ch in re.sub(r"[^\[\]{}]", "", stripped):
        depth += 1 if ch in "[{" else -1
        best = max(best, depth)
    return best


# ---------------------------------------------------------------------------
# Output paths and output values
# ---------------------------------------------------------------------------

def check_output_path(path, *, key: str = "output") -> Path:
    """An output path a command can write: not a folder, in an existing writable folder.

    Called before any work (the CLI checks every output option first) and again by
    :func:`atomic_path`; raises an :class:`InputError` naming ``key`` and the path.
    """
    text = str(path)
    p = Path(text)
    expected = "a file path in an existing, writable folder"
    if not text or text.endswith(("/", os.sep)) or p.is_dir() or p.name in ("", ".", ".."):
        raise InputError("is a folder", key=key, value=text, expected=expected)
    folder = p.parent if str(p.parent) else Path(".")
    if not folder.is_dir():
        raise InputError("folder does not exist", key=key, value=text, expected=expected)
    if not os.access(folder, os.W_OK | os.X_OK) or (p.exists() and not os.access(p, os.W_OK)):
        raise InputError("not writable", key=key, value=text, expected=expected)
    return p


def first_non_finite(value, path: str = ""):
    """The key path of the first NaN or infinite number in nested dicts/lists/arrays, or None.

    Used at the output boundary: no command writes or prints a non-finite result.
    """
    import numpy as np

    stack = [(path, value)]
    while stack:
        where, v = stack.pop()
        if isinstance(v, bool) or v is None or isinstance(v, (str, bytes)):
            continue
        if isinstance(v, dict):
            stack.extend((f"{where}.{k}" if where else str(k), x) for k, x in
                         reversed(list(v.items())))
        elif isinstance(v, (list, tuple)):
            stack.extend((f"{where}[{i}]", x) for i, x in reversed(list(enumerate(v))))
        elif isinstance(v, np.ndarray):
            if v.dtype.kind in "fc" and not np.all(np.isfinite(v)):
                k = int(np.flatnonzero(~np.isfinite(v.reshape(-1)))[0])
                return f"{where}[{', '.join(map(str, np.unravel_index(k, v.shape)))}]"
            if v.dtype == object:
                stack.extend((f"{where}[{i}]", x) for i, x in enumerate(v.reshape(-1)))
        elif isinstance(v, (float, np.floating, complex, np.complexfloating)):
            if not np.isfinite(v):
                return where or "value"
    return None


def check_finite_output(value, *, what: str, file: str | None = None) -> None:
    """Refuse to write or print a result holding a NaN or an infinity.

    The one output check of the commands: ``value`` is the result as it is about to be written
    (nested dicts, lists, arrays); the first non-finite number is reported with its key path.
    """
    where = first_non_finite(value)
    if where is not None:

        raise UnreachableError(f"{file + ': ' if file else ''}{where}: {what} is not finite; "
                               "expected finite numbers (nothing written: the input leads "
                               "outside the range where the model holds; check its magnitudes)")
