"""Atomic file output: write to a temporary file in the same folder, then rename.

A failed run never leaves a partial file, and an existing file is replaced only
by a complete new one.
"""

from __future__ import annotations

import json
import math
import os
import tempfile
from contextlib import contextmanager
from pathlib import Path

from stripcoef.errors import InputError


@contextmanager
def atomic_path(path, *, key: str = "output"):
    """Yield a temporary path next to ``path``; rename it onto ``path`` on success."""
    path = Path(path)
    folder = path.parent if str(path.parent) else Path(".")
    if not folder.is_dir():
        raise InputError("folder does not exist", key=key, value=str(path),
                         expected="a path in an existing, writable folder")
    try:
        fd, tmp = tempfile.mkstemp(prefix=f".{path.name}.", suffix=".tmp", dir=folder)
    except OSError as exc:
        raise InputError(f"cannot write ({exc.strerror})", key=key, value=str(path),
                         expected="a path in an existing, writable folder") from None
    os.close(fd)
    try:
        yield Path(tmp)
        os.chmod(tmp, _final_mode(path))
        os.replace(tmp, path)
    except BaseException:
        try:
            os.unlink(tmp)
        except OSError:
            pass
        raise


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


def read_text(path, *, kind: str) -> str:
    """Read a UTF-8 text file; a missing or unreadable file is an InputError naming it.

    ``kind`` says what the file should be ("vehicle file", "CSV log", ...).
    """
    path = Path(path)
    try:
        return path.read_text()
    except FileNotFoundError:
        raise InputError("file not found", file=str(path), expected=f"an existing {kind}") from None
    except IsADirectoryError:
        raise InputError("is a folder", file=str(path), expected=f"a {kind}") from None
    except (OSError, UnicodeDecodeError) as exc:
        raise InputError(f"cannot read ({exc.__class__.__name__})", file=str(path),
                         expected=f"a readable UTF-8 {kind}") from None


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
