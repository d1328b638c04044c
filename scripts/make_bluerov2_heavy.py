"""Write the BlueROV2-Heavy files from one list of parts: the vehicle file and its mesh.

Run from the repository root:  python -m scripts.make_bluerov2_heavy

Writes geometry/bluerov2_heavy.yaml (the parts as a vehicle file) and
geometry/bluerov2_heavy.stl (the same parts united into one watertight surface by
:func:`stripcoef.geometry.surface.vehicle_surface`, at the tessellation the panel method uses
by default: :func:`stripcoef.assembly.added_mass.panel_surface`), and the copies of both in
src/stripcoef/samples/.  So the file and the mesh give the same added mass
(tests/test_vehicle_surface.py).

Published by Blue Robotics [P] (product pages, "Technical Details"; bluerovs are sold as kits,
no dimensioned drawing of the frame is published):

- BlueROV2 Heavy Configuration: 457 mm long, 575 mm wide, 254 mm high; 338 mm wide without
  the heavy kit's thruster decks (the frame's side panels); about 11.5 kg in air with
  ballast, trimmed near neutral buoyancy; eight T200 thrusters, four horizontal ones vectored
  at 45 deg at the corners and four vertical ones on the decks.
  https://bluerobotics.com/store/rov/bluerov2-upgrade-kits/brov2-heavy-retrofit/ and
  https://bluerobotics.com/store/rov/bluerov2/
- T200 thruster: 113 mm long, 100 mm in diameter; 344 g in air and 156 g in water, so it
  displaces 188 cm^3.
  https://bluerobotics.com/store/thrusters/t100-t200-thrusters/t200-thruster-r2-rp/
- Watertight enclosures: the 4" series tube is 4.5" (114.3 mm) outside, the 3" series 3.5"
  (88.9 mm); the BlueROV2's electronics enclosure is a 4" x 11.75" (298 mm) tube with a
  dome, its battery enclosure a 3" tube.  https://bluerobotics.com/store/watertight-enclosures/

Assumed here [A]: every place, the frame's members (HDPE 12.7 mm thick; each side panel cut
away to its outer rails and posts, as the published photographs show), the battery tube's
length, the buoyancy foam block's size (its thickness closes the volume to the published mass
at neutral buoyancy in fresh water), the T200 as a duct ring of its published outer size
whose wall holds its published displacement (motor and propeller lumped into the wall), the
horizontal thrusters' ducts drawn along x (a vehicle file's cylinder runs along x, y or z;
the published layout vectors them at 45 deg, which the thruster directions keep), the
thruster guards left out (open grilles: potential flow passes them).
Body axes FRD (x forward, y starboard, z down), metres, origin at the frame's centre.
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]

#: published overall size [m] (length x, width y, height z) [P]
OVERALL = (0.457, 0.575, 0.254)
#: published width of the frame without the heavy kit's decks [m] [P]
FRAME_WIDTH = 0.338
#: published mass in air [kg] [P]
MASS = 11.5
#: T200: published outer diameter and length [m], displaced volume [m^3] [P]
T200_D, T200_L, T200_VOLUME = 0.100, 0.113, (344.0 - 156.0) * 1e-6
#: the duct ring's inner diameter holding the published displacement [m] [A]
T200_ID = float(np.sqrt(T200_D ** 2 - 4.0 * T200_VOLUME / (np.pi * T200_L)))
#: 4" and 3" series tube outer diameters [m] [P]; electronics tube length 11.75" [P]
TUBE4_OD, TUBE3_OD, TUBE4_L = 0.1143, 0.0889, 0.298
#: HDPE plate thickness of the frame [m] [A]
PLATE = 0.0127
#: width of the side panels' rails and posts left after the cut-outs [m] [A]
RAIL = 0.035
#: fresh water [kg/m^3] (the vehicle file's fluid)
RHO = 1000.0


def _fmt(v) -> str:
    if isinstance(v, str):
        return v
    if isinstance(v, (list, tuple, np.ndarray)):
        return "[" + ", ".join(_fmt(x) for x in v) + "]"
    return f"{float(v):.6g}"


def _flow(d: dict) -> str:
    return "{" + ", ".join(f"{k}: {_fmt(v)}" for k, v in d.items()) + "}"


def appendages(foam_thickness: float) -> list[dict]:
    """The appendages of the vehicle file (the hull is the electronics enclosure)."""
    lx, ly, lz = OVERALL
    hx, hz = 0.5 * lx, 0.5 * lz
    y_out = 0.5 * FRAME_WIDTH                       # side panels' outer faces [P]
    y_in = y_out - PLATE
    y_mid = y_out - 0.5 * PLATE
    out = []
    for side, s in (("port", -1), ("starboard", 1)):
        # a side panel cut away to its rails (top, bottom) and posts (fore, aft) [A]
        rail, post = [lx - 2 * RAIL, PLATE, RAIL], [RAIL, PLATE, lz]
        out += [
            {"name": f"rail_top_{side}", "type": "box",
             "center": [0.0, s * y_mid, -hz + 0.5 * RAIL], "size": rail},
            {"name": f"rail_bottom_{side}", "type": "box",
             "center": [0.0, s * y_mid, hz - 0.5 * RAIL], "size": rail},
            {"name": f"post_fore_{side}", "type": "box",
             "center": [hx - 0.5 * RAIL, s * y_mid, 0.0], "size": post},
            {"name": f"post_aft_{side}", "type": "box",
             "center": [-hx + 0.5 * RAIL, s * y_mid, 0.0], "size": post},
        ]
    # the buoyancy foam block on top, between the panels, saddled 10 mm onto the
    # electronics tube [A]; its thickness closes the volume (main)
    out.append({"name": "buoyancy_foam", "type": "box",
                "center": [0.0, 0.0, -hz + 0.5 * foam_thickness],
                "size": [lx - 2 * RAIL, 2 * y_in, foam_thickness]})
    # two transverse crossbars under the battery tube (5 mm into it: its clamps), between the
    # side panels' bottom rails (2 mm into them) [A]
    top = BATTERY_Z + 0.5 * TUBE3_OD - 0.005
    for name, x in (("crossbar_fore", 0.10), ("crossbar_aft", -0.10)):
        out.append({"name": name, "type": "box", "center": [x, 0.0, 0.5 * (top + hz)],
                    "size": [PLATE, 2 * y_in + 0.004, hz - top]})
    out.append({"name": "battery_tube", "type": "cylinder", "axis": "x",
                "center": [0.0, 0.0, BATTERY_Z], "diameter": TUBE3_OD, "length": 0.26})
    # T200s: horizontal ones at the corners, mounted into the side panels; vertical ones on
    # the decks outboard of the panels, their outer edge at the published width [P layout]
    for tag, sx, sy in (("fp", 1, -1), ("fs", 1, 1), ("ap", -1, -1), ("as", -1, 1)):
        out.append({"name": f"t200_hor_{tag}", "type": "cylinder", "axis": "x",
                    "center": [sx * (hx - 0.5 * T200_L), sy * H_THRUSTER_Y, H_THRUSTER_Z],
                    "diameter": T200_D, "length": T200_L, "inner_diameter": T200_ID})
    for tag, sx, sy in (("fp", 1, -1), ("fs", 1, 1), ("ap", -1, -1), ("as", -1, 1)):
        y = 0.5 * ly - 0.5 * T200_D
        out.append({"name": f"t200_vert_{tag}", "type": "cylinder", "axis": "z",
                    "center": [sx * V_THRUSTER_X, sy * y, V_THRUSTER_Z],
                    "diameter": T200_D, "length": T200_L, "inner_diameter": T200_ID})
        # the deck arm from the side panel's top rail into the duct's wall (2.5 mm) [A]
        a, b = y_in + 0.004, y - 0.5 * T200_D + 0.0025
        out.append({"name": f"deck_{tag}", "type": "box",
                    "center": [sx * V_THRUSTER_X, sy * 0.5 * (a + b), -hz + 0.5 * RAIL],
                    "size": [0.06, b - a, PLATE]})
    return out


#: places [m] [A]: the battery tube's axis, the horizontal thrusters' (y, z), the vertical
#: ones' x and z (their ducts' tops flush with the frame's top)
BATTERY_Z = 0.075
H_THRUSTER_Y, H_THRUSTER_Z = 0.112, 0.06
V_THRUSTER_X, V_THRUSTER_Z = 0.12, -0.5 * OVERALL[2] + 0.5 * T200_L
DOME_R = 0.5 * TUBE4_OD
#: the electronics tube's top this far into the foam block (a saddle) [m] [A]
SADDLE = 0.004


def vehicle_data(foam_thickness: float, cg=(0.0, 0.0, 0.0)) -> dict:
    """The vehicle file as a mapping."""
    hx = 0.5 * OVERALL[0]
    x_dome = hx - DOME_R
    thr = {"ct_forward": 51.5, "ct_backward": 40.2, "max_forward": 51.5, "max_backward": 40.2}
    c = np.sqrt(0.5)
    hors = [("t1", 1, 1, [c, -c, 0]), ("t2", 1, -1, [c, c, 0]), ("t3", -1, 1, [c, c, 0]),
            ("t4", -1, -1, [c, -c, 0])]
    verts = [("t5", 1, 1), ("t6", 1, -1), ("t7", -1, 1), ("t8", -1, -1)]
    y_v = 0.5 * OVERALL[1] - 0.5 * T200_D
    thrusters = [dict(name=n, position=[sx * (hx - 0.5 * T200_L), sy * H_THRUSTER_Y,
                                        H_THRUSTER_Z], direction=d, **thr)
                 for n, sx, sy, d in hors]
    thrusters += [dict(name=n, position=[sx * V_THRUSTER_X, sy * y_v, V_THRUSTER_Z],
                       direction=[0, 0, 1], **thr) for n, sx, sy in verts]
    return {
        "name": "BlueROV2 Heavy",
        "description": "BlueROV2 Heavy frame ROV (published size, mass, enclosures and T200s; "
                       "frame members and places assumed, see comments)",
        "fluid": {"water": "fresh"},
        "reference_point": "center_of_buoyancy",
        "reference_speed": 0.5,
        "hull": {"name": "electronics_tube",
                 "z": -0.5 * OVERALL[2] + foam_thickness - SADDLE + DOME_R, "profile": [
            {"type": "cylinder", "x": [x_dome - TUBE4_L, x_dome], "radius": DOME_R},
            {"type": "ellipsoid_nose", "x": [x_dome, hx], "radius": DOME_R}]},
        "appendages": appendages(foam_thickness),
        "mass": {"mass": MASS, "center_of_gravity": list(cg)},
        "thrusters": thrusters,
    }


HEADER = """\
# BlueROV2 Heavy (Blue Robotics) as a vehicle file of its parts.  Written by
# scripts/make_bluerov2_heavy.py with geometry/bluerov2_heavy.stl, the same parts united into
# one closed surface: the two give the same added mass (tests/test_vehicle_surface.py).
#
# Published by Blue Robotics [P] (Technical Details of the product pages): 0.457 m long,
# 0.575 m wide (0.338 m without the heavy kit's thruster decks), 0.254 m high; about 11.5 kg
# in air with ballast, trimmed near neutral buoyancy; eight T200 thrusters (0.113 m long,
# 0.100 m in diameter, 344 g in air, 156 g in water: 188 cm^3 displaced), four horizontal
# ones vectored at 45 deg at the corners, four vertical ones on the decks; a 4" electronics
# enclosure (tube 114.3 mm outside, 298 mm long, with a dome) and a 3" battery enclosure
# (88.9 mm outside); T200 maximum thrust at 16 V about 5.25 kgf forward, 4.1 kgf reverse.
# Assumed [A]: every place and the frame's members: HDPE 12.7 mm thick, each side panel cut
# away to its rails and posts ({rail} m wide), two transverse crossbars, deck arms to the
# vertical thrusters; the battery tube 0.26 m long; the buoyancy foam block {foam:.4g} m thick
# (it closes the volume to 11.5 kg at neutral buoyancy in fresh water); each T200 a duct ring
# 0.100 m outside, {t200_id:.4g} m inside, 0.113 m long, its wall holding the published 188 cm^3;
# the horizontal ducts drawn along x (the thruster directions keep the 45 deg); the thruster
# guards left out (open grilles); the CG 0.02 m below the CB.
#
# Compare with the published identified models of this vehicle:
# - von Benzon, Sorensen, Uth, Jouffroy, Liniger, Pedersen (2022), "An open-source benchmark
#   simulator: control of a BlueROV2 underwater robot", J. Mar. Sci. Eng. 10(12) 1898,
#   doi:10.3390/jmse10121898 (BlueROV2 Heavy: X_udot 6.36, Y_vdot 7.12, Z_wdot 18.69 kg,
#   K_pdot 0.186, M_qdot 0.135, N_rdot 0.222 kg m^2, magnitudes; m 13.5 kg, V 0.0134 m^3);
# - Wu (2018), MSc thesis, Flinders University (BlueROV2 Heavy: X_udot 5.5, Y_vdot 12.7,
#   Z_wdot 14.57 kg, K_pdot = M_qdot = N_rdot 0.12 kg m^2, magnitudes; the set the public
#   BlueROV2 simulator descriptions reuse, e.g. CentraleNantesROV/bluerov2 hydrodynamics.xacro).
"""


def yaml_text(data: dict, foam: float) -> str:
    lines = [HEADER.format(rail=RAIL, foam=foam, t200_id=T200_ID)]
    for key in ("name", "description"):
        lines.append(f"{key}: {data[key]}")
    lines.append("fluid: {water: fresh}")
    lines.append(f"reference_point: {data['reference_point']}")
    lines.append(f"reference_speed: {data['reference_speed']}")
    hull = data["hull"]
    lines += ["hull:", f"  name: {hull['name']}", f"  z: {_fmt(hull['z'])}", "  profile:"]
    lines += [f"    - {_flow(s)}" for s in hull["profile"]]
    lines.append("appendages:")
    lines += [f"  - {_flow(a)}" for a in data["appendages"]]
    m = data["mass"]
    lines += ["mass:", f"  mass: {_fmt(m['mass'])}" + " " * 25 + "# [P] in air, with ballast",
              f"  center_of_gravity: {_fmt(m['center_of_gravity'])}   # [A] 0.02 m below the CB"]
    lines.append("thrusters:")
    lines.append("  # horizontal, vectored 45 deg [P]; forward-right / forward-left directions [A]")
    lines += [f"  - {_flow(t)}" for t in data["thrusters"][:4]]
    lines.append("  # vertical [P]; thrust down (+z) for a positive command [A]")
    lines += [f"  - {_flow(t)}" for t in data["thrusters"][4:]]
    return "\n".join(lines) + "\n"


def build():
    """(vehicle file text, Vehicle, foam thickness [m]): the foam's thickness found so that
    the strip volume times fresh water's density is the published mass (secant steps), the
    CG 0.02 m below the CB."""
    from stripcoef.assembly.mass import displaced_volume
    from stripcoef.geometry.vehicle import parse_vehicle

    def volume(t):
        st = parse_vehicle(vehicle_data(t)).cut(1000)
        return displaced_volume(st)

    t0, t1 = 0.02, 0.04
    v0, v1 = volume(t0)[0], volume(t1)[0]
    for _ in range(4):          # secant (nearly linear: the tube moves with the foam)
        t0, v0, t1 = t1, v1, t1 + (MASS / RHO - v1) * (t1 - t0) / (v1 - v0)
        v1 = volume(t1)[0]
    foam = t1
    _, cb = volume(round(foam, 4))
    cg = [round(float(cb[0]), 4), 0.0, round(float(cb[2]) + 0.02, 4)]
    data = vehicle_data(round(foam, 4), cg)
    return yaml_text(data, round(foam, 4)), parse_vehicle(data), round(foam, 4)


def bluerov2_heavy_parts():
    """The parts (trimesh solids, overlapping) of the vehicle file [m]."""
    from stripcoef.geometry.surface import part_meshes

    return part_meshes(build()[1])


def bluerov2_heavy_mesh():
    """The parts united (:func:`stripcoef.assembly.added_mass.panel_surface` at the panel
    method's default panel count): the surface the vehicle file is panelled on."""
    from stripcoef.assembly.added_mass import panel_surface
    from stripcoef.hull.panels import DEFAULT_PANELS

    return panel_surface(build()[1], DEFAULT_PANELS)


def main(argv=None):
    from stripcoef.assembly.added_mass import panel_surface
    from stripcoef.hull.panels import DEFAULT_PANELS

    text, vehicle, foam = build()
    mesh = panel_surface(vehicle, DEFAULT_PANELS)
    for folder in (ROOT / "geometry", ROOT / "src" / "stripcoef" / "samples"):
        (folder / "bluerov2_heavy.yaml").write_text(text)
        mesh.export(folder / "bluerov2_heavy.stl")
    ext = np.ptp(mesh.vertices, axis=0)
    print(f"wrote bluerov2_heavy.yaml and .stl (geometry/, src/stripcoef/samples/): foam "
          f"{foam:.4g} m, {len(mesh.faces)} faces, watertight {mesh.is_watertight}, extent "
          f"{ext.round(4).tolist()} m, volume {mesh.volume:.5f} m^3 (parts overlap "
          f"{mesh.metadata['overlap']:.2e} m^3), {mesh.metadata['sections']} sides a circle")
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
