"""Atomic file output: write to a temporary file in the same folder, then rename.

A failed run never leaves a partial file, and an existing file is replaced only
by a complete new one.
"""

from __future__ import annotations

import json
import math
import os
import re
import shutil
import tempfile
from contextlib import contextmanager
from pathlib import Path

from stripcoef.errors import InputError, UnreachableError


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

    1. every staging folder gets a pointer to the journal's name (``.journal``);
    2. the journal (``.stripcoef-commit-<pid>-*.json`` in the first output's folder: every
       rename, source and destination) is written to a temporary name and renamed into place:
       this one atomic rename is the commit point;
    3. the staged files are renamed onto their destinations (each an atomic rename), the
       staging folders removed, the journal deleted.

    A kill -9 before step 2 leaves every earlier output as it was (and a staging folder); a
    kill -9 after it leaves a journal that completes the set. :func:`recover_outputs` finishes
    what a killed run left in a folder: it rolls a journal forward (the renames not yet done,
    then its staging folders and itself removed) and removes a staging folder of a dead process
    that no journal commits. It runs before a new set is staged in a folder and (roll-forward
    only) before :func:`read_text` reads a file, so the next run and every reader of the
    outputs see the whole new set or the whole old one. A staging folder or journal of a
    process that is still running is left alone (its run is not over). A failure before the
    commit (an error, a full disk) removes the staging folders at once. As a context manager it
    commits on success::

        with OutputSet() as outs:
            write_export(model, "yaml", outs.path("cal.yaml", key="out"))
            markdown_report(result, outs.path("report.md", key="report"))
        # both (and the report's plots) renamed here, or none
    """

    def __init__(self):
        self._staging: dict[Path, Path] = {}        # destination folder -> staging folder
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
                self._staging[folder] = Path(tempfile.mkdtemp(
                    prefix=f"{STAGING_PREFIX}{os.getpid()}-", suffix=".tmp", dir=folder))
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
        _roll_forward(journal, record)
        self._staging.clear()

    def discard(self) -> None:
        """Remove the staging folders and what they hold; no output changes."""
        for staging in self._staging.values():
            shutil.rmtree(staging, ignore_errors=True)
        self._staging.clear()

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
    moved), remove its staging folders, then the journal: idempotent, so a kill during it is
    finished by the next :func:`recover_outputs`."""
    for src, dst in record["moves"]:
        try:
            os.replace(src, dst)
        except FileNotFoundError:
            pass                                  # moved before the kill
    for staging in record["staging"]:
        shutil.rmtree(staging, ignore_errors=True)
    _discard(journal)


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
    """Whether process ``pid`` runs (this process counts as running)."""
    if pid == os.getpid():
        return True
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except OSError:                               # another user's process: it exists
        return True
    return True


def _owner(name: str, prefix: str):
    """The process id in a staging folder's or journal's name (None if it has none)."""
    head = name[len(prefix):].split("-", 1)[0]
    return int(head) if head.isdigit() else None


def recover_outputs(folder, *, roll_back: bool = True) -> None:
    """Finish what a killed :class:`OutputSet` left in ``folder``: roll every journal of a
    dead process forward (its set was committed), and (``roll_back``) remove every staging
    folder of a dead process that no journal commits (its set was not). Best effort: a folder
    that cannot be read or written is left as it is (the reader or writer then reports it)."""
    try:
        entries = [e for e in os.scandir(folder) if e.name.startswith(STAGING_PREFIX)]
    except OSError:
        return
    for e in entries:
        if not (e.name.startswith(JOURNAL_PREFIX) and e.name.endswith(".json")):
            continue
        pid = _owner(e.name, JOURNAL_PREFIX)
        if pid is not None and _pid_alive(pid):
            continue
        try:
            record = json.loads(Path(e.path).read_text())
            _roll_forward(Path(e.path), record)
        except (OSError, ValueError, KeyError, TypeError):
            continue
    if not roll_back:
        return
    for e in entries:
        if e.name.startswith(JOURNAL_PREFIX) and e.name.endswith(".part"):
            pid = _owner(e.name, JOURNAL_PREFIX)    # a journal not yet committed
            if pid is not None and not _pid_alive(pid):
                _discard(e.path)
            continue
        if not (e.name.endswith(".tmp") and e.is_dir()):
            continue
        pid = _owner(e.name, STAGING_PREFIX)
        if pid is None or _pid_alive(pid):
            continue
        journal = _journal_named(Path(e.path))
        if journal is not None and journal.is_file():
            try:
                _roll_forward(journal, json.loads(journal.read_text()))
            except (OSError, ValueError, KeyError, TypeError):
                pass
            continue
        shutil.rmtree(e.path, ignore_errors=True)


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
    """A SafeLoader class that refuses duplicate keys, nesting deeper than
    :data:`MAX_NESTING` and documents expanding past :data:`MAX_EXPANDED_NODES` nodes."""
    import yaml

    class Loader(yaml.SafeLoader):
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
