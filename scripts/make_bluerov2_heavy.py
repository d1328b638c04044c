"""Write geometry/bluerov2_heavy.stl: a BlueROV2-Heavy-like frame from trimesh primitives.

Run from the repository root:  python -m scripts.make_bluerov2_heavy

Published (Blue Robotics, BlueROV2 Heavy Configuration technical details) [P]: overall
0.457 m long x 0.575 m wide x 0.254 m high; about 11.5 kg in air; eight T200 thrusters, four
horizontal ones vectored at 45 deg at the corners, four vertical ones; a 4" electronics
enclosure and a 3" battery enclosure along x.
Assumed here [A] (not published as drawings we can cite): the sizes and places of every part
below -- two HDPE side panels 12.7 mm thick, a buoyancy block on top, the enclosures' outer
diameters (0.114 m and 0.089 m) and lengths, T200 pods as solid cylinders 0.10 m in diameter
and 0.11 m long (potential flow: the duct's water taken as part of the body), horizontal
wings joining the vertical thrusters to the side panels. Body axes FRD (x forward, y
starboard, z down), metres, origin at the box centre; watertight (boolean union).
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import trimesh

#: published overall size [m] (length x, width y, height z) [P]
OVERALL = (0.457, 0.575, 0.254)
#: T200 pod (solid cylinder) diameter and length [m] [A]
POD_D, POD_L = 0.10, 0.11
#: polygon sides of every cylinder [A]
SECTIONS = 20


def _box(size, center):
    return trimesh.creation.box(size, transform=trimesh.transformations.translation_matrix(center))


def _cylinder(diameter, length, center, direction):
    """Solid cylinder (``SECTIONS``-gon prism) of ``diameter`` and ``length`` [m] along
    ``direction`` (unit vector), centred at ``center`` [m]."""
    c = trimesh.creation.cylinder(radius=0.5 * diameter, height=length, sections=SECTIONS)
    rot = trimesh.geometry.align_vectors([0, 0, 1], np.asarray(direction, float))
    c.apply_transform(rot)
    c.apply_translation(center)
    return c


def bluerov2_heavy_parts():
    """The parts (trimesh solids, overlapping) of the BlueROV2-Heavy-like frame [m]."""
    lx, ly, lz = OVERALL
    y_panel = 0.17                                   # side panels' mid-plane [A]
    parts = [_box([lx, 0.0127, lz], [0.0, s * y_panel, 0.0]) for s in (-1, 1)]
    parts.append(_box([0.40, 2 * y_panel, 0.06], [0.0, 0.0, -0.5 * lz + 0.03]))   # buoyancy [A]
    parts.append(_cylinder(0.114, 0.32, [0.02, 0.0, -0.01], [1, 0, 0]))            # 4" tube [A]
    parts.append(_cylinder(0.089, 0.26, [0.0, 0.0, 0.075], [1, 0, 0]))             # 3" tube [A]
    parts.append(_box([0.30, 2 * y_panel, 0.0127], [0.0, 0.0, 0.5 * lz - 0.02]))   # lower tray [A]
    y_v = 0.5 * ly - 0.5 * POD_D                     # vertical pods reach the published width
    for sx in (-1, 1):
        for sy in (-1, 1):
            # vectored horizontal thrusters at the corners, axis at 45 deg in the x-y plane [P]
            parts.append(_cylinder(POD_D, POD_L, [sx * 0.14, sy * 0.10, 0.06],
                                   [np.sqrt(0.5), -sx * sy * np.sqrt(0.5), 0.0]))
            # vertical thrusters outboard of the panels [P layout, A place], and their wings
            parts.append(_cylinder(POD_D, POD_L, [sx * 0.12, sy * y_v, -0.055], [0, 0, 1]))
            parts.append(_box([0.10, y_v - y_panel + 0.01, 0.0127],
                              [sx * 0.12, sy * 0.5 * (y_v + y_panel), -0.055]))
    return parts


def bluerov2_heavy_mesh():
    """Watertight boolean union of :func:`bluerov2_heavy_parts` (trimesh, manifold engine)."""
    return trimesh.boolean.union(bluerov2_heavy_parts(), engine="manifold")


def main(argv=None):
    out = Path(__file__).resolve().parents[1] / "geometry" / "bluerov2_heavy.stl"
    m = bluerov2_heavy_mesh()
    ext = np.ptp(m.vertices, axis=0)
    m.export(out)
    print(f"wrote {out.name}: {len(m.faces)} faces, watertight {m.is_watertight}, "
          f"extent {ext.round(4).tolist()} m, volume {m.volume:.5f} m^3")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
