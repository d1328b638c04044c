r"""3D boundary-element cross-check with Capytaine (optional extra ``stripcoef[bem]``).

The body is deeply submerged in an unbounded fluid: no free surface
(``free_surface=np.inf``), so Capytaine's Green function reduces to the Rankine
source :math:`1/(4\pi r)`, the frequency plays no role and the result is the
exact potential-flow added-mass matrix of the panelled body

.. math:: A_{ij} = -\rho \iint_S \phi_j\, n_i\, dS, \quad
          \partial\phi_j/\partial n = n_j \text{ on } S,\ i, j = 1..6

(Newman 1977, sec. 4.13-4.15, eq. 4.148; Babarit & Delhommeau 2015, "Theoretical
and numerical aspects of the open source BEM solver NEMOH", EWTEC, for the
solver that Capytaine builds on).  The ``direct`` (Green's identity) method is
used: it converges at second order where the default ``indirect`` (source)
method is 2-3 % high at a few thousand panels (measured on spheroid meshes against
Lamb's exact values: benchmarks/mesh_reference_convergence.py).

Trap avoided: ``capytaine.assemble_dataset`` silently drops results with an
infinite free surface, so each result's ``added_mass`` is read directly.

Cost is dense O(N^2) memory and O(N^3) time: about 2 s at 2.5k triangles,
10 s and 2.5 GB at 6.4k, 45 s and 9 GB at 12.7k on this machine, so meshes
above :data:`MAX_FACES` are refused unless the caller raises the limit.
"""

from __future__ import annotations

import time
from pathlib import Path

import numpy as np

from stripcoef.errors import InputError
from stripcoef import progress

#: Capytaine's DOF names in stripcoef's order (surge, sway, heave, roll, pitch, yaw).
CAPYTAINE_DOFS = ("Surge", "Sway", "Heave", "Roll", "Pitch", "Yaw")
#: Largest mesh (faces) solved by default; dense memory ~ 56 N^2 bytes.
MAX_FACES = 8000


#: Panel aspect ratio (longest edge over the height on it) beyond which the BEM is not trusted
#: when such panels cover more than :data:`PANEL_AREA_FRACTION` of the surface [-].
#: [assumption] constant-strength panels collocated at their centroid resolve the potential
#: across a panel only as well as its short side: a panel much longer than wide averages the
#: flow over its length (Hess & Smith 1967, sec. 4; Newman 1977 sec. 4.13 for the integral
#: equation).  Measured: trimesh's capsule primitive (1.2 m x 0.02 m panels, aspect ~60) gave
#: M_qdot -1.27 against -4.71 kg m^2 of a well-panelled mesh of the same body (issue 14).
PANEL_ASPECT_MAX = 20.0
#: Share of the wetted area in too-long panels that makes the BEM untrusted [-].
PANEL_AREA_FRACTION = 0.01


def panel_quality(mesh) -> dict:
    r"""Aspect ratios of a triangle mesh's panels, to judge a BEM run before trusting it.

    .. math:: \mathrm{AR} = \frac{\ell_{max}}{h},\qquad h = \frac{2 A}{\ell_{max}}

    (longest edge :math:`\ell_{max}` [m], area A [m^2], h the height onto the longest edge).
    Returns ``max_aspect`` [-], ``area_fraction`` [-] of the surface in panels with AR >
    :data:`PANEL_ASPECT_MAX`, and ``trusted`` (that fraction <= :data:`PANEL_AREA_FRACTION`).
    See :data:`PANEL_ASPECT_MAX` for the reference and the measured failure.
    """
    tri = np.asarray(mesh.triangles, dtype=float)
    edges = np.linalg.norm(tri[:, [1, 2, 0]] - tri, axis=2)
    longest = edges.max(axis=1)
    area = 0.5 * np.linalg.norm(np.cross(tri[:, 1] - tri[:, 0], tri[:, 2] - tri[:, 0]), axis=1)
    ok = area > 0
    aspect = np.full(area.shape, np.inf)
    aspect[ok] = longest[ok] ** 2 / (2.0 * area[ok])
    bad = aspect > PANEL_ASPECT_MAX
    frac = float(area[bad].sum() / max(area.sum(), 1e-300))
    return {"max_aspect": float(aspect[ok].max()) if ok.any() else float("inf"),
            "area_fraction": frac, "trusted": frac <= PANEL_AREA_FRACTION,
            "limit": PANEL_ASPECT_MAX}


def _capytaine():
    try:
        import capytaine as cpt  # noqa: PLC0415  (optional extra)
    except ImportError:
        raise InputError("the BEM cross-check needs Capytaine, which is not installed",
                         key="method",
                         expected="pip install 'stripcoef[bem]'") from None
    import logging
    logging.getLogger("capytaine").setLevel(logging.ERROR)
    return cpt


def _as_trimesh(mesh_or_path, load_kw):
    import trimesh

    from stripcoef.geometry.mesh import MeshBody, load_mesh
    if isinstance(mesh_or_path, MeshBody):
        return mesh_or_path.mesh
    if isinstance(mesh_or_path, trimesh.Trimesh):
        return mesh_or_path
    if isinstance(mesh_or_path, (str, Path)):
        return load_mesh(mesh_or_path, **load_kw).mesh
    raise InputError("not a mesh", key="mesh", value=type(mesh_or_path).__name__,
                     expected="a mesh file path, a MeshBody or a trimesh.Trimesh")


def bem_added_mass(mesh_or_path, *, rho: float, reference_point=(0.0, 0.0, 0.0),
                   max_faces: int = MAX_FACES, method: str = "direct",
                   **load_kw) -> np.ndarray:
    r"""6x6 added-mass matrix of a closed mesh in unbounded fluid by Capytaine's BEM.

    .. math:: A_{ij} = -\rho \iint_S \phi_j n_i\, dS

    Parameters
    ----------
    mesh_or_path : str, Path, MeshBody or trimesh.Trimesh
        The body in FRD body axes [m] (a path is read with
        :func:`stripcoef.geometry.mesh.load_mesh` and ``load_kw``).
    rho : float
        Fluid density [kg/m^3]
    reference_point : (3,)
        Point about which rotations and moments are taken, body axes [m]
    max_faces : int
        Refuse larger meshes (memory and time grow as N^2 and N^3).
    method : {"direct", "indirect"}
        Capytaine's BEM formulation (``direct`` is the accurate one).

    Returns
    -------
    (6, 6) array
        M_A in [kg, kg m, kg m^2], DOF order surge, sway, heave, roll, pitch,
        yaw, symmetrised.

    References
    ----------
    Newman (1977) *Marine Hydrodynamics*, sec. 4.13-4.15; Ancellin & Dias (2019),
    "Capytaine: a Python-based linear potential flow solver", JOSS 4(36), 1341.
    """
    cpt = _capytaine()
    if not np.isfinite(rho) or rho <= 0:
        raise InputError("fluid density must be positive", key="rho", value=rho,
                         expected="> 0 kg/m^3")
    if method not in ("direct", "indirect"):
        raise InputError("unknown BEM method", key="method", value=method,
                         expected="direct or indirect")
    tm = _as_trimesh(mesh_or_path, load_kw)
    n = len(tm.faces)
    if n > max_faces:
        raise InputError(f"mesh has {n} faces, too many for the dense BEM "
                         f"(~{56 * n * n / 1e9:.1f} GB)", key="max_faces", value=max_faces,
                         expected=f"a decimated mesh with <= {max_faces} faces, or a higher limit")
    ref = np.asarray(reference_point, dtype=float).reshape(3)
    mesh = cpt.Mesh(vertices=np.asarray(tm.vertices, dtype=float),
                    faces=np.asarray(tm.faces, dtype=int), name="body")
    body = cpt.FloatingBody(mesh=mesh, dofs=cpt.rigid_body_dofs(rotation_center=tuple(ref)),
                            name="body")
    problems = [cpt.RadiationProblem(body=body, radiating_dof=d, free_surface=np.inf,
                                     omega=np.inf, rho=float(rho)) for d in CAPYTAINE_DOFS]
    results = cpt.BEMSolver(method=method).solve_all(problems, progress_bar=progress.enabled())
    a = np.zeros((6, 6))
    for j, res in enumerate(results):           # column j: motion in DOF j
        for i, d in enumerate(CAPYTAINE_DOFS):
            a[i, j] = float(np.real(res.added_mass[d]))
    return 0.5 * (a + a.T)


def timed_bem_added_mass(*args, **kwargs):
    """:func:`bem_added_mass` and its wall time [s]."""
    t0 = time.perf_counter()
    a = bem_added_mass(*args, **kwargs)
    return a, time.perf_counter() - t0


def comparison_figure(strip, bem, *, name: str = "", key: str = "plot"):
    """Strip theory against the BEM, per DOF: the diagonal added mass of each DOF side by side
    (translations [kg] and rotations [kg m^2] on their own axes) and the relative difference
    of every term [%]; a :class:`matplotlib.figure.Figure` (:mod:`stripcoef.figures`).

    ``strip``, ``bem``: (6, 6) added-mass matrices M_A about the same point [kg, kg m, kg m^2].
    """
    from stripcoef.conventions import DOF, added_mass_name
    from stripcoef.figures import new_figure

    strip, bem = np.asarray(strip, float), np.asarray(bem, float)
    fig = new_figure(figsize=(12.0, 4.2), key=key)
    ax_t, ax_r, ax_d = fig.subplots(1, 3, width_ratios=[1.0, 1.0, 1.4])
    width = 0.38
    for ax, idx, unit in ((ax_t, range(3), "kg"), (ax_r, range(3, 6), "kg m^2")):
        pos = np.arange(3)
        ax.bar(pos - width / 2, [strip[i, i] for i in idx], width, label="strip theory")
        ax.bar(pos + width / 2, [bem[i, i] for i in idx], width, label="BEM (Capytaine)")
        ax.set_xticks(pos, [f"{DOF[i]}\n{added_mass_name(i, i)}" for i in idx])
        ax.set_ylabel(f"added mass M_A[i, i] [{unit}]")
        ax.set_xlabel("degree of freedom, SNAME term [-]")
        ax.grid(True, axis="y", alpha=0.3)
    ax_t.set_title("translations")
    ax_r.set_title("rotations")
    ax_r.legend(fontsize=8, loc="upper left", bbox_to_anchor=(0.0, -0.18), ncol=2)
    scale = max(np.abs(np.diag(bem)).max(), 1e-300)
    terms = [(i, j) for i in range(6) for j in range(i, 6)
             if abs(bem[i, j]) > 1e-3 * np.sqrt(abs(bem[i, i] * bem[j, j])) + 1e-12 * scale]
    diff = [100.0 * (strip[i, j] - bem[i, j]) / abs(bem[i, j]) for i, j in terms]
    ax_d.barh(np.arange(len(terms)), diff, color=["C0" if i == j else "C1" for i, j in terms])
    ax_d.set_yticks(np.arange(len(terms)), [added_mass_name(i, j) for i, j in terms],
                    fontsize=8)
    ax_d.invert_yaxis()
    ax_d.set_ylabel("SNAME term [-]")
    ax_d.axvline(0.0, color="k", lw=0.6)
    ax_d.set_xlabel("strip − BEM, relative to |BEM| [%]")
    ax_d.set_title("every non-zero term (orange: couplings)")
    ax_d.grid(True, axis="x", alpha=0.3)
    fig.suptitle((f"{name}: " if name else "") + "added mass by strip theory and by the BEM")
    return fig
