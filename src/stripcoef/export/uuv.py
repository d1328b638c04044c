r"""UUV Simulator / DAVE (Gazebo classic) export: ``hydrodynamic_model`` of type ``fossen``.

What the plugin reads (uuvsimulator/uuv_simulator, checked against the source)
-----------------------------------------------------------------------------
``uuv_gazebo_plugins/uuv_gazebo_plugins/src/UnderwaterObjectPlugin.cc`` reads
``<fluid_density>``, ``<flow_velocity_topic>`` and one ``<link name="...">`` per link;
``src/HydrodynamicModel.cc`` then reads, per link:

* ``<volume>``, ``<center_of_buoyancy>`` (x y z), ``<neutrally_buoyant>``, optional ``<box>``
  (below);
* ``<hydrodynamic_model><type>fossen</type>`` (``HMFossen``) with

  - ``<added_mass>``: exactly 36 numbers, row-major (``GZ_ASSERT``), **positive** M_A;
    force ``-Ma * filteredAcc`` and C_A from the full Ma (Fossen 2011, eq. 6.43);
  - ``<linear_damping>``: 6 or 36 numbers, ``DLin``;
  - ``<linear_damping_forward_speed>``: 6 or 36 numbers, ``DLinForwardSpeed``;
  - ``<quadratic_damping>``: 6 or 36 numbers, ``DNonLin``, of which
    ``ComputeDampingMatrix`` uses **only the diagonal**;

  with :math:`D = -D_{Lin} - u\,D_{LinFS} - \mathrm{diag}(D_{NonLin,ii}|\nu_i|)` and force
  :math:`-D\nu`: damping values are signed SNAME derivatives (negative), and
  ``linear_damping_forward_speed`` holds lift-type derivatives multiplied by the surge
  speed u (Y_uv, Z_uw, M_uq, N_ur: force :math:`Y = Y_{uv}\,u\,v`).

Axes and point.  The plugin flips y and z of the link-frame velocity (``ToNED``) and flips
the wrench back (``FromNED``): its parameters are in FRD when the link frame is FLU (the
Gazebo convention; with an FRD link frame they would be in FLU).  It applies the wrench
with ``AddRelativeForce``/``AddRelativeTorque``, which Gazebo classic applies at the link's
centre of gravity (``gazebo/physics/ode/ODELink.cc``: ``dBodyAddRelForce`` acts at the ODE
body origin, the CoG), while it reads ``RelativeLinearVel()`` (the link frame's velocity):
the coefficients are about the CoG and the link origin should be placed at the CoG.
``<center_of_buoyancy>`` is in link axes relative to the CoG
(``BuoyantObject.cc``: ``AddForceAtRelativePosition(buoyancyForce, GetCoB())``).

Partial submersion: ``<box>``.  ``HydrodynamicModel.cc`` (uuvsimulator/uuv_simulator at
commit bfb40cb153684a0703173117b6bbf4258e8e71c5, 2020-06-15, the repository's last; lines
67-84) reads ``<box><width/><length/><height/></box>`` inside the plugin's ``<link>`` as a
box centred on the link origin, ``Box((-width/2, -length/2, -height/2), (width/2, length/2,
height/2))``: ``width`` along link x, ``length`` along y, ``height`` along z [m] (it replaces
Gazebo's bounding box, which its FIXME says is invalid).  ``BuoyantObject::GetBuoyancyForce``
(``BuoyantObject.cc`` lines 82-120) uses only its height H: with the link origin at depth
z < 0 (world z up, surface at 0), the buoyant volume is V for z < -H/2 and
:math:`V (|z| + H/2) / H` for -H/2 < z < 0 (and none for z > 0).  The export writes the
body's extents: width = L, length = B, height = H (``Conditions.length``, ``breadth``,
``height``); the linear law is exact for a prism centred on the CoG, an approximation
otherwise.  A model file without breadth and height (written before they were recorded)
gets no ``<box>`` and a comment saying so.

Trap warnings (:class:`SimulatorTrapWarning`): quadratic cross terms (dropped, the plugin
reads only the diagonal); an added-mass diagonal term larger than the rigid-body term (the
plugin applies added mass explicitly from a filtered finite-difference acceleration, which
its own ``ComputeAcc`` comment says "can lead to an oscillating system"; issues #181, #96).
"""

from __future__ import annotations

from dataclasses import replace
from xml.sax.saxutils import escape

import numpy as np

from stripcoef.conventions import quadratic_damping_name
from stripcoef.export._common import (ExportFormat, ExportView, clean, explicit_added_mass_trap, fmt, header_lines, trap,
                      xml_comment)

NAME = "uuv"

PLUGIN_FILENAME = "libuuv_underwater_object_ros_plugin.so"


def parameter_axes(link_axes: str) -> str:
    """Axes the plugin's parameters are in for a link frame in ``link_axes`` (ToNED flips y, z)."""
    return "FRD" if link_axes == "FLU" else "FLU"


def _row(values) -> str:
    return " ".join(fmt(v) for v in np.ravel(values))


def _matrix_lines(m: np.ndarray, indent: str) -> list[str]:
    return [indent + "  " + _row(row) for row in m]


def _box(model):
    """(width, length, height) [m] of the plugin's ``<box>``: the body's extents along link
    x, y, z (module docstring), or None when the model does not record them."""
    c = model.conditions
    dims = [c.length, c.breadth, c.height]
    if any(d is None or not np.isfinite(d) or d <= 0 for d in dims):
        return None
    return tuple(float(d) for d in dims)


def render(view: ExportView, *, link_name: str = "base_link") -> str:
    """The plugin block for one link (``view``: the model about the CoG, link axes)."""
    model = view.model
    link_axes = view.axes
    params = replace(view, axes=parameter_axes(link_axes))
    ma = clean(params.matrix("added_mass"))
    dl = clean(params.matrix("linear_damping"))
    dq = clean(params.matrix("quadratic_damping"))
    mrb = clean(params.matrix("rigid_body_mass"))
    lift = clean(params.matrix("lift"))
    cob = view.r_b          # link axes, relative to the CoG
    ig = clean(view.inertia_about_cg())

    dropped = [(i, j) for i in range(6) for j in range(6) if i != j and dq[i, j] != 0.0]
    if dropped:
        dropped.sort(key=lambda ij: -abs(dq[ij]))
        names = ", ".join(f"{quadratic_damping_name(i, j)} = {-dq[i, j]:.4g}"
                          for i, j in dropped[:6])
        if len(dropped) > 6:
            names += f" and {len(dropped) - 6} smaller"
        trap("uuv: the UUV Simulator plugin uses only the diagonal of quadratic_damping "
             f"(HydrodynamicModel.cc, ComputeDampingMatrix); dropped cross terms: {names}")

    explicit_added_mass_trap(
        "uuv", ma, mrb,
        "the plugin applies -M_A times a filtered finite-difference acceleration of the "
        "previous step, which oscillates or diverges (HydrodynamicModel.cc ComputeAcc; "
        "UUV Simulator issues #181, #96)")

    notes = header_lines(view, NAME)
    notes += [
        f"link '{link_name}': link frame {link_axes}; place the link origin at the CoG (the plugin",
        "reads the link-frame velocity and applies the wrench at the CoG).",
        f"Parameters in {params.axes} about the CoG (the plugin's ToNED flips y and z).",
        "added_mass: +M_A (kg, kg m, kg m^2), row-major. Damping: signed SNAME derivatives",
        "(negative): linear_damping = -D_L, quadratic_damping = diag(-D_Q) (the plugin reads",
        "only the diagonal), linear_damping_forward_speed = lift-type terms times u.",
        f"center_of_buoyancy: CB - CG in link axes ({link_axes}) [m].",
        f"Link inertial (URDF/SDF): mass {fmt(model.mass)} kg at the link origin, inertia about the",
        f"CoG in link axes: ixx {fmt(ig[0, 0])} ixy {fmt(ig[0, 1])} ixz {fmt(ig[0, 2])} "
        f"iyy {fmt(ig[1, 1])} iyz {fmt(ig[1, 2])} izz {fmt(ig[2, 2])} kg m^2.",
    ]
    box = _box(model)
    if box is None:
        notes.append("No <box>: the model has no breadth and height (re-estimate it); the "
                     "plugin then uses Gazebo's bounding box for partial submersion.")
    else:
        notes += [f"<box>: the body's extents along link x, y, z (width {fmt(box[0])}, length "
                  f"{fmt(box[1])}, height {fmt(box[2])} m), centred on the link origin; the",
                  "plugin scales buoyancy linearly over the height near the surface "
                  "(BuoyantObject.cc)."]
    if model.thrusters:
        notes.append("Thrusters not exported here: " + ", ".join(t.name for t in model.thrusters)
                     + " (uuv_thruster_ros_plugin per thruster).")
    notes += [
        "linear_damping_forward_speed = -L, the model's lift (body and fin lift: Y_uv, N_ur, ...,",
        "force -u L nu; Prestero 2001 sec. 3.6); the Munk part of the u-terms is in C_A(nu), which",
        "the plugin builds itself from added_mass.",
    ]
    if model.control_surfaces:
        notes.append("Control surfaces not exported here: " + ", ".join(
            s.name for s in model.control_surfaces) + " (uuv_fin_ros_plugin per fin).")

    ind = "      "
    out = ['<?xml version="1.0" ?>', *xml_comment(notes)]
    out.append(f'<plugin name="uuv_plugin" filename="{PLUGIN_FILENAME}">')
    out.append(f"  <fluid_density>{fmt(model.density)}</fluid_density>")
    out.append("  <flow_velocity_topic>hydrodynamics/current_velocity</flow_velocity_topic>")
    out.append(f'  <link name="{escape(link_name, {chr(34): "&quot;"})}">')
    out.append("    <neutrally_buoyant>0</neutrally_buoyant>")
    out.append(f"    <volume>{fmt(model.volume)}</volume>")
    out.append(f"    <center_of_buoyancy>{_row(cob)}</center_of_buoyancy>")
    if box is not None:
        out.append("    <box>")
        out += [f"      <{k}>{fmt(v)}</{k}>" for k, v in zip(("width", "length", "height"), box)]
        out.append("    </box>")
    out.append("    <hydrodynamic_model>")
    out.append("      <type>fossen</type>")
    out.append("      <added_mass>")
    out += _matrix_lines(ma, ind)
    out.append("      </added_mass>")
    out.append("      <linear_damping>")
    out += _matrix_lines(-dl, ind)
    out.append("      </linear_damping>")
    if np.any(lift):
        out.append("      <linear_damping_forward_speed>")
        out += _matrix_lines(-lift, ind)
        out.append("      </linear_damping_forward_speed>")
    else:
        out.append(f"      <linear_damping_forward_speed>{_row(np.zeros(6))}"
                   "</linear_damping_forward_speed>")
    out.append(f"      <quadratic_damping>{_row(-np.diag(dq))}</quadratic_damping>")
    out.append("    </hydrodynamic_model>")
    out.append("  </link>")
    out.append("</plugin>")
    return "\n".join(out) + "\n"


#: This format's entry of the registry :data:`stripcoef.export.FORMATS`.
FORMAT = ExportFormat(
    name=NAME,
    description="UUV Simulator / DAVE classic hydrodynamic_model 'fossen' (FRD parameters, about the CoG)",
    suffix=".xml",
    render=render,
    axes_allowed=("FLU", "FRD"),
    default_axes="FLU",
    default_point="CG",
    points_allowed=("CG",),      # the plugin applies forces at the CoG: no other point
    options=("link_name",))
