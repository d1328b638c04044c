"""Test bodies for the mesh benchmarks: bodies of revolution, a finned torpedo, an open-frame ROV.

All along x, metres, origin at mid-length.  Used by mesh_accuracy.py and mesh_speed.py.
"""

from __future__ import annotations

import numpy as np
import trimesh

from stripcoef.geometry.mesh import revolved_mesh
from stripcoef.geometry.profiles import myring_nose, myring_tail

#: REMUS-like Myring hull (Prestero 2001, table 2.1): nose a, middle b, tail c, diameter d.
MYRING = {"a": 0.191, "b": 0.654, "c": 0.541, "d": 0.191, "n": 2.0, "theta": np.radians(25.0)}


def spheroid_profile(length, diameter, n=200):
    """Eccentric-angle spacing (clustered at the tips)."""
    t = np.linspace(0.0, np.pi, n + 1)[::-1]
    return 0.5 * length * np.cos(t), 0.5 * diameter * np.sin(t)


def capsule_profile(length=1.5, diameter=0.2, n_cap=40, n_mid=120):
    rad = 0.5 * diameter
    half = 0.5 * length - rad
    th = np.linspace(0.0, 0.5 * np.pi, n_cap + 1)
    x = np.r_[-half - rad * np.cos(th), np.linspace(-half, half, n_mid + 1)[1:-1], half + rad * np.sin(th)]
    r = np.r_[rad * np.sin(th), np.full(n_mid - 1, rad), rad * np.cos(th)]
    return x, r


def myring_profile(n=240):
    p = MYRING
    length = p["a"] + p["b"] + p["c"]
    x0 = -0.5 * length
    s = 0.5 * (1.0 - np.cos(np.linspace(0.0, np.pi, n + 1)))
    x = x0 + length * s
    tail_end, mid_end = x0 + p["c"], x0 + p["c"] + p["b"]
    r = np.where(x < tail_end, myring_tail(x, x0, tail_end, 0.5 * p["d"], p["theta"]),
                 np.where(x > mid_end, myring_nose(x, mid_end, x0 + length, 0.5 * p["d"], p["n"]),
                          0.5 * p["d"]))
    r[0] = r[-1] = 0.0
    return x, r


def body_of_revolution(profile, sections):
    return revolved_mesh(*profile, sections=sections)


def finned_torpedo(n_profile=120, sections=48, fin_span=0.09, fin_chord=0.08, fin_t=0.012):
    """Myring hull with a cruciform tail: four flat fins (boxes) unioned with the hull."""
    hull = revolved_mesh(*myring_profile(n_profile), sections=sections)
    p = MYRING
    x0 = -0.5 * (p["a"] + p["b"] + p["c"])
    xc = x0 + 0.17                      # fin mid-chord, on the tail cone
    r_root = 0.5 * p["d"] * 0.55
    fins = []
    for ang in (0.0, 0.5 * np.pi, np.pi, 1.5 * np.pi):
        box = trimesh.creation.box([fin_chord, fin_t, r_root + fin_span])
        box.apply_translation([xc, 0.0, 0.5 * (r_root + fin_span)])
        box.apply_transform(trimesh.transformations.rotation_matrix(ang, [1, 0, 0]))
        fins.append(box)
    return trimesh.boolean.union([hull] + fins, engine="manifold")


def open_frame_rov(subdiv=0):
    """Box-like open frame: a top float, two lower pontoons, four vertical posts (unioned).

    Overall about 1.0 m long, 0.7 m wide, 0.55 m high.
    """
    parts = [trimesh.creation.box([0.9, 0.6, 0.15], transform=trimesh.transformations.translation_matrix([0, 0, -0.2])),
             trimesh.creation.box([1.0, 0.12, 0.15], transform=trimesh.transformations.translation_matrix([0, -0.29, 0.2])),
             trimesh.creation.box([1.0, 0.12, 0.15], transform=trimesh.transformations.translation_matrix([0, 0.29, 0.2]))]
    for x in (-0.38, 0.38):
        for y in (-0.27, 0.27):
            parts.append(trimesh.creation.box([0.06, 0.06, 0.3],
                                              transform=trimesh.transformations.translation_matrix([x, y, 0.0])))
    m = trimesh.boolean.union(parts, engine="manifold")
    for _ in range(subdiv):
        m = m.subdivide()
    return m


def open_frame_rov_quarter():
    """The x >= 0, y >= 0 quarter of :func:`open_frame_rov`, open on the planes x = 0 and y = 0
    (for Capytaine's ReflectionSymmetricMesh: four times the faces for the same memory)."""
    def box(lo, hi):
        lo, hi = np.asarray(lo, float), np.asarray(hi, float)
        return trimesh.creation.box(hi - lo, transform=trimesh.transformations.translation_matrix(0.5 * (lo + hi)))
    q = trimesh.boolean.union([box([0, 0, -0.275], [0.45, 0.3, -0.125]),
                               box([0, 0.23, 0.125], [0.5, 0.35, 0.275]),
                               box([0.35, 0.24, -0.15], [0.41, 0.30, 0.15])], engine="manifold")
    c, n = q.triangles_center, q.face_normals
    cut = ((np.abs(c[:, 0]) < 1e-9) & (n[:, 0] < -0.99)) | ((np.abs(c[:, 1]) < 1e-9) & (n[:, 1] < -0.99))
    q.update_faces(~cut)
    q.remove_unreferenced_vertices()
    return q


def refine_to(mesh, faces):
    """Subdivide a mesh's longest edges until it has about ``faces`` faces (for the BEM)."""
    m = mesh.copy()
    max_edge = float(np.max(m.edges_unique_length))
    while len(m.faces) < faces:
        max_edge *= 0.8
        v, f = trimesh.remesh.subdivide_to_size(m.vertices, m.faces, max_edge=max_edge)
        m = trimesh.Trimesh(v, f, process=True)
    return m
