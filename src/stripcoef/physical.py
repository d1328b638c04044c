"""Whether a model is a physically possible vehicle: one check, :func:`check_physical`, run by
every path that makes or reads a model (assembly, model files, exports, limits), each failure a
one-line :class:`~stripcoef.errors.InputError` naming the key, the value and what was expected.
"""

import numpy as np

from stripcoef.errors import InputError


def _indefinite_cause(m_rb, m_a, conditions, file=None) -> tuple[str, str]:
    r"""Why :math:`M = M_{RB} + M_A` is not positive definite, and the remedy, in words.

    The eigenvector v of the smallest eigenvalue of the symmetric part names the direction
    (its DOFs with :math:`|v_i| \ge 0.3 \max|v|`); the cause is a negative diagonal term
    :math:`M_{A,ii}` in it, else the coupling with the largest
    :math:`|M_{ij}| / \sqrt{M_{ii} M_{jj}}` (a 2x2 minor is positive only if it is < 1;
    Horn & Johnson 1985, "Matrix Analysis", sec. 7.1).  The remedy follows how the added mass
    was computed (``conditions``: the 3D panel method or strip theory) and the input (``file``:
    a mesh can be repaired by ``stripcoef mesh``)."""
    from stripcoef.conventions import DOF

    total = 0.5 * ((m_rb + m_a) + (m_rb + m_a).T)
    w, vec = np.linalg.eigh(total)
    v = vec[:, 0]
    dofs = [i for i in range(6) if abs(v[i]) >= 0.3 * np.abs(v).max()]
    where = DOF[dofs[0]] + "".join((" - " if v[i] * v[dofs[0]] < 0 else " + ") + DOF[i]
                                   for i in dofs[1:])
    neg = [i for i in dofs if m_a[i, i] < 0]
    if neg:
        i = min(neg, key=lambda k: m_a[k, k])
        cause = f"along {where}: M_A[{DOF[i]}, {DOF[i]}] = {m_a[i, i]:.4g} is negative"
    else:
        d = np.sqrt(np.clip(np.diag(total), 1e-300, None))
        ratio = np.abs(total) / np.outer(d, d)
        np.fill_diagonal(ratio, 0.0)
        pairs = [(ratio[i, j], i, j) for i in dofs for j in dofs if i < j] or \
            [(ratio[i, j], i, j) for i in range(6) for j in range(i + 1, 6)]
        _, i, j = max(pairs)
        cause = (f"along {where}: the coupling M_A[{DOF[i]}, {DOF[j]}] = {m_a[i, j]:.4g} is too "
                 f"large for the diagonal (|M_ij| / sqrt(M_ii M_jj) = {ratio[i, j]:.3g} of "
                 "M_RB + M_A, at most 1)")
    method = str((conditions or {}).get("added_mass_method") or "")
    name = str(file or "FILE")
    repair = ("" if name.lower().endswith((".yaml", ".yml")) else
              f"a repaired mesh (stripcoef mesh {name} --repair -o FIXED.stl) or ")
    if "panel" in method:
        n = (conditions or {}).get("added_mass_panels") or 1600
        remedy = f"{repair}a finer panel solve (--added-mass-panels {min(2 * int(n), 6000)})"
    elif (conditions or {}).get("strips"):
        remedy = (f"{repair}more strips (--strips) or the 3D panel method "
                  "(--added-mass-method panels)")
    else:
        remedy = "check the model file's added_mass and rigid_body_mass"
    return cause, remedy


def check_physical(model, *, file: str | None = None) -> None:
    r"""Raise an :class:`InputError` if ``model`` is not a physically possible vehicle.

    Checked, each error naming the key, the value and what was expected:

    - every matrix, point and scalar finite; mass, volume and density > 0 [kg, m^3, kg/m^3];
    - :math:`M_{RB}` symmetric positive definite (Fossen 2011, eq. 3.44: a rigid body's
      kinetic energy :math:`\tfrac12\nu^T M_{RB}\nu > 0`), and so
      :math:`M = M_{RB} + M_A` (its symmetric part: the kinetic energy of body and fluid,
      Fossen 2011, sec. 6.3.1);
    - damping that dissipates: non-negative diagonals of :math:`D_L` and :math:`D_Q` and a
      positive semi-definite symmetric part of :math:`D_L`
      (:math:`\nu^T D_L \nu \ge 0`, Fossen 2011, sec. 6.4; a negative one is an energy source).

    Eigenvalue tolerances are relative to the matrix's largest entry (1e-9) [-].
    """
    def fail(key, what, value, expected):
        raise InputError(what, file=file, key=key, value=value, expected=expected)

    arrays = (("added_mass", model.added_mass), ("linear_damping", model.linear_damping),
              ("quadratic_damping", model.quadratic_damping),
              ("rigid_body_mass", model.rigid_body_mass),
              ("reference_point", model.reference_point),
              ("center_of_gravity", model.center_of_gravity),
              ("center_of_buoyancy", model.center_of_buoyancy))
    for key, arr in arrays:
        a = np.asarray(arr, dtype=float)
        if not np.all(np.isfinite(a)):
            k = np.unravel_index(int(np.flatnonzero(~np.isfinite(a))[0]), a.shape)
            fail(f"{key}[{']['.join(map(str, k))}]", "non-finite entry", float(a[k]),
                 "finite numbers (the model is not usable; from a geometry: try more "
                 "strips or another mesh axis)")
    for key in ("mass", "volume", "density"):
        v = float(getattr(model, key))
        if not (np.isfinite(v) and v > 0):
            fail(key, "not a positive number", v, "a finite number > 0")

    def lowest(m):
        m = np.asarray(m, dtype=float)
        return float(np.linalg.eigvalsh(0.5 * (m + m.T)).min()), max(1.0, float(np.abs(m).max()))

    m_rb = np.asarray(model.rigid_body_mass, dtype=float)
    low, scale = lowest(m_rb)
    if low <= 1e-12 * scale:
        fail("rigid_body_mass", "not positive definite",
             f"smallest eigenvalue {low:.4g}",
             "a positive-definite M_RB (mass > 0, inertia satisfying the triangle inequality)")
    low, scale = lowest(m_rb + np.asarray(model.added_mass, dtype=float))
    if low <= 1e-12 * scale:
        cause, remedy = _indefinite_cause(m_rb, np.asarray(model.added_mass, dtype=float),
                                          model.conditions, file)
        fail("added_mass", f"M_RB + M_A not positive definite ({cause})",
             f"smallest eigenvalue {low:.4g}", f"a positive-definite total mass matrix: {remedy}")
    for key, mat in (("linear_damping", model.linear_damping),
                     ("quadratic_damping", model.quadratic_damping)):
        mat = np.asarray(mat, dtype=float)
        for i in range(6):
            if mat[i, i] < 0.0:
                fail(f"{key}[{i}][{i}]", "drag matrix is not positive", float(mat[i, i]),
                     ">= 0 (Fossen's convention: D positive, drag opposes motion)")
    low, scale = lowest(model.linear_damping)
    if low < -1e-9 * scale:
        fail("linear_damping", "drag matrix is not positive",
             f"smallest eigenvalue of the symmetric part {low:.4g}",
             "a positive semi-definite matrix (negative damping is an energy source)")
