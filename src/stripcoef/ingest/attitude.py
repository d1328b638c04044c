r"""Attitude of a log in any convention, brought to the package's: NED, FRD, Euler zyx.

A log gives the attitude as Euler angles (zyx: roll, pitch, yaw) or as a unit quaternion,
in an earth-fixed frame NED or ENU and body axes FRD or FLU.  Everything goes through the
rotation matrix :math:`R` (body to world):

.. math:: R_{NED \leftarrow FRD} = A_{world}\, R_{world \leftarrow body}\, A_{body}

with :math:`A_{world}` from :func:`stripcoef.conventions.world_axes_operator` and
:math:`A_{body}` the first block of :func:`stripcoef.conventions.axes_operator` (both their
own inverse). Body rates come from the attitude by :math:`\dot R = R\,S(\omega)`.
"""

from __future__ import annotations

import warnings

import numpy as np
from scipy.spatial.transform import Rotation

from stripcoef.conventions import axes_operator, rotation_matrix, world_axes_operator
from stripcoef.errors import InputError

QUATERNION_ORDERS = ("wxyz", "xyzw")
#: Largest accepted deviation of a logged quaternion's norm from 1 [-] (beyond: wrong columns).
QUATERNION_NORM_TOLERANCE = 0.05


def euler_matrices(phi, theta, psi) -> np.ndarray:
    r"""Body-to-NED rotations :math:`R_{zyx}(\phi,\theta,\psi)` of n samples, shape (n, 3, 3).

    The vectorised form of :func:`stripcoef.conventions.rotation_matrix` (the one
    definition, called on arrays); angles [rad], R [-].

    References
    ----------
    Fossen (2011), eq. 2.18.
    """
    r = rotation_matrix(np.asarray(phi, float), np.asarray(theta, float),
                        np.asarray(psi, float))
    return np.moveaxis(np.asarray(r, dtype=float), -1, 0) if r.ndim == 3 else r[None]


def quaternion_matrices(q, *, file: str | None = None, key: str | None = None) -> np.ndarray:
    r"""Rotation matrices of unit quaternions :math:`q = [\eta, \varepsilon_1, \varepsilon_2,
    \varepsilon_3]` (scalar first), shape (n, 3, 3).

    .. math:: R(q) = I_3 + 2\eta\,S(\varepsilon) + 2\,S(\varepsilon)^2

    Each quaternion is normalised; a norm off 1 by more than
    :data:`QUATERNION_NORM_TOLERANCE` is an error (the columns are probably not a quaternion).

    Parameters
    ----------
    q : (n, 4) array
        Quaternions, scalar first [-]

    Computed by ``scipy.spatial.transform.Rotation``.

    References
    ----------
    Fossen (2011), sec. 2.2.2 (unit quaternions, R(q)).
    """
    q = np.atleast_2d(np.asarray(q, dtype=float))
    norm = np.linalg.norm(q, axis=1)
    bad = np.nonzero(np.abs(norm - 1.0) > QUATERNION_NORM_TOLERANCE)[0]
    if bad.size:
        k = int(bad[0])
        raise InputError(f"not a unit quaternion at sample {k + 1}", file=file, key=key,
                         value=round(float(norm[k]), 6),
                         expected=f"a norm within {QUATERNION_NORM_TOLERANCE} of 1 "
                         "(check the columns and their order)")
    # scipy's Rotation (scalar last) is the one quaternion implementation
    return Rotation.from_quat((q / norm[:, None])[:, [1, 2, 3, 0]]).as_matrix()


def to_ned_frd(r, *, world: str = "NED", body: str = "FRD") -> np.ndarray:
    r"""Rotations of a log's frames brought to NED/FRD,
    :math:`R_{NED \leftarrow FRD} = A_{world} R A_{body}` (module docstring), (n, 3, 3) [-].

    References
    ----------
    Fossen (2011), sec. 2.1; ROS REP 103 (ENU, FLU).
    """
    a_w = world_axes_operator(world)
    a_b = axes_operator(body)[:3, :3]
    return np.einsum("ij,njk,kl->nil", a_w, np.asarray(r, float), a_b)


def euler_from_matrices(r) -> np.ndarray:
    r"""Euler angles zyx of body-to-NED rotations, (n, 3) [rad]:

    .. math:: \phi = \operatorname{atan2}(R_{32}, R_{33}),\quad
              \theta = -\arcsin R_{31},\quad \psi = \operatorname{atan2}(R_{21}, R_{11})

    :math:`\psi` is unwrapped (continuous over the log, as a simulation integrates it);
    :math:`\phi` and :math:`\psi` are ill-defined at :math:`\theta = \pm 90^\circ`. Computed by
    ``scipy.spatial.transform.Rotation.as_euler("ZYX")``.

    References
    ----------
    Fossen (2011), sec. 2.2.4 (Euler angles from a rotation matrix / unit quaternion).
    """
    r = np.asarray(r, float)
    with warnings.catch_warnings():       # at +-90 deg pitch: scipy warns, as the docstring says
        warnings.simplefilter("ignore", UserWarning)
        psi, theta, phi = Rotation.from_matrix(r).as_euler("ZYX").T
    return np.column_stack([phi, theta, np.unwrap(psi)])


def rotation_log(r) -> np.ndarray:
    r"""Rotation vectors of rotation matrices (matrix logarithm), (n, 3) [rad]:

    .. math:: \theta = \arccos\frac{\operatorname{tr} R - 1}{2},\quad
              \omega\theta = \frac{\theta}{2\sin\theta}
              \begin{bmatrix} R_{32}-R_{23} \\ R_{13}-R_{31} \\ R_{21}-R_{12} \end{bmatrix}

    (valid for :math:`\theta < \pi`), computed by ``scipy.spatial.transform.Rotation``.

    References
    ----------
    Murray, Li & Sastry (1994), A Mathematical Introduction to Robotic Manipulation,
    sec. 2.2 (exponential coordinates of SO(3), the logarithm).
    """
    return Rotation.from_matrix(np.asarray(r, float)).as_rotvec()


def body_rates(t, r) -> np.ndarray:
    r"""Body angular velocity :math:`\omega = [p, q, r]` [rad/s] from sampled attitude.

    From :math:`\dot R = R\,S(\omega)`: over a step with constant :math:`\omega`,
    :math:`R_{k+1} = R_k \exp(S(\omega)\,\Delta t)`, so

    .. math:: \omega_{k+1/2} = \log(R_k^T R_{k+1}) / (t_{k+1} - t_k)

    (:func:`rotation_log`), exact for a constant rate over the step and second-order
    accurate at the midpoints; the midpoint rates are interpolated linearly to the samples
    (the first and last sample take the nearest midpoint's rate). Noise on the attitude is
    amplified by 1/dt: smooth or fit rates from a gyro when the log has them.

    Parameters
    ----------
    t : (n,) array
        Strictly increasing sample times [s], n >= 2
    r : (n, 3, 3) array
        Body-to-NED rotations [-]

    References
    ----------
    Fossen (2011), sec. 2.2.1 (:math:`\dot R = R S(\omega)`); Murray, Li & Sastry (1994),
    sec. 2.2.
    """
    t = np.asarray(t, float)
    r = np.asarray(r, float)
    dr = np.einsum("nji,njk->nik", r[:-1], r[1:])      # R_k^T R_{k+1}
    mid = rotation_log(dr) / np.diff(t)[:, None]
    tm = 0.5 * (t[:-1] + t[1:])
    return np.column_stack([np.interp(t, tm, mid[:, i]) for i in range(3)])
