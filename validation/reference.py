"""Published reference tables (``reference_tables/<source>/*.csv``) as validated data.

Every table is a CSV file whose leading ``#`` lines are its caption and citation, followed by
a header row with the columns in :data:`COLUMNS`.  Each row is one published (or derived)
number:

``name``
    unique within the source folder (e.g. ``X_udot.analytical``, ``surge.K_Q.scaled``);
``value``
    the number as printed (kept verbatim in ``value_text``; ``value`` is its float);
``unit``
    SI unit in ASCII (``kg*m^2``, ``N*s^2/m^2``; ``1`` for dimensionless);
``sign_convention``
    how the printed sign maps to SNAME / Fossen (e.g. "magnitude as printed; SNAME
    X_udot = -value");
``provenance``
    ``read`` (from the paper, ``source`` gives the table/equation), ``computed`` (from read
    values, ``formula`` gives the expression), ``assumed`` or ``assumed (unverified)``
    (``note`` says why);
``source``, ``formula``, ``note``
    where the number comes from, how a computed number is derived, remarks;
``rtol``, ``atol``, ``tolerance_reason``
    the tolerance a comparison against this row uses, and why (empty when unused).

A ``formula`` is an arithmetic expression in which ``{other.name}`` stands for the value of
another row of the same source; :func:`recompute` evaluates it (``+ - * / **``, ``abs``,
``sqrt``, ``log``, ``log10``, ``exp``, ``min``, ``max`` only).

The tables are documented in ``docs/reference-tables.md``.
"""

from __future__ import annotations

import ast
import csv
import difflib
import math
import os
import re
from dataclasses import dataclass
from functools import lru_cache
from pathlib import Path

from stripcoef.errors import InputError

#: Columns every reference table has, in this order.
COLUMNS: tuple[str, ...] = ("name", "value", "unit", "sign_convention", "provenance", "source",
                            "formula", "rtol", "atol", "tolerance_reason", "note")

#: Allowed provenance tags.
PROVENANCE: tuple[str, ...] = ("read", "computed", "assumed", "assumed (unverified)")

_REF = re.compile(r"\{([^{}]+)\}")
_FUNCS = {"abs": abs, "sqrt": math.sqrt, "log": math.log, "log10": math.log10, "exp": math.exp,
          "min": min, "max": max}


def reference_dir() -> Path:
    """Folder holding the reference tables.

    ``$STRIPCOEF_REFERENCE_DIR`` if set, else ``reference_tables/`` at the root of the source
    checkout (:data:`validation.ROOT`).
    """
    env = os.environ.get("STRIPCOEF_REFERENCE_DIR")
    if env:
        return Path(env)
    from validation import ROOT

    return ROOT / "reference_tables"


def _root(root) -> Path:
    path = Path(root) if root is not None else reference_dir()
    if not path.is_dir():
        raise InputError("reference tables folder not found", file=str(path),
                         expected="the reference_tables/ folder of a stripcoef checkout "
                                  "(or set STRIPCOEF_REFERENCE_DIR)")
    return path


def sources(*, root=None) -> list[str]:
    """Names of the source folders (``videoray_pro3``, ``rov2``, ...)."""
    base = _root(root)
    return sorted(p.name for p in base.iterdir() if p.is_dir() and not p.name.startswith((".", "_")))


def tables(source: str, *, root=None) -> list[str]:
    """Names (file stems) of the CSV tables of one source."""
    base = _root(root)
    folder = base / source
    try:
        changed = folder.stat().st_mtime_ns if folder.is_dir() else None
    except OSError:
        changed = None
    if changed is None:
        raise InputError("unknown reference source", file=str(base), value=source,
                         expected="one of " + ", ".join(sources(root=base)))
    return list(_table_names(str(folder), changed))


@lru_cache(maxsize=None)
def _table_names(folder: str, changed: int) -> tuple[str, ...]:
    """The CSV stems in ``folder`` as of its modification time ``changed`` [ns] (a table added
    or removed changes the folder's time, and a new listing is made): one listing instead of
    a glob per :func:`reference_value` (the lift section looks up about 100,000 values: 10 s
    of CPU in globs)."""
    return tuple(sorted(p.stem for p in Path(folder).glob("*.csv")))


def _number(text: str, *, file: str, key: str, required: bool):
    text = text.strip()
    if not text:
        if required:
            raise InputError("missing number", file=file, key=key, expected="a number")
        return None
    try:
        value = float(text)
    except ValueError:
        raise InputError("not a number", file=file, key=key, value=text, expected="a number") from None
    if not math.isfinite(value):
        raise InputError("not a finite number", file=file, key=key, value=text, expected="a finite number")
    return value


@lru_cache(maxsize=None)
def _read_table(path: str) -> tuple[tuple[str, ...], tuple[dict, ...]]:
    header: list[str] = []
    body: list[str] = []
    with open(path, newline="", encoding="utf-8") as fh:
        for line in fh:
            if not body and line.startswith("#"):
                header.append(line[1:].strip())
            else:
                body.append(line)
    reader = csv.DictReader(body)
    columns = tuple(reader.fieldnames or ())
    if columns != COLUMNS:
        raise InputError("wrong header row", file=path, key="header", value=",".join(columns),
                         expected=",".join(COLUMNS))
    rows = []
    stem = Path(path).stem
    for i, raw in enumerate(reader, start=len(header) + 2):
        where = f"line {i}"
        if None in raw or any(v is None for v in raw.values()):
            raise InputError("wrong number of fields", file=path, key=where, expected=f"{len(COLUMNS)} fields")
        name = raw["name"].strip()
        if not name:
            raise InputError("empty name", file=path, key=where, expected="a row name")
        row = {k: raw[k].strip() for k in COLUMNS}
        row["value_text"] = row["value"]
        row["value"] = _number(row["value"], file=path, key=f"{where} ({name}).value", required=True)
        for tol in ("rtol", "atol"):
            row[tol] = _number(row[tol], file=path, key=f"{where} ({name}).{tol}", required=False)
            if row[tol] is not None and row[tol] < 0:
                raise InputError("negative tolerance", file=path, key=f"{where} ({name}).{tol}",
                                 value=row[tol], expected=">= 0")
        if not row["unit"]:
            raise InputError("missing unit", file=path, key=f"{where} ({name}).unit",
                             expected="an SI unit, or 1 for dimensionless")
        if row["provenance"] not in PROVENANCE:
            raise InputError("unknown provenance", file=path, key=f"{where} ({name}).provenance",
                             value=row["provenance"], expected="one of " + ", ".join(PROVENANCE))
        if row["provenance"] == "computed" and not row["formula"]:
            raise InputError("computed row without formula", file=path, key=f"{where} ({name}).formula",
                             expected="the expression it was computed with")
        if row["provenance"] == "read" and not row["source"]:
            raise InputError("read row without source", file=path, key=f"{where} ({name}).source",
                             expected="the table/equation/section it was read from")
        if row["provenance"].startswith("assumed") and not row["note"]:
            raise InputError("assumed row without reason", file=path, key=f"{where} ({name}).note",
                             expected="why the value is assumed")
        if (row["rtol"] is not None or row["atol"] is not None) and not row["tolerance_reason"]:
            raise InputError("tolerance without reason", file=path, key=f"{where} ({name}).tolerance_reason",
                             expected="the reason for the tolerance")
        row["table"] = stem
        row["line"] = i
        rows.append(row)
    return tuple(header), tuple(rows)


def _table_path(source: str, name: str, root) -> Path:
    base = _root(root)
    available = tables(source, root=base)
    if name not in available:
        raise InputError("unknown reference table", file=str(base / source), value=name,
                         expected="one of " + ", ".join(available))
    return base / source / f"{name}.csv"


def load_table(source: str, name: str, *, root=None) -> list[dict]:
    """Rows of ``reference_tables/<source>/<name>.csv`` as dicts (copies; safe to modify).

    ``value``, ``rtol``, ``atol`` are floats (tolerances ``None`` when empty); ``value_text``
    keeps the number as printed; ``table`` and ``line`` say where the row is.

    Raises
    ------
    InputError
        unknown source or table (listing those that exist), or a malformed file.
    """
    _, rows = _read_table(str(_table_path(source, name, root)))
    return [dict(r) for r in rows]


def table_caption(source: str, name: str, *, root=None) -> list[str]:
    """The ``#`` comment lines (caption, citation, notes) at the top of a table."""
    header, _ = _read_table(str(_table_path(source, name, root)))
    return list(header)


def _index(source: str, root) -> dict[str, dict]:
    """Every row of ``source`` by name (read-only: callers copy a row before handing it out),
    built once per set of tables (the tables' contents are read once already,
    :func:`_read_table`)."""
    base = _root(root)
    return _index_of(source, str(base), tuple(tables(source, root=base)))


@lru_cache(maxsize=None)
def _index_of(source: str, root: str, names: tuple) -> dict[str, dict]:
    out: dict[str, dict] = {}
    for t in names:
        for row in load_table(source, t, root=root):
            if row["name"] in out:
                first = out[row["name"]]
                raise InputError("duplicate row name in source", file=f"{source}/{t}.csv",
                                 key=f"line {row['line']}", value=row["name"],
                                 expected=f"a name unique in {source}/ (also in {first['table']}.csv)")
            out[row["name"]] = row
    return out


def reference_value(source: str, name: str, *, root=None) -> dict:
    """The row called ``name`` in any table of ``source``.

    Raises
    ------
    InputError
        if the source or the row does not exist; the message lists the closest names and the
        tables of the source.
    """
    index = _index(source, root)
    if name not in index:
        close = difflib.get_close_matches(name, list(index), n=8, cutoff=0.5)
        hint = ("closest: " + ", ".join(close) + "; ") if close else ""
        raise InputError("unknown reference value", file=f"{source}/", value=name,
                         expected=f"a row name ({hint}{len(index)} names in tables "
                                  + ", ".join(tables(source, root=root)) + ")")
    return dict(index[name])


def _eval_node(node, *, expr: str):
    if isinstance(node, ast.Expression):
        return _eval_node(node.body, expr=expr)
    if isinstance(node, ast.Constant) and isinstance(node.value, (int, float)):
        return float(node.value)
    if isinstance(node, ast.UnaryOp) and isinstance(node.op, (ast.USub, ast.UAdd)):
        v = _eval_node(node.operand, expr=expr)
        return -v if isinstance(node.op, ast.USub) else v
    if isinstance(node, ast.BinOp):
        a, b = _eval_node(node.left, expr=expr), _eval_node(node.right, expr=expr)
        ops = {ast.Add: lambda: a + b, ast.Sub: lambda: a - b, ast.Mult: lambda: a * b,
               ast.Div: lambda: a / b, ast.Pow: lambda: a ** b}
        for op, fn in ops.items():
            if isinstance(node.op, op):
                return fn()
    if (isinstance(node, ast.Call) and isinstance(node.func, ast.Name) and node.func.id in _FUNCS
            and not node.keywords):
        return float(_FUNCS[node.func.id](*[_eval_node(a, expr=expr) for a in node.args]))
    raise InputError("unsupported formula syntax", key="formula", value=expr,
                     expected="numbers, {row.name}, + - * / **, abs sqrt log log10 exp min max")


def evaluate(source: str, expression: str, *, root=None) -> float:
    """Value of an arithmetic ``expression`` whose ``{name}`` placeholders are rows of ``source``."""
    index = _index(source, root)

    def sub(match):
        name = match.group(1).strip()
        if name not in index:
            reference_value(source, name, root=root)  # raises with the listing
        return repr(index[name]["value"])

    text = _REF.sub(sub, expression)
    try:
        tree = ast.parse(text, mode="eval")
    except SyntaxError:
        raise InputError("formula is not an expression", key="formula", value=expression,
                         expected="an arithmetic expression") from None
    return _eval_node(tree, expr=expression)


def recompute(source: str, name: str, *, root=None) -> float:
    """Evaluate the ``formula`` of the computed row ``name`` from the values it references."""
    row = reference_value(source, name, root=root)
    if row["provenance"] != "computed":
        raise InputError("row is not computed", file=f"{source}/{row['table']}.csv", key=name,
                         value=row["provenance"], expected="provenance 'computed'")
    return evaluate(source, row["formula"], root=root)


def printed_precision(value_text: str) -> float:
    """Half a unit in the last printed digit of a number as printed (``"21.42"`` -> 0.005)."""
    text = value_text.strip().lower()
    mantissa, _, exponent = text.partition("e")
    decimals = len(mantissa.split(".")[1]) if "." in mantissa else 0
    return 0.5 * 10.0 ** (-decimals + (int(exponent) if exponent else 0))


def agrees(row: dict, value: float) -> bool:
    """True if ``value`` is within the row's tolerance: ``|value - v| <= atol + rtol*|v|``.

    A row without a tolerance uses its printed precision.
    """
    atol = row.get("atol")
    rtol = row.get("rtol")
    if atol is None and rtol is None:
        atol = printed_precision(row["value_text"])
    return abs(value - row["value"]) <= (atol or 0.0) + (rtol or 0.0) * abs(row["value"])


# ---------------------------------------------------------------------------
# Internal-consistency checks of the papers (used by the tests and docs/validation.md)
# ---------------------------------------------------------------------------



@dataclass(frozen=True)
class Check:
    """A computed row compared with a printed row of the same source.

    ``mismatch`` is ``None`` when the paper is consistent, else the reason it is not (the
    test of a mismatch is a strict xfail with this reason).
    """

    source: str
    computed: str
    printed: str
    mismatch: str | None = None


#: Every numeric cross-check between a paper's printed numbers and what its own inputs give.
CHECKS: tuple[Check, ...] = (
    Check("videoray_pro3", "N_r.from_yaw_fit", "N_r.experimental"),
    Check("videoray_pro3", "N_rdot.from_yaw_fit", "N_rdot.experimental"),
    Check("videoray_pro3", "N_rr.from_yaw_fit", "N_rr.experimental",
          "Table I prints N_r|r| = 0.4504; its own beta/gamma = 1.1219/26.95 = 0.0416 (10.8x smaller)"),
    Check("videoray_pro3", "N_rdot.from_yaw_fit_with_I_yy", "N_rdot.experimental",
          "the text says gamma is the inverse inertia 'about y-axis'; with I_yy, 1/gamma - I_yy = 0.0132, "
          "not Table I's 0.0118 (I_zz reproduces it)"),
    Check("videoray_pro3", "verification.u_steady_from_table1", "verification.u_predicted",
          "the paper's model predicts 0.51 m/s at n = 60; Table I's experimental X_u, X_u|u| with two "
          "thrusters T = Ct n|n| give 0.483 m/s"),
    Check("rov2", "surge.mean_of_tests.m_a", "surge.average.m_a"),
    Check("rov2", "surge.mean_of_tests.K_L", "surge.average.K_L"),
    Check("rov2", "surge.mean_of_tests.K_Q", "surge.average.K_Q"),
    Check("rov2", "surge.mean_of_tests.rms", "surge.average.rms"),
    Check("rov2", "scale.drag_factor_exact", "scale.drag_factor"),
    Check("rov2", "scale.rot_drag_factor_exact", "scale.rot_drag_factor"),
    Check("rov2", "surge.K_L.scaled", "surge.K_L.experiment"),
    Check("rov2", "surge.m_a.scaled", "surge.experiment",
          "Table II average 0.5800 kg x (1/0.3)^3 = 21.48 kg; Table III prints 21.42 (= 0.58 x 3.33^3)"),
    Check("rov2", "surge.m_a.scaled_ratio_3.33", "surge.experiment"),
    Check("rov2", "surge.K_Q.scaled", "surge.K_Q.experiment",
          "Table II average 9.5439 x (1/0.3)^2 = 106.04; Table IV prints 106.03 (= 9.5439 x 11.11)"),
    Check("rov2", "surge.K_Q.scaled_printed_factor", "surge.K_Q.experiment",
          "9.5439 x 11.111 (eq. 9's printed factor) = 106.04; Table IV prints 106.03"),
    Check("rov2", "surge.K_Q.scaled_factor_11.11", "surge.K_Q.experiment"),
    Check("rov2", "air.r_from_alpha_g9.81", "air.r_from_alpha"),
    Check("rov2", "air.K_Q_from_gamma_times_r", "air.K_Q"),
    Check("rov2", "air.K_Q_from_gamma_eq4", "air.K_Q",
          "with the printed gamma = -K_Q r/(M+m_a) and the mass implied by beta and K_L (0.304 kg), "
          "K_Q = 0.0374, not the printed 0.0057 (which is |gamma| M r)"),
)


def check_results(*, root=None) -> list[dict]:
    """Evaluate :data:`CHECKS`: printed and computed values, relative difference, agreement."""
    out = []
    for c in CHECKS:
        printed = reference_value(c.source, c.printed, root=root)
        computed = recompute(c.source, c.computed, root=root)
        rel = (computed - printed["value"]) / abs(printed["value"]) if printed["value"] else float("nan")
        out.append({"check": c, "printed": printed, "computed": computed, "relative_difference": rel,
                    "agrees": agrees(printed, computed)})
    return out
