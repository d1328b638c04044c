"""Simple bodies with a measured whole-body drag coefficient, and stripcoef's drag of them.

The references are reference_tables/body_drag_3d (Hoerner 1965 via public copies; its
README says which rows can measure the method and which cannot: a body whose drag the method
reads from the same number is no independent check). Each body is a closed mesh of size
D = 0.1 m (its extent across the flow: the sphere's and the cones' base diameter, the cube's
edge a), run at U = 1 m/s in water (rho 1000 kg/m^3, nu 1e-6 m^2/s): Re = U D / nu = 1e5 on
that size, inside the references' subcritical range (sphere Re 1e3-2e5, cube Re 1e4-1e6).
stripcoef's drag coefficient in direction k is its quadratic term over the reference's area,

    C_D,model = |D_Q[k, k]| / (1/2 rho A)        [-]

(the D_Q term the VideoRay check and the uncertainty study sample; its linear share at U,
the Reynolds-number part of skin friction, is printed but not compared).

Bodies (x: the mesh axis the method cuts its strips along):
- ``sphere``: x, y and z against sphere.Cd (A = pi D^2/4);
- ``cube``: a cube of edge a, faces normal to x, y, z: all three against cube.face_on.Cd (A = a^2);
- ``cube_edge``: the cube turned 45 deg about z: x and y meet an edge (cube.edge_on.Cd, on the
  face area a^2 as the reference states), z a face (cube.face_on.Cd);
- ``cone60``, ``cone30``: flat-based cones of apex angle 60 and 30 deg along x, against
  cone.apex60.Cd / cone.apex30.Cd (A = pi d^2/4, the base); the model's drag is symmetric in
  the flow direction (a |u| u term);
- ``cube_edge_x``: the cube turned 45 deg about x: y and z meet an edge (cube.edge_on.Cd),
  x a face (cube.face_on.Cd); the same measured values as ``cube_edge`` through another path of
  the model (diamond sections instead of rectangles): not independent data;
- ``hemisphere``: a solid hemisphere along x, dome at the bow (+x): its X_uu (the drag going
  ahead) against hemisphere_solid.Cd_dome, dome on the flow, and its surge drag going astern
  (the result's ``conditions.surge_quadratic_damping_astern``, :data:`ASTERN`) against
  hemisphere_solid.Cd_high, flat face on the flow (A = pi d^2/4); the |u|u term holds only the
  first;
- ``cyl_across_1``, ``cyl_across_2``: flat-ended circular cylinders of diameter D and length
  D and 2D along x, in sway and heave, against the data book's finite cylinders at right
  angles to the flow (cylinder_crossflow.l_over_d_1.Cd, _2; A = d l);
- ``ellipsoid_2to1``: a prolate spheroid of length 2D along x against ellipsoid_2to1.Cd
  (nose-on, A = pi D^2/4; Re = 1e5 on D as the reference's table states);
- ``cone20``: a flat-based cone of half-angle 10 deg (apex 20 deg, L/D 2.84) against Munson's
  cone.half_angle10.Cd.munson (A = pi d^2/4);
- ``square_plate``, ``disc``: a 4 mm thick square plate of side D and a 4 mm disc of diameter D,
  normal to x, against square_plate.Cd and disc.Cd (A: the plate's or disc's area);
- ``cyl_end_0.5``, ``cyl_end_1``, ``cyl_end_2``, ``cyl_end_4``: flat-ended cylinders of
  diameter D along x, L/D 0.5 (Munson), 1, 2, 4 (the data book), A = pi D^2/4.

Held out or not (issue 35): since the model's axial drag of short and blunt hulls is measured
whole-body drag (src/stripcoef/data/ellipsoid_axial_drag.csv, blunt_body_axial_drag.csv,
plate_drag_aspect_ratio.csv), a body whose axial reference is a number those curves are built
from checks only that the mesh reaches the curve (L/D, aspect ratio, area), not the curve:
:data:`BUILT_FROM` names those (body, DOF) pairs and the file; they are printed but not used to
measure the method's band (scripts/make_method_uncertainty.py). Every other row is held out:
no number of it is an input of the model.

Run: python -m benchmarks.drag_bodies   (seconds; prints model vs reference)
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import trimesh

ROOT = Path(__file__).resolve().parent.parent

RHO = 1000.0          # water [kg/m^3]
NU = 1e-6             # [m^2/s]
SPEED = 1.0           # [m/s]
SIZE = 0.1            # D or a [m]
THICKNESS = 0.004     # plates and discs [m]
SOURCE = "body_drag_3d"
TABLE = "whole_body_drag"


def _revolved(r, x, sections=128):
    """Closed body of revolution about x from a meridian (r, x), r = 0 at both ends."""
    m = trimesh.creation.revolve(np.column_stack([r, x]), sections=sections)   # about z
    m = trimesh.Trimesh(m.vertices, m.faces, process=True)
    if m.volume < 0:
        m.invert()
    m.apply_transform(trimesh.geometry.align_vectors([0, 0, 1], [1, 0, 0]))
    return m


def sphere():
    t = np.linspace(0.0, np.pi, 97)
    return _revolved(0.5 * SIZE * np.sin(t), -0.5 * SIZE * np.cos(t))


def cone(apex_deg):
    """Flat-based cone, base diameter SIZE, apex angle ``apex_deg`` [deg], apex at +x."""
    length = 0.5 * SIZE / np.tan(np.radians(0.5 * apex_deg))
    r = np.r_[np.linspace(0.0, 0.5 * SIZE, 40), np.linspace(0.5 * SIZE, 0.0, 20)[1:]]
    x = np.r_[np.linspace(length, 0.0, 40), np.zeros(19)]
    return _revolved(r, x)


def hemisphere():
    """Solid hemisphere, base diameter SIZE, dome towards +x."""
    t = np.linspace(0.0, 0.5 * np.pi, 49)
    r = np.r_[0.5 * SIZE * np.sin(t), np.linspace(0.5 * SIZE, 0.0, 20)[1:]]
    x = np.r_[0.5 * SIZE * np.cos(t), np.zeros(19)]
    return _revolved(r, x)


def ellipsoid_2to1():
    t = np.linspace(0.0, np.pi, 97)
    return _revolved(0.5 * SIZE * np.sin(t), -SIZE * np.cos(t))


def cylinder_end_on(ld):
    """Flat-ended circular cylinder of diameter SIZE and length ld * SIZE along x."""
    m = trimesh.creation.cylinder(radius=0.5 * SIZE, height=ld * SIZE, sections=96)
    m.apply_transform(trimesh.geometry.align_vectors([0, 0, 1], [1, 0, 0]))
    return m


def cone_half_angle(half_deg):
    """Flat-based cone of base diameter SIZE and half-angle ``half_deg`` [deg], apex at +x."""
    return cone(2.0 * half_deg)


def square_plate():
    """Square plate of side SIZE, THICKNESS thick, normal to x."""
    return trimesh.creation.box([THICKNESS, SIZE, SIZE])


def disc():
    """Disc of diameter SIZE, THICKNESS thick, normal to x."""
    return cylinder_end_on(THICKNESS / SIZE)


def cube():
    return trimesh.creation.box([SIZE] * 3)


def cube_edge():
    m = cube()
    m.apply_transform(trimesh.transformations.rotation_matrix(np.pi / 4, [0, 0, 1]))
    return m


def cube_edge_x():
    """The cube turned 45 deg about x: y and z meet an edge, x a face (the strips' sections are
    diamonds, classified by their bounding box)."""
    m = cube()
    m.apply_transform(trimesh.transformations.rotation_matrix(np.pi / 4, [1, 0, 0]))
    return m


def cylinder_across(ld):
    """Flat-ended circular cylinder of diameter SIZE and length ld * SIZE along x (the strip
    axis), seen across its axis in y and z."""
    return cylinder_end_on(ld)


PI_D2 = np.pi * SIZE ** 2 / 4
#: name -> (builder, reference area [m^2], what the area is, [(dof index, reference row)])
BODIES = {
    "sphere": (sphere, PI_D2, "pi D^2/4", [(0, "sphere.Cd"), (1, "sphere.Cd"), (2, "sphere.Cd")]),
    "cube": (cube, SIZE ** 2, "face a^2", [(0, "cube.face_on.Cd"), (1, "cube.face_on.Cd"),
                                          (2, "cube.face_on.Cd")]),
    "cube_edge": (cube_edge, SIZE ** 2, "face a^2", [(0, "cube.edge_on.Cd"),
                                                    (1, "cube.edge_on.Cd"),
                                                    (2, "cube.face_on.Cd")]),
    "cube_edge_x": (cube_edge_x, SIZE ** 2, "face a^2", [(0, "cube.face_on.Cd"),
                                                        (1, "cube.edge_on.Cd"),
                                                        (2, "cube.edge_on.Cd")]),
    "cyl_across_1": (lambda: cylinder_across(1.0), SIZE ** 2, "d l",
                     [(1, "cylinder_crossflow.l_over_d_1.Cd"),
                      (2, "cylinder_crossflow.l_over_d_1.Cd")]),
    "cyl_across_2": (lambda: cylinder_across(2.0), 2 * SIZE ** 2, "d l",
                     [(1, "cylinder_crossflow.l_over_d_2.Cd"),
                      (2, "cylinder_crossflow.l_over_d_2.Cd")]),
    "cone60": (lambda: cone(60.0), PI_D2, "base pi d^2/4", [(0, "cone.apex60.Cd")]),
    "cone30": (lambda: cone(30.0), PI_D2, "base pi d^2/4", [(0, "cone.apex30.Cd")]),
    "hemisphere": (hemisphere, PI_D2, "base pi d^2/4", [(0, "hemisphere_solid.Cd_dome"),
                                                       (0, "hemisphere_solid.Cd_high")]),
    "ellipsoid_2to1": (ellipsoid_2to1, PI_D2, "pi D^2/4", [(0, "ellipsoid_2to1.Cd")]),
    "cone20": (lambda: cone_half_angle(10.0), PI_D2, "base pi d^2/4",
               [(0, "cone.half_angle10.Cd.munson")]),
    "square_plate": (square_plate, SIZE ** 2, "plate D^2", [(0, "square_plate.Cd")]),
    "disc": (disc, PI_D2, "disc pi D^2/4", [(0, "disc.Cd")]),
    "cyl_end_0.5": (lambda: cylinder_end_on(0.5), PI_D2, "pi D^2/4",
                    [(0, "cylinder_axial.l_over_d_0.5.Cd.munson")]),
    "cyl_end_1": (lambda: cylinder_end_on(1.0), PI_D2, "pi D^2/4",
                  [(0, "cylinder_axial.l_over_d_1.Cd")]),
    "cyl_end_2": (lambda: cylinder_end_on(2.0), PI_D2, "pi D^2/4",
                  [(0, "cylinder_axial.l_over_d_2.Cd")]),
    "cyl_end_4": (lambda: cylinder_end_on(4.0), PI_D2, "pi D^2/4",
                  [(0, "cylinder_axial.l_over_d_4.Cd")]),
}

#: (body, DOF) -> the model's data file whose numbers the reference row is (or is a copy of):
#: not held out, so not used to measure the method (module docstring)
BUILT_FROM = {
    ("sphere", 0): "ellipsoid_axial_drag.csv (L/d 1: 0.47)",
    ("sphere", 1): "ellipsoid_axial_drag.csv (L/d 1: 0.47; short-body cross-flow)",
    ("sphere", 2): "ellipsoid_axial_drag.csv (L/d 1: 0.47; short-body cross-flow)",
    ("cyl_across_2", 1): "cylinder_length_factor.csv (L/D 2: 0.58, DNV's copy of Hoerner's "
                         "finite cylinders)",
    ("cyl_across_2", 2): "cylinder_length_factor.csv (L/D 2: 0.58, DNV's copy of Hoerner's "
                         "finite cylinders)",
    ("ellipsoid_2to1", 0): "ellipsoid_axial_drag.csv (L/d 2: 0.27)",
    ("square_plate", 0): "plate_drag_aspect_ratio.csv (1.18), blunt_body_axial_drag.csv (disc 1.17)",
    ("disc", 0): "blunt_body_axial_drag.csv (L/d 0: 1.17)",
    ("cyl_end_0.5", 0): "blunt_body_axial_drag.csv (L/d 0.5: 1.15)",
    ("cyl_end_1", 0): "blunt_body_axial_drag.csv (L/d 1: 0.90)",
    ("cyl_end_2", 0): "blunt_body_axial_drag.csv (L/d 2: 0.85)",
    ("cyl_end_4", 0): "blunt_body_axial_drag.csv (L/d 4: 0.87)",
}


#: (body, reference row) compared with the model's surge drag going astern (the result's
#: ``conditions.surge_quadratic_damping_astern``), not with its |u|u term, which holds the drag
#: going ahead: the hemisphere flat face first (the benchmark's dome is at the bow, +x)
ASTERN = {("hemisphere", "hemisphere_solid.Cd_high")}


def held_out(name, dof):
    """Whether the (body, DOF) row is independent of the model's own curves."""
    return (name, dof) not in BUILT_FROM


def vehicle(name):
    from stripcoef.fluid import Fluid
    from stripcoef.geometry.vehicle import Vehicle

    m = BODIES[name][0]()
    m.apply_translation(-m.center_mass)
    return Vehicle.from_mesh(m, name=name, fluid=Fluid(density=RHO, kinematic_viscosity=NU,
                                                       source="benchmark: water"))


def compare(name, estimate=None):
    """(vehicle, model, rows): one row per compared direction k with the model's and the
    reference's C_D [-], the reference row, the area and the Reynolds number."""
    from stripcoef.assembly.estimate import estimate as estimate_any
    from validation.reference import reference_value

    veh = vehicle(name)
    model = (estimate or (lambda v: estimate_any(v, added_mass_method="strips", speed=SPEED)))(veh)
    _, area, area_text, refs = BODIES[name]
    dq = np.abs(np.diag(np.asarray(model.quadratic_damping)))
    dl = np.abs(np.diag(np.asarray(model.linear_damping)))
    rows = []
    for k, row in refs:
        astern = (name, row) in ASTERN
        q = float(model.conditions["surge_quadratic_damping_astern"]) if astern else dq[k]
        rows.append({"dof": k, "cd_model": float(q / (0.5 * RHO * area)), "astern": astern,
                     "cd_d_q": float(dq[k] / (0.5 * RHO * area)),
                     "cd_ref": float(reference_value(SOURCE, row)["value"]), "row": row,
                     "area": area_text, "reynolds": SPEED * SIZE / NU,
                     "held_out": held_out(name, k), "built_from": BUILT_FROM.get((name, k), ""),
                     "linear_share": float(dl[k] * SPEED / max(dl[k] * SPEED + dq[k] * SPEED ** 2,
                                                               1e-300))})
    return veh, model, rows
