"""Roll relief of meshes (corrections.mode_inertia, roll_relief, roll_symmetry_order)."""

import warnings

import numpy as np
import pytest
import trimesh
from scipy.special import elliprd

from stripcoef.assembly.added_mass import added_mass
from stripcoef.assembly.estimate import displaced_volume
from stripcoef.hull.corrections import mode_inertia, roll_relief, roll_symmetry_order
from stripcoef.geometry.mesh import mesh_body, revolved_mesh
from stripcoef.geometry.profiles import myring_nose, myring_tail
from stripcoef.strips import Strips, uniform_stations

RHO = 1000.0


def test_mode2_of_a_sphere_is_exact():
    """v_n = r n_r cos 2theta on a sphere is the degree-2 spherical harmonic R sin^2 cos 2theta:
    phi = -R v_n / 3 on the surface, I_2 = 16 pi rho R^5 / 45 (Lamb 1932, sec. 84-86)."""
    t = np.linspace(0.0, np.pi, 400)[::-1]
    R = 0.4
    i2 = mode_inertia(R * np.cos(t), R * np.sin(t), mode=2, rho=RHO)
    assert i2 == pytest.approx(16 * np.pi * RHO * R ** 5 / 45, rel=1e-3)


@pytest.mark.parametrize("m", [2, 3, 4])
def test_long_cylinder_tends_to_the_2d_value(m):
    """rho pi r^4 / m per unit length (2D multipole); end relief ~ r/L."""
    vals = []
    for length in (10.0, 40.0):
        x = np.linspace(-length / 2, length / 2, 200)
        vals.append(mode_inertia(x, np.full_like(x, 0.5), mode=m, rho=RHO, panels=300)
                    / (RHO * np.pi * 0.5 ** 4 / m * length))
    assert vals[0] < vals[1] < 1.0
    assert vals[1] == pytest.approx(1.0, abs=0.01)
    assert 1.0 - vals[0] == pytest.approx(4.0 * (1.0 - vals[1]), rel=0.25)   # ~ 1/L


def rect(y0, y1, z0, z1):
    return np.array([[y0, z0], [y1, z0], [y1, z1], [y0, z1]])


def test_symmetry_orders():
    assert roll_symmetry_order([rect(-0.3, 0.3, -0.075, 0.075)]) == 2
    square = rect(-0.1, 0.1, -0.1, 0.1)
    assert roll_symmetry_order([square]) == 4
    cross = [np.array([[-0.2, -0.01], [-0.01, -0.01], [-0.01, -0.2], [0.01, -0.2], [0.01, -0.01],
                       [0.2, -0.01], [0.2, 0.01], [0.01, 0.01], [0.01, 0.2], [-0.01, 0.2],
                       [-0.01, 0.01], [-0.2, 0.01]])]
    assert roll_symmetry_order(cross) == 4
    ell = [np.array([[0, 0], [0.3, 0], [0.3, 0.05], [0.05, 0.05], [0.05, 0.2], [0, 0.2]])]
    assert roll_symmetry_order(ell) == 2


def lamb_plate_roll_ratio(a, b):
    """Exact 3D / strip roll added mass of an elliptic plate (semi-axes a along x, b span)
    rotating about x: Lamb (1932) sec. 373 ellipsoid (c -> 0) over the strip integral
    int rho pi b(x)^4 / 8 dx = (2/15) rho pi a b^4."""
    c = 1e-7 * b
    al = 2 / 3 * a * b * c * elliprd(b * b, c * c, a * a)
    be = 2 / 3 * a * b * c * elliprd(a * a, c * c, b * b)
    vol = 4 / 3 * np.pi * a * b * c
    i3 = 0.2 * vol * (b * b - c * c) ** 2 * (2 - al - 2 * be) / ((b * b + c * c) * (al + 2 * be) - 4 * c * c)
    return i3 / (2 / 15 * np.pi * a * b ** 4)


@pytest.mark.parametrize("ratio, low, high", [(0.25, 0.97, 1.0), (1.0, 0.88, 0.94),
                                              (3.56, 0.78, 0.84)])
def test_elliptic_plate_against_lamb(ratio, low, high):
    """The roll-equivalent body (mode 2) against the exact elliptic plate: the documented
    deviation (docs/theory.md sec. 6): -1 % at b/a = 0.25, -9 % at 1, -19 % at 3.56."""
    a, b = 1.0, ratio
    x, dx = uniform_stations(-a, a, 200)
    m44 = RHO * np.pi * (b * np.sqrt(np.clip(1 - x ** 2 / a ** 2, 0, None))) ** 4 / 8
    st = Strips(x=x, dx=dx)
    f = roll_relief(st, m44, rho=RHO, mode=2)
    assert low < f / lamb_plate_roll_ratio(a, b) < high


# Capytaine (direct, no free surface) on the benchmark finned torpedo
# (benchmarks/mesh_shapes.finned_torpedo), 9,390 faces: roll added mass [kg m^2]
TORPEDO_BEM_ROLL = 0.0136071


def finned_torpedo():
    """Myring hull (REMUS-like, Prestero 2001 table 2.1) + 4 box fins, not unioned (the
    slicer unites overlapping bodies per strip); as benchmarks/mesh_shapes.finned_torpedo."""
    a, b, c, d = 0.191, 0.654, 0.541, 0.191
    length = a + b + c
    x0 = -0.5 * length
    x = x0 + length * 0.5 * (1.0 - np.cos(np.linspace(0.0, np.pi, 121)))
    tail_end, mid_end = x0 + c, x0 + c + b
    r = np.where(x < tail_end, myring_tail(x, x0, tail_end, 0.5 * d, np.radians(25.0)),
                 np.where(x > mid_end, myring_nose(x, mid_end, x0 + length, 0.5 * d, 2.0), 0.5 * d))
    r[0] = r[-1] = 0.0
    parts = [revolved_mesh(x, r, sections=48)]
    r_root, span = 0.5 * d * 0.55, 0.09
    for ang in (0.0, 0.5 * np.pi, np.pi, 1.5 * np.pi):
        box = trimesh.creation.box([0.08, 0.012, r_root + span])
        box.apply_translation([x0 + 0.17, 0.0, 0.5 * (r_root + span)])
        box.apply_transform(trimesh.transformations.rotation_matrix(ang, [1, 0, 0]))
        parts.append(box)
    return trimesh.util.concatenate(parts)


def test_finned_torpedo_roll_against_bem():
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        st = mesh_body(finned_torpedo(), origin="file").strips(200)
    vol, cb = displaced_volume(st)
    m, _ = added_mass(st, RHO, about=cb, volume=vol, center=cb)
    assert m[3, 3] == pytest.approx(TORPEDO_BEM_ROLL, rel=0.05)
