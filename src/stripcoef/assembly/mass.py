r"""Displaced volume, centre of buoyancy and mass properties from the strips.

Volume and first moments are strip sums of section areas (holes' water excluded); mass,
centre of gravity and inertia come from the vehicle file's mass block or, where it gives
density zones, from the strips' volumes (Fossen 2011, sec. 3.3, eqs. 3.37 and 3.44-3.45).
"""

from __future__ import annotations
import numpy as np
from stripcoef.errors import InputError
from stripcoef.strips import Strips
from stripcoef.strips import hole_water


def displaced_volume(strips: Strips):
    r"""Displaced volume and centre of buoyancy from the strips.

    .. math:: V = \sum_{parts} A\,dx - \sum_{holes} c\,d\,dx,\qquad
              r_B = \frac{1}{V}\Big(\sum A\,dx\,(x, y_c, z_c) - \sum c\,d\,dx\,(x, y_h, z_h)\Big)

    Part areas A [m^2], hole chord c and depth d [m], strip widths dx [m]; centroids [m].

    Returns
    -------
    (float, ndarray)
        V [m^3], r_B [m] in body axes

    References
    ----------
    Midpoint-rule volume and first moment of the strips (Newman 1977, sec. 7.4 strip
    slicing); Fossen (2011), sec. 4.1 (B and r_B).
    """
    vol = 0.0
    mom = np.zeros(3)
    for p in strips.parts:
        dv = p.area * strips.width(p)
        vol += dv.sum()
        mom += np.array([(dv * strips.x[p.index]).sum(), (dv * p.y).sum(), (dv * p.z).sum()])
    for h, dv in hole_water(strips):
        if not h.in_hull:
            continue
        vol -= dv.sum()
        mom -= np.array([(dv * strips.x[h.index]).sum(), (dv * h.y).sum(), (dv * h.z).sum()])
    if vol <= 0:
        raise InputError("the body has no displaced volume", key="geometry", value=vol,
                         expected="a volume > 0")
    return float(vol), mom / vol


def _density_of(part, x, vehicle, rho_default):
    """Density per strip of a part from the vehicle's zones (last matching zone wins)."""
    dens = np.full(x.size, rho_default)
    for z in vehicle.mass.zones:
        if z.bodies is not None and part.name not in z.bodies:
            continue
        inside = (x >= z.x_aft) & (x <= z.x_fwd)
        dens[inside] = z.density
    return dens


def check_zones(strips: Strips, zones, *, file: str | None = None) -> None:
    """Every density zone covers at least one strip of a body it applies to.

    A zone that covers none would be ignored without a word: an error naming the zone, its
    x range and the extent of its bodies (outside the body), or the strip width (a zone
    narrower than one strip: more strips).
    """
    for i, z in enumerate(zones):
        parts = [p for p in strips.parts if z.bodies is None or p.name in z.bodies]
        if any(np.any((strips.x[p.index] >= z.x_aft) & (strips.x[p.index] <= z.x_fwd))
               for p in parts):
            continue
        key = f"mass.zones[{i}].x"
        value = [z.x_aft, z.x_fwd]
        if not parts:
            raise InputError("density zone over no body", file=file, key=key, value=value,
                             expected="a zone over a body that has strips")
        lo = min(float(np.min(strips.x[p.index] - 0.5 * strips.dx[p.index])) for p in parts)
        hi = max(float(np.max(strips.x[p.index] + 0.5 * strips.dx[p.index])) for p in parts)
        if z.x_fwd < lo or z.x_aft > hi:
            raise InputError(f"density zone {z.name!r} entirely outside the body", file=file,
                             key=key,
                             value=value, expected=f"an x range overlapping the body "
                                                   f"(x from {lo:.4g} to {hi:.4g} m)")
        dx = float(min(np.max(strips.dx[p.index]) for p in parts))
        raise InputError(f"density zone {z.name!r} covers no strip", file=file, key=key,
                         value=value,
                         expected=f"a zone wider than a strip ({dx:.3g} m; or more strips)")


def mass_properties(strips: Strips, vehicle, rho_fluid: float, volume: float, cb):
    r"""Mass [kg], centre of gravity [m] and inertia tensor about the CG [kg m^2].

    Directly from the vehicle file when given; otherwise from density zones (Ferreira et al. 2009,
    Table I and eq. 34) or, without either, a uniform body of the fluid's density
    (neutrally buoyant). The inertia of the strips is

    .. math:: I = \sum \rho_i A_i\,dx\,(|r_i|^2 I - r_i r_i^T) +
              \rho_i\,dx\,\mathrm{diag}(i_{yy}+i_{zz},\ i_{zz} + A\,dx^2/12,\
              i_{yy} + A\,dx^2/12)

    with :math:`r_i` from the CG (parallel-axis theorem, Fossen 2011 eq. 3.37).
    """
    spec = vehicle.mass if vehicle is not None else None
    have_mass = spec is not None and spec.mass is not None
    rho_default = rho_fluid
    if spec is not None and spec.default_density is not None:
        rho_default = spec.default_density
    # densities per strip: zones, or a default density without zones (a uniform body of
    # that density, not of the fluid's: issue 36, it was ignored)
    zones = spec is not None and (bool(spec.zones) or (spec.default_density is not None
                                                       and not have_mass))
    if have_mass and spec.center_of_gravity is not None and spec.inertia is not None:
        return spec.mass, np.asarray(spec.center_of_gravity, float), np.asarray(spec.inertia)
    if spec is not None and spec.zones:
        check_zones(strips, spec.zones, file=getattr(vehicle, "source", None))
    # distribute mass over the strips
    elems = []  # (dm, r, second-moment diag contribution)
    for p in strips.parts:
        xs = strips.x[p.index]
        dx = strips.width(p)
        dens = _density_of(p, xs, vehicle, rho_default) if zones else np.full(xs.size, 1.0)
        dm = dens * p.area * dx
        elems.append((dm, np.column_stack([xs, p.y, p.z]),
                      np.column_stack([dens * dx * (p.iyy + p.izz),
                                       dens * dx * p.izz + dm * dx**2 / 12.0,
                                       dens * dx * p.iyy + dm * dx**2 / 12.0])))
    for h, dv in hole_water(strips):
        if not h.in_hull:
            continue
        xs = strips.x[h.index]
        if zones:
            hull = next((p for p in strips.parts if p.role == "hull"), None)
            dens = _density_of(hull, xs, vehicle, rho_default) if hull is not None \
                else np.full(xs.size, rho_default)
        else:
            dens = np.ones(xs.size)
        elems.append((-dens * dv, np.column_stack([xs, h.y, h.z]), np.zeros((xs.size, 3))))
    dm = np.concatenate([e[0] for e in elems])
    r = np.concatenate([e[1] for e in elems])
    sec = np.concatenate([e[2] for e in elems])
    total = dm.sum()
    if total <= 0:
        key = "mass.zones" if spec.zones else "mass.default_density"
        raise InputError("a massless body", file=getattr(vehicle, "source", None), key=key,
                         value=float(total),
                         expected="densities > 0 over the body (a mass > 0 kg)")
    scale = 1.0
    if have_mass:
        scale = spec.mass / total           # uniform distribution scaled to the given mass
    elif not zones:
        scale = rho_fluid                   # neutrally buoyant, uniform
    dm = dm * scale
    sec = sec * scale
    mass = float(dm.sum())
    cg = (dm[:, None] * r).sum(axis=0) / mass
    if have_mass and spec.center_of_gravity is not None:
        cg = np.asarray(spec.center_of_gravity, float)
    d = r - cg
    inertia = np.zeros((3, 3))
    inertia += np.einsum("i,ij,ik->jk", dm, d, d) * -1.0
    inertia += np.eye(3) * (dm * (d**2).sum(axis=1)).sum()
    inertia += np.diag(sec.sum(axis=0))
    if have_mass and spec.inertia is not None:
        inertia = spec.inertia
    return mass, cg, inertia
