r"""Similitude: coefficients of a scaled model to full scale (Eng et al., Eng et al. 2009, eqs. 8-10).

With geometric ratio :math:`\lambda = L_{full}/L_{model}` (Eng et al. 2009: :math:`\lambda = 1/0.3`),
the same fluid and the same speed, and a drag coefficient independent of the Reynolds number:

- drag force :math:`D = \tfrac12\rho C_d A V^2` scales with the area (eq. 9):
  :math:`K_L, K_Q \times \lambda^2` (Eng et al. 2009 applies the same factor to the linear term);
- rotational drag torque :math:`T_d = C_D \rho A_p L^3 \dot\theta^2` (eq. 10):
  :math:`K_L, K_Q` (rotational) :math:`\times \lambda^5`;
- added mass scales with the displaced volume (Triantafyllou & Hover, ref. [14] of Eng et al. 2009):
  :math:`m_a \times \lambda^3`; added moment of inertia :math:`\times \lambda^5`.

Reynolds caveat (Eng et al. 2009, sec. II.D): dynamic similarity needs equal Re, i.e. the model
moving :math:`\lambda` times faster in the same water.  The scaling above holds only where
:math:`C_d` is flat in Re (Eng et al. 2009's CFD: 0-0.5 m/s); a linear drag term is a viscous /
low-Re effect and does not in general follow :math:`\lambda^2`.
"""

from __future__ import annotations

import math

from stripcoef.errors import InputError

#: Parameter name -> exponent of lambda, for translational (surge/sway/heave) results.
TRANSLATION = {"m_a": 3, "K_L": 2, "K_Q": 2}
#: For rotational results (torsion pendulum, yaw).
ROTATION = {"I_a": 5, "m_a": 5, "K_L": 5, "K_Q": 5}
REYNOLDS_CAVEAT = ("similitude at equal speed assumes drag coefficients independent of the "
                   "Reynolds number (Eng et al. 2009 sec. II.D: true for its CFD over 0-0.5 m/s); the "
                   "full-scale Re is lambda times the model's, and linear (viscous) drag does "
                   "not in general scale as lambda^2")


def exponents(rotational: bool) -> dict:
    """Exponent of lambda per parameter name."""
    return ROTATION if rotational else TRANSLATION


def scale_value(value: float, name: str, ratio: float, *, rotational: bool = False) -> float:
    r"""Full-scale value :math:`\theta_{full} = \lambda^k \theta_{model}` (Eng et al. 2009, eqs. 9-10).

    ``ratio`` :math:`\lambda = L_{full}/L_{model}` [-]; ``value`` and the result in the
    parameter's own unit (e.g. [kg], [N s^2/m^2]); k from :func:`exponents` (module docstring).
    """
    _check_ratio(ratio)
    table = exponents(rotational)
    if name not in table:
        raise InputError("no similitude law for this parameter", key=name,
                         expected="one of " + ", ".join(sorted(table)))
    return value * ratio ** table[name]


def _check_ratio(ratio) -> None:
    if isinstance(ratio, bool) or not isinstance(ratio, (int, float)) \
            or not (ratio > 0 and math.isfinite(ratio)):
        raise InputError("bad scale ratio", key="ratio", value=ratio,
                         expected="a positive finite number L_full / L_model")


def scale_result(result: dict, ratio: float, *, rotational: bool | None = None,
                 file: str | None = None) -> dict:
    """Scale the parameters and std of a result dict (the JSON contract) to full scale.

    ``rotational`` defaults to True for torsion results and yaw/roll/pitch DOFs.
    Parameters without a similitude law (alpha, beta...) are dropped; the output lists
    the factor used for each.
    """
    _check_ratio(ratio)
    for key in ("parameters", "std"):
        if not isinstance(result.get(key), dict):
            raise InputError("not an identification result", file=file, key=key,
                             expected='a JSON object with "parameters" and "std" '
                             "(the output of stripcoef identify --json)")
        for name, value in result[key].items():
            if value is None and key == "std":
                continue
            if isinstance(value, bool) or not isinstance(value, (int, float)) \
                    or not math.isfinite(value):
                raise InputError("not a finite number", file=file, key=f"{key}.{name}",
                                 value=value,
                                 expected="a finite number (the output of stripcoef identify "
                                          "--json)")
    if rotational is None:
        if not result.get("method") and not result.get("dof"):
            raise InputError("cannot tell a rotational from a translational result", file=file,
                             key="method", expected='a result with its "method" and "dof" (the '
                             "output of stripcoef identify --json), or rotational given "
                             "(--rotational or --translational)")
        rotational = (str(result.get("method", "")).startswith("torsion")
                      or result.get("dof") in ("roll", "pitch", "yaw"))
    table = exponents(rotational)
    params, std, factors = {}, {}, {}
    for name, value in result["parameters"].items():
        if name in table and value is not None:
            try:
                f = ratio ** table[name]
            except OverflowError:
                f = math.inf
            if not math.isfinite(f * value):
                raise InputError("scaled value overflows", key="ratio", value=ratio,
                                 expected=f"a ratio whose power {table[name]} keeps {name} finite")
            params[name] = value * f
            s = result["std"].get(name)
            std[name] = None if s is None else s * f
            factors[name] = f
    if not params:
        raise InputError("no scalable parameter in the result", file=file, key="parameters",
                         value=sorted(result["parameters"]),
                         expected="some of " + ", ".join(sorted(table)))
    rel = {n: (100.0 * std[n] / abs(params[n]) if std[n] is not None and params[n] else None)
           for n in params}
    return {"method": "similitude", "model": result.get("model", ""),
            "dof": result.get("dof", ""), "ratio": ratio, "rotational": rotational,
            "parameters": params, "std": std, "relative_error_percent": rel,
            "factors": factors, "caveat": REYNOLDS_CAVEAT, "source": result.get("method", "")}
