"""The vectorised section path (all rings of all sections at once).

`panel._RingSet` cleans, orients, measures and resamples every ring of every section in
padded arrays; `added_mass_sections`, `discretise`, the polygon drag geometry and the wetted
perimeter use it.  The panel method has one implementation (a single section is the case of
one); these tests hold batching to its one-section result, and the ring set to the one-ring
functions that other stages still use (`orient_contours`, `ring_centroid`,
`polygon_drag._parts_geometry` ...), on mixed sections: holes, several parts, sharp corners,
either orientation, closing and repeated points, rings of different lengths, empty sections.
"""

import numpy as np
import pytest

from stripcoef.errors import InputError
from stripcoef.geometry.polygons import ring_centroid, ring_shape, signed_area
from stripcoef.sections import polygon_drag, section_drag
from stripcoef.sections.panel import (
    _interp_rows,
    _ring_set,
    _solve_batch,
    added_mass_sections,
    discretise,
    orient_contours,
    part_rings,
)
from stripcoef.strips import Part

RHO = 1025.0


def ellipse(a, b, n, y0=0.0, z0=0.0):
    th = np.linspace(0.0, 2.0 * np.pi, n, endpoint=False)
    return np.column_stack([y0 + a * np.cos(th), z0 + b * np.sin(th)])


def rect(b, h, y0=0.0, z0=0.0):
    return np.array([[-b, -h], [b, -h], [b, h], [-b, h]]) + [y0, z0]


def mixed_sections():
    rng = np.random.default_rng(7)
    noisy = ellipse(0.2, 0.15, 50) + rng.normal(0.0, 1e-3, (50, 2))
    circle = ellipse(0.3, 0.3, 40)
    return [
        [ellipse(0.3, 0.3, 200)],
        [np.vstack([ellipse(0.3, 0.3, 97)[::-1], ellipse(0.3, 0.3, 97)[-1:]])],  # CW, closed
        [ellipse(1.0, 0.2, 150)],                                    # slender: more panels
        [rect(0.2, 0.1)], [rect(0.2, 0.1)[::-1]],                    # sharp corners
        [np.array([[0, 0], [2, 0], [2, 1], [1, 1], [1, 2], [0, 2]], float)],   # L shape
        [ellipse(0.5, 0.5, 120), ellipse(0.4, 0.4, 80)],             # ring: hole, both CCW
        [ellipse(0.4, 0.4, 60)[::-1], ellipse(0.5, 0.5, 200)[::-1]],  # short reversed ring
        [ellipse(0.1, 0.1, 60, y0=-0.5), ellipse(0.1, 0.1, 64, y0=0.5)],   # two parts
        [rect(0.1, 0.1, z0=-0.2), rect(0.1, 0.1, z0=0.2), ellipse(0.05, 0.05, 40, y0=0.5)],
        [rect(1, 1), rect(0.5, 0.5)],                                # square duct
        [],                                                          # no material
        [noisy],
        [np.vstack([circle, circle[:1] * (1 + 1e-14)])],             # near-equal closing point
        [np.repeat(circle, 2, axis=0)],                              # every point twice
        None,
    ]


def one_by_one(sections, about, panels):
    """Each section on its own: orient, discretise (a ring set of one section) and solve."""
    out = np.zeros((len(sections), 3, 3))
    for s, c in enumerate(sections):
        if not c:
            continue
        rings = orient_contours(c)
        nodes = discretise(c, panels=panels)
        p1 = np.vstack(nodes)
        p2 = np.vstack([np.roll(r, -1, axis=0) for r in nodes])
        holes, start = [], 0
        for r in nodes:
            if signed_area(r) < 0:
                holes.append(slice(start, start + len(r)))
            start += len(r)
        point = ring_centroid(rings) if about is None else about
        out[s] = _solve_batch(p1[None], p2[None], [holes], np.array([point], float), RHO)[0]
    return out


@pytest.mark.parametrize("panels", [None, 0, 32, 64])
@pytest.mark.parametrize("about", [None, (0.1, -0.05)])
def test_added_mass_of_sections_together_equals_each_alone(panels, about):
    secs = mixed_sections()
    batch = added_mass_sections(secs, rho=RHO, about=about, panels=panels)
    ref = one_by_one(secs, about, panels)
    np.testing.assert_allclose(batch, ref, rtol=1e-12, atol=1e-12 * np.abs(ref).max())
    assert np.all(batch[[11, 15]] == 0.0)


def test_ring_set_is_cleaned_and_oriented_like_orient_contours():
    secs = mixed_sections()
    rs = _ring_set(secs)
    rings = [r for c in secs if c for r in orient_contours(c)]
    assert rs.count.tolist() == [len(r) for r in rings]
    for r, ring in enumerate(rings):
        assert np.array_equal(rs.ring(r), ring)
        seg, turn = ring_shape(ring)
        assert np.array_equal(rs.shape(r)[0], seg) and np.array_equal(rs.shape(r)[1], turn)
        assert np.sign(rs.area[r]) == np.sign(signed_area(ring))
    cent = rs.centroids()
    for s, c in enumerate(secs):
        want = ring_centroid(orient_contours(c)) if c else (0.0, 0.0)
        assert tuple(cent[s]) == want


def polygon_part(sections):
    pts = [np.vstack(c) for c in sections]
    return Part(name="p", shape="polygon", index=np.arange(len(sections)), y=0.0, z=0.0,
                half_breadth=[0.5 * np.ptp(p[:, 0]) for p in pts],
                half_height=[0.5 * np.ptp(p[:, 1]) for p in pts], area=1.0,
                contours=sections, role="hull")


def test_drag_geometry_equals_the_per_section_rule():
    secs = [c for c in mixed_sections() if c]
    part = polygon_part(secs)
    data = polygon_drag._part_cache(part)
    # the whole part at once equals each section's geometry on its own
    geoms = [polygon_drag._ring_set_geometry(_ring_set([c]), [c]) for c in secs]
    owner = np.concatenate([np.full(g["owner"].size, i) for i, g in enumerate(geoms)])
    assert np.array_equal(data["owner"], owner)
    assert np.array_equal(data["rounded"], np.concatenate([g["rounded"] for g in geoms]))
    for key in ("y", "z"):
        for i in range(4):
            assert np.array_equal(data[key][i], np.concatenate([g[key][i] for g in geoms]))
    # and the coefficients are those of section_cross_flow_drag, section by section
    re = np.geomspace(2e4, 1e6, len(secs))
    cd_y, cd_z = section_drag(part, re, 2 * re)
    for s, c in enumerate(secs):
        one = polygon_drag.section_cross_flow_drag(c, reynolds_y=re[s], reynolds_z=2 * re[s])
        assert cd_y[s] * 2 * part.half_height[s] == pytest.approx(one["cd_y"] * one["height_y"],
                                                                  rel=1e-12)
        assert cd_z[s] * 2 * part.half_breadth[s] == pytest.approx(one["cd_z"] * one["height_z"],
                                                                   rel=1e-12)


def test_perimeter_and_ring_cache():
    from stripcoef.assembly.damping import wetted_perimeter
    secs = [c for c in mixed_sections() if c]
    part = polygon_part(secs)
    # reference: the sum of each ring's edge lengths, ring by ring
    ref = [sum(float(np.linalg.norm(np.roll(r, -1, axis=0) - r, axis=1).sum()) for r in rings)
           for rings in part.contours]
    np.testing.assert_allclose(wetted_perimeter(part), ref, rtol=1e-11)
    rs = part_rings(part)
    assert part_rings(part) is rs                       # built once per part ...
    part.contours = secs[:3]
    part.index = np.arange(3)
    assert part_rings(part) is not rs and part_rings(part).nsec == 3   # ... and per contours


def test_interp_rows_is_numpy_interp():
    """Row-wise interpolation with the shift trick, on rows whose knots are closer than the
    rounding of the shift (many rows, tiny spacing), at knots, between and past the end."""
    rng = np.random.default_rng(1)
    nr, nk = 300, 12
    last = rng.integers(3, nk, nr)
    xp = np.cumsum(rng.uniform(1e-15, 1e-13, (nr, nk)), axis=1) + 1.0
    xp[:, 0] = 1.0
    for r in range(nr):
        xp[r, last[r] + 1:] = xp[r, last[r]]                          # padding: the last knot
    fp = rng.normal(size=(nr, nk))
    x = np.concatenate([xp[:, :5], np.sort(rng.uniform(1.0, xp.max(axis=1)[:, None] * (1 + 1e-16),
                                                       (nr, 6)), axis=1)], axis=1)
    (got,) = _interp_rows(x, xp, [fp], last)
    for r in range(nr):
        want = np.interp(x[r], xp[r, :last[r] + 1], fp[r, :last[r] + 1])
        assert np.array_equal(got[r], want), r


def test_invalid_rings_raise_the_one_ring_error():
    good = [ellipse(1.0, 1.0, 40)]
    for bad, match in [(np.zeros((5, 3)), "contour must be"), ([[0, 0], [1, np.nan], [0, 1]],
                                                                 "non-finite"),
                       ([[0, 0], [1, 0], [1, 0], [0, 0]], "fewer than 3"),
                       ([[0, 0], [1, 0], [2, 0]], "zero area")]:
        secs = [good, good, [ellipse(0.5, 0.5, 30), np.asarray(bad, float)]]
        with pytest.raises(InputError, match=match) as err:
            added_mass_sections(secs, rho=RHO)
        with pytest.raises(InputError) as ref:
            orient_contours(secs[2], "sections[2]")
        assert str(err.value) == str(ref.value)
    with pytest.raises(InputError, match="rho"):
        added_mass_sections([good], rho=0.0)


def test_damping_exponents_use_one_call_per_perturbation():
    """local_exponent with (Re_y, Re_z) equals one exponent at a time."""
    from stripcoef.assembly.damping import local_exponent
    part = polygon_part([c for c in mixed_sections() if c])
    re_y = np.geomspace(1e4, 3e6, part.index.size)
    re_z = re_y[::-1].copy()
    n_y, n_z = local_exponent(lambda ry, rz: section_drag(part, ry, rz), re_y, re_z)
    (one_y,) = local_exponent(lambda ry: (section_drag(part, ry, re_z)[0],), re_y)
    (one_z,) = local_exponent(lambda rz: (section_drag(part, re_y, rz)[1],), re_z)
    assert np.array_equal(n_y, one_y) and np.array_equal(n_z, one_z)
