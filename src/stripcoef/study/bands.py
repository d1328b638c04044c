"""The method's uncertainty bands beside the model's point values.

:func:`method_bands` reads the rows of the method table (``data/method_uncertainty.csv``,
:func:`stripcoef.study.sources.method_sources`) for a vehicle's shape class and returns them as
:class:`stripcoef.model.MethodBand` records; :func:`with_bands` puts them on the model
(:attr:`HydroModel.bands`), from which the text output, the JSON (``bands``,
``coefficient_bands``) and the exporters' comments read them; :func:`uncertain_terms` names the
coefficients whose 95 % band reaches past 50 % of their value (the CLI's warning).
"""

from __future__ import annotations

from dataclasses import replace

import numpy as np

from stripcoef.model import UNCERTAIN, MethodBand


def method_bands(vehicle, model) -> tuple:
    """The method rows of ``vehicle``'s shape class as MethodBand records (lift and control
    rows only for a model with lift or control surfaces; the added-mass rows of the panel
    method when ``model``'s added mass is its)."""
    from stripcoef.study.sources import _method_table, method_sources

    lift = bool(np.any(np.asarray(model.lift) != 0.0) or model.control_surfaces)
    # the added-mass rows of the method the model was estimated with (the panel method's or
    # strip theory's: --added-mass-method), not of the default one
    panels = "panel method" in str((model.provenance or {}).get("method", ""))
    basis = {(r["class"], r["matrix"], r["dofs"]): r["basis"] for r in _method_table()}
    out = []
    for src in method_sources(vehicle, lift=lift, panels=panels):
        matrix, dofs = src.name.split(".")
        cls = src.reason.split(":", 1)[0]
        out.append(MethodBand(matrix=matrix, dofs=dofs, distribution=src.distribution,
                              sd=float(src.spread), basis=basis.get((cls, matrix, dofs), ""),
                              in_scope=src.in_scope, source=src.reason))
    return tuple(out)


def with_bands(model, vehicle):
    """``model`` with the method bands of ``vehicle`` (:func:`method_bands`)."""
    return replace(model, bands=method_bands(vehicle, model))


def _not_predicted(model) -> set[str]:
    """Coefficient names of the matrices whose band is a placeholder (basis not_predicted)."""
    from stripcoef.conventions import (added_mass_name, linear_damping_name,
                                       quadratic_damping_name)
    namers = {"added_mass": added_mass_name, "linear_damping": linear_damping_name,
              "quadratic_damping": quadratic_damping_name}
    out = set()
    for b in model.bands:
        if b.basis == "not_predicted" and b.matrix in namers:
            out |= {namers[b.matrix](i, j) for i in range(6) for j in range(6)}
    return out


def uncertain_terms(model, *, threshold: float = UNCERTAIN) -> list[str]:
    """Coefficients whose 95 % band reaches past ``threshold`` (0.5: 50 %) of their value,
    the widest first (from :meth:`HydroModel.coefficient_bands`); the terms of a matrix the
    method does not predict (linear damping: a placeholder band) are left out, the warning
    says so once, and so are the added-mass couplings (an additive band of their diagonal
    scale)."""
    from stripcoef.conventions import added_mass_name

    coeffs = model.coefficients()
    # couplings move by a share of their diagonal scale, not of themselves: their band is
    # printed (+- c sqrt(M_ii M_jj)) but a near-zero coupling is not "uncertain by 50 %"
    skip = _not_predicted(model) | {added_mass_name(i, j) for i in range(6) for j in range(6)
                                    if i != j}
    width = {}
    for name, (lo, hi) in model.coefficient_bands().items():
        if name in skip:
            continue
        v = abs(coeffs[name])
        if v > 0.0:
            width[name] = max(abs(hi - coeffs[name]), abs(coeffs[name] - lo)) / v
    return sorted((k for k, w in width.items() if w > threshold), key=lambda k: -width[k])


def band_lines(model) -> list[str]:
    """One line per band row: the matrix, DOF group and its 95 % band (the text output)."""
    return [f"{b.matrix} {b.dofs}: 95 % band {b.describe()}" for b in model.bands]


def warn_uncertain(model) -> None:
    """One :class:`ModelWarning` naming the coefficients uncertain by more than 50 % (95 %
    method band), with the command that gives the whole study; nothing when there are none."""
    import warnings

    from stripcoef.errors import ModelWarning

    names = uncertain_terms(model)
    if names:
        more = f" and {len(names) - 8} more" if len(names) > 8 else ""
        loose = sorted({b.matrix.replace("_", " ") for b in model.bands
                        if b.basis == "not_predicted"})
        also = f"; {' and '.join(loose)} not predicted" if loose else ""
        warnings.warn(f"{model.name}: {len(names)} coefficients are uncertain by more than "
                      f"{UNCERTAIN * 100:.0f} % (the method's 95 % band): "
                      f"{', '.join(names[:8])}{more}{also} (bands in the JSON "
                      "'coefficient_bands'; 'stripcoef uncertainty VEHICLE' propagates them)",
                      ModelWarning, stacklevel=2)
