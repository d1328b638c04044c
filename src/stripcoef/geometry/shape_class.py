r"""Which shape class a vehicle belongs to, from its geometry (never its name or file type).

The method error of strip theory depends on the shape (docs/validation.md): exact for bodies
of revolution, a few percent for finned torpedoes, tens of percent to orders of magnitude for
the rotations of bluff bodies. :func:`shape_class` reads three numbers off the vehicle's
strips (:meth:`stripcoef.geometry.vehicle.Vehicle.cut`, the same sections the model uses; the
span ratio is read by the added-mass ``auto`` rule, :mod:`stripcoef.assembly.methods`):

- **round fraction** :math:`\rho_r = \sum_{round} \Delta x / L` [-]: the share of the length
  whose whole section (every part of the strip) is round about the x axis: equal extents,
  :math:`|B - H| \le 0.03 \max(B, H)`, and an area that fills its bounding box as a circle
  does, :math:`|A / (\pi B H / 4) - 1| \le 0.03` (B, H: breadth and height of the section
  [m], A: its area [m^2]);
- **slenderness** :math:`L / D` [-]: length over the largest extent across x of the round
  sections (of every section when none is round) [m / m];
- **span ratio** :math:`S / D` [-]: the largest extent across x of any section (fins, wings
  and appendages included) over D [m / m] (1 for a body of revolution);
- **fill** :math:`\phi = \sum A \Delta x / (L B_{max} H_{max})` [-]: displaced volume over
  the volume of the bounding box (1 for a box, :math:`\pi/4` for a cylinder, :math:`\pi/6` for
  an ellipsoid; small for a frame of tubes).

The rule (thresholds between the reference shapes of the calibration set,
reference_tables/method_errors/method_errors.csv: round fraction 0.99-1 for the bodies of revolution,
0.90-0.96 for the six finned hulls (0.82 MARES, 0.94 REMUS 100; the smallest margin is the
small-fin hull's 0.955 against 0.97: fins much smaller still would make a hull ``revolution``),
at most 0.18 for the bluff shapes; fill 0.09 for the open frame, 0.17 for the BlueROV2 Heavy
vehicle file, 0.35-1 for the bluff shapes, 0.29 for the VideoRay vehicle file):

1. ``revolution``: :math:`\rho_r \ge 0.97` -- every section round (a sphere, a spheroid, a
   capsule, a short cylinder along x: strip theory with its 3D end corrections is the exact
   axisymmetric solution there, whatever L / D);
2. ``finned``: :math:`\rho_r \ge 0.5` and :math:`L/D \ge 3` -- a slender round hull over
   most of its length, fins or appendages on the rest (a finned torpedo);
3. ``open_frame``: :math:`\phi < 0.20` -- a frame of members with water between them;
4. ``bluff``: anything else (boxes, short cylinders across x, flat ellipsoids, box ROVs).

Slender-body theory and its error with L/D and section shape: Newman 1977, *Marine
Hydrodynamics*, sec. 7.4; the measured errors per class: docs/validation.md.
"""

from __future__ import annotations

import numpy as np

CLASSES = ("revolution", "finned", "bluff", "open_frame")
#: tolerance of "round": equal extents and circle-like area, relative [-]
ROUND_TOL = 0.03
#: share of the length that must be round: all of it (revolution) or most (finned) [-]
REVOLUTION_ROUND = 0.97
FINNED_ROUND = 0.5
#: slenderness L / D above which a mostly round hull counts as a torpedo [-]
FINNED_SLENDERNESS = 3.0
#: fill (volume / bounding-box volume) below which a body is an open frame [-]
OPEN_FILL = 0.20


def features(vehicle, strips: int | None = None) -> dict:
    """``round_fraction``, ``slenderness``, ``fill``, ``span_ratio`` [-] and ``length`` [m] of a vehicle
    (module docstring: the formulas), on ``strips`` strips (default: the vehicle's own count,
    the sections its model is made of: a body too short for fewer strips is still seen)."""
    return strip_features(vehicle.cut(strips))


def strip_features(st) -> dict:
    """:func:`features` of the strips ``st`` (a :class:`~stripcoef.strips.Strips`, cut
    already: the estimate's own, :func:`stripcoef.assembly.methods.choose_method`)."""
    n = st.n
    ymin, ymax = np.full(n, np.inf), np.full(n, -np.inf)
    zmin, zmax = np.full(n, np.inf), np.full(n, -np.inf)
    area = np.zeros(n)
    for p in st.parts:
        i = np.asarray(p.index, dtype=int)
        if not i.size:
            continue
        np.minimum.at(ymin, i, p.y - p.half_breadth)
        np.maximum.at(ymax, i, p.y + p.half_breadth)
        np.minimum.at(zmin, i, p.z - p.half_height)
        np.maximum.at(zmax, i, p.z + p.half_height)
        np.add.at(area, i, np.asarray(p.area, float) * np.asarray(p.coverage, float))
    covered = np.isfinite(ymin) & (area > 0)
    b = np.where(covered, ymax - ymin, 0.0)
    h = np.where(covered, zmax - zmin, 0.0)
    big = np.maximum(b, h)
    with np.errstate(divide="ignore", invalid="ignore"):
        circle = np.where(covered, area / (0.25 * np.pi * b * h), 0.0)
        equal = np.where(covered, np.abs(b - h) / big, 1.0)
    round_ = covered & (equal <= ROUND_TOL) & (np.abs(circle - 1.0) <= ROUND_TOL)
    length = float(st.length)
    round_fraction = float(np.sum(st.dx[round_]) / length)
    d = float(np.max(big[round_])) if round_.any() else float(np.max(big))
    box = length * float(np.max(b)) * float(np.max(h))
    fill = float(np.sum(area * st.dx) / box) if box > 0 else 0.0
    return {"round_fraction": round_fraction, "slenderness": length / d, "fill": fill,
            "length": length, "span_ratio": float(np.max(big)) / d}


def classify(f: dict) -> str:
    """The class of a :func:`features` dict by the documented rule (module docstring)."""
    if f["round_fraction"] >= REVOLUTION_ROUND:
        return "revolution"
    if f["round_fraction"] >= FINNED_ROUND and f["slenderness"] >= FINNED_SLENDERNESS:
        return "finned"
    if f["fill"] < OPEN_FILL:
        return "open_frame"
    return "bluff"


def shape_class(vehicle) -> str:
    """``revolution``, ``finned``, ``bluff`` or ``open_frame`` (module docstring: the rule)."""
    return classify(features(vehicle))
