r"""Gazebo (gz-sim) export: the ``Hydrodynamics`` system plugin plus ``<fluid_added_mass>``.

What the consumers read (checked against their sources)
-------------------------------------------------------
* gz-sim ``src/systems/hydrodynamics/Hydrodynamics.cc`` (``Hydrodynamics::Configure``)
  loops over ``"xyzkmn"`` (force axis ``i``) and ``"UVWPQR"`` (velocity ``j``, ``k``)
  and reads, each defaulting to 0:

  - ``<{f}{V}>`` linear derivatives, e.g. ``<xU>`` = X_u, ``<nV>`` = N_v;
  - ``<{f}{Vj}abs{Vk}>`` quadratic derivatives; ``HydrodynamicsUtils.hh``
    ``buildDampingMatrix`` makes the applied force
    :math:`F_i = \sum_j c_{ij} x_j + \sum_{j,k} c_{ijk} |x_k| x_j`, so the
    Fossen term :math:`-D_{Q,ij}|\nu_j|\nu_j` is the tag ``<{f_i}{V_j}abs{V_j}>``
    with value :math:`-D_{Q,ij}` (X_u|u| -> ``<xUabsU>``, N_v|v| -> ``<nVabsV>``);
  - ``<{f}Dot{V}>`` legacy added mass, applied explicitly as ``+Ma * stateDot``
    with ``Ma`` = the SNAME derivative (X_udot < 0); its Coriolis matrix
    (``buildCoriolisMatrix``) uses **only the diagonal** of ``Ma``;
  - ``<link_name>``.

  The lift terms (force :math:`-uL\nu`, Prestero 2001 sec. 3.6) are written as
  ``<{f_i}{V_j}absU>`` = :math:`-L_{ij}`: the plugin's :math:`|u|\,v_j` equals
  :math:`u\,v_j` in forward motion (they differ when reversing, where fin lift is poorly
  known anyway).

  Values are signed SNAME derivatives, hence negative for damping and legacy added
  mass.  Velocities are those of the **link origin** in the **link frame** and the
  wrench is applied at the link origin (``Link::AddWorldWrench``): no NED
  conversion is done, so FRD coefficients must be converted to the link's axes
  (usually FLU) and to the link origin.
* sdformat ``sdf/1.11/inertial.sdf``: ``<inertial><fluid_added_mass>`` with the 21
  elements ``xx xy xz xp xq xr yy yz yp yq yr zz zp zq zr pp pq pr qq qr rr``,
  positive, "about the link's origin", in kg, kg m and kg m^2.  Only the DART engine
  uses it (gz-physics ``dartsim/src/AddedMassFeatures.cc``), implicitly and with the
  full-matrix Coriolis; other engines (Bullet, MuJoCo) still need the plugin's
  ``<xDotU>`` tags.  Hydrodynamics.cc reports ``gzerr`` when both are set, so the
  exporter writes one or the other, never both.
* ``<inertial><inertia>``: moments and products about the CG with the ``-m x y``
  convention (the inertia-tensor entries), ``<pose>`` = CG in link axes.

Trap warnings (:class:`SimulatorTrapWarning`)
---------------------------------------------
* legacy added mass with a diagonal term larger than the rigid-body term: explicit
  added mass then goes unstable (gz-sim issue #1923, "Unbounded velocity growth");
* legacy added mass with coupling terms: the plugin's C_A ignores them;
* an asymmetric M_A: ``<fluid_added_mass>`` holds 21 elements (its symmetric part is written).

References
----------
Fossen (2011), Handbook of Marine Craft Hydrodynamics and Motion Control, eqs. 6.43, 7.190.
"""

from __future__ import annotations

from xml.sax.saxutils import escape

import numpy as np

from stripcoef.export._common import (ExportFormat, ExportView, clean, explicit_added_mass_trap, fmt, header_lines,
                      is_symmetric, trap, xml_comment)

NAME = "gazebo"

#: Force-axis and velocity letters of the plugin's tag grammar (Hydrodynamics.cc, Configure).
FORCE_LETTERS = "xyzkmn"
VELOCITY_LETTERS = "UVWPQR"
#: The 21 elements of SDF <fluid_added_mass> (sdf/1.11/inertial.sdf), upper triangle row by row.
FLUID_ADDED_MASS_TAGS = ("xx", "xy", "xz", "xp", "xq", "xr", "yy", "yz", "yp", "yq", "yr",
                         "zz", "zp", "zq", "zr", "pp", "pq", "pr", "qq", "qr", "rr")
_FAM_LETTERS = "xyzpqr"

PLUGIN_FILENAME = "gz-sim-hydrodynamics-system"
PLUGIN_NAME = "gz::sim::systems::Hydrodynamics"
#: Ignition Gazebo Fortress (ign-gazebo 6, sdformat 12): its plugin's library and class, and
#: the newest SDF version sdformat 12 knows (1.9, no <fluid_added_mass>: from SDF 1.10 on).
FORTRESS_PLUGIN_FILENAME = "ignition-gazebo-hydrodynamics-system"
FORTRESS_PLUGIN_NAME = "ignition::gazebo::systems::Hydrodynamics"
SDF_VERSION, FORTRESS_SDF_VERSION = "1.11", "1.9"



def _sname_tags(matrix, tag_of) -> list[str]:
    """``<tag>-m[i,j]</tag>`` lines for the diagonal and every non-zero entry (SNAME signs)."""
    m = np.asarray(matrix, dtype=float)
    return [f"      <{tag_of(i, j)}>{fmt(-m[i, j])}</{tag_of(i, j)}>"
            for i in range(6) for j in range(6) if i == j or m[i, j] != 0.0]

def linear_tag(i: int, j: int) -> str:
    """Tag of the linear derivative of force ``i`` on velocity ``j`` (``<yR>`` = Y_r)."""
    return FORCE_LETTERS[i] + VELOCITY_LETTERS[j]


def quadratic_tag(i: int, j: int, k: int | None = None) -> str:
    """Tag of the |x_k| x_j derivative of force ``i`` (``<xUabsU>`` = X_u|u|); k defaults to j."""
    k = j if k is None else k
    return FORCE_LETTERS[i] + VELOCITY_LETTERS[j] + "abs" + VELOCITY_LETTERS[k]


def added_mass_tag(i: int, j: int) -> str:
    """Legacy plugin tag of the added-mass derivative (``<yDotR>`` = Y_rdot)."""
    return FORCE_LETTERS[i] + "Dot" + VELOCITY_LETTERS[j]


def fluid_added_mass_tag(i: int, j: int) -> str:
    """SDF ``<fluid_added_mass>`` element for M_A[i, j] (i <= j), e.g. ``xq``."""
    a, b = sorted((i, j))
    return _FAM_LETTERS[a] + _FAM_LETTERS[b]


def render(view: ExportView, *, link_name: str = "base_link",
           legacy_added_mass: bool = False, fortress: bool = False,
           buoyancy_volume: bool = True) -> str:
    """SDF text: a model with the link's inertial (and added mass) and the plugin block.

    All matrices come from ``view`` (the model about the link origin, in the link's axes).
    ``fortress``: SDF 1.9 and the Ignition plugin names for Fortress, whose sdformat 12 has
    no ``<fluid_added_mass>`` (it would be dropped without a word), hence the legacy added-mass
    tags, which Fortress's plugin reads with the same grammar (ign-gazebo6 Hydrodynamics.cc).
    ``buoyancy_volume``: the box of the displaced volume for the Buoyancy system, which sums
    the volume of every collision of a link (gz-sim Buoyancy.cc): with it, a trap warning
    says to keep it the link's only collision.
    """
    if fortress:
        legacy_added_mass = True
    model = view.model
    ma = clean(view.matrix("added_mass"))
    mrb = clean(view.matrix("rigid_body_mass"))
    dl = clean(view.matrix("linear_damping"))
    dq = clean(view.matrix("quadratic_damping"))
    ig = clean(view.inertia_about_cg())
    r_g = view.r_g
    r_b = view.r_b
    link = escape(link_name)

    notes = header_lines(view, NAME)
    notes += [
        f"link '{link_name}': its origin is the reference point above, its axes are {view.axes}.",
        "Hydrodynamics system: gz-sim src/systems/hydrodynamics/Hydrodynamics.cc; values are",
        "signed SNAME derivatives (negative damping): <xU> = X_u [kg/s], <xUabsU> = X_u|u| [kg/m].",
    ]
    if legacy_added_mass:
        notes += [
            "Added mass as the plugin's legacy <xDotU> tags (negative, SNAME X_udot) for engines",
            "without <fluid_added_mass> (Bullet, Bullet-Featherstone, MuJoCo). Applied explicitly;",
            "its Coriolis uses only the diagonal. Do not also set <fluid_added_mass>.",
        ]
    else:
        notes += [
            "Added mass as SDF <inertial><fluid_added_mass> (positive, about the link origin,",
            "sdf/1.11/inertial.sdf): DART only. For other engines export with the legacy added-mass option.",
        ]
    if fortress:
        notes += [
            "Fortress file: SDF 1.9 (sdformat 12 drops <fluid_added_mass> silently, it exists from",
            "SDF 1.10), plugin ignition-gazebo-hydrodynamics-system, legacy added-mass tags.",
        ]
    if buoyancy_volume:
        notes += [
            "Buoyancy: the 'buoyancy_volume' collision is a non-colliding box of the displaced volume",
            "centred on the CB, for the world plugin gz-sim-buoyancy-system (add it to the world with",
            f"<uniform_fluid_density>{fmt(model.density)}</uniform_fluid_density>). That system sums",
            "the volume of EVERY collision of the link: keep this box the link's only collision, or",
            "export without it and let the hull's own collisions carry the volume.",
        ]
    else:
        notes += [
            "Buoyancy: no volume box written; gz-sim-buoyancy-system takes the link's volume from",
            f"its own collisions (they must displace {fmt(model.volume)} m^3 centred on the CB).",
        ]
    if model.thrusters:
        notes.append("Thrusters not exported here: " + ", ".join(t.name for t in model.thrusters)
                     + " (use gz-sim-thruster-system per thruster).")

    out = ['<?xml version="1.0" ?>', *xml_comment(notes)]
    out.append(f'<sdf version="{FORTRESS_SDF_VERSION if fortress else SDF_VERSION}">')
    out.append(f'  <model name="{escape(model.name, {chr(34): "&quot;"})}">')
    out.append(f'    <link name="{link}">')
    out.append("      <inertial>")
    out.append(f"        <pose>{fmt(r_g[0])} {fmt(r_g[1])} {fmt(r_g[2])} 0 0 0</pose>")
    out.append(f"        <mass>{fmt(model.mass)}</mass>")
    out.append("        <inertia>")
    for tag, (a, b) in (("ixx", (0, 0)), ("ixy", (0, 1)), ("ixz", (0, 2)),
                        ("iyy", (1, 1)), ("iyz", (1, 2)), ("izz", (2, 2))):
        out.append(f"          <{tag}>{fmt(ig[a, b])}</{tag}>")
    out.append("        </inertia>")
    if not legacy_added_mass:
        sym, asym = is_symmetric(ma)
        if not sym:
            trap(f"gazebo: <fluid_added_mass> holds a symmetric matrix; M_A is asymmetric "
                 f"(largest |M_A - M_A^T| = {asym:.3g}), its symmetric part is written")
        msym = 0.5 * (ma + ma.T)
        out.append("        <fluid_added_mass>")
        for i in range(6):
            for j in range(i, 6):
                tag = fluid_added_mass_tag(i, j)
                out.append(f"          <{tag}>{fmt(msym[i, j])}</{tag}>")
        out.append("        </fluid_added_mass>")
    out.append("      </inertial>")
    if buoyancy_volume and model.volume > 0:
        trap("gazebo: gz-sim's Buoyancy system sums the volume of every collision of a link; "
             "the exported 'buoyancy_volume' box already holds the displaced volume "
             f"({model.volume:.4g} m^3), so hull collisions added to the same link count it "
             "again (buoyancy doubled): keep the box the link's only collision, or export "
             "without it (--no-buoyancy-volume)")
        side = model.volume ** (1.0 / 3.0)
        out += [
            '      <collision name="buoyancy_volume">',
            f"        <pose>{fmt(r_b[0])} {fmt(r_b[1])} {fmt(r_b[2])} 0 0 0</pose>",
            f"        <geometry><box><size>{fmt(side)} {fmt(side)} {fmt(side)}</size></box></geometry>",
            "        <surface><contact><collide_bitmask>0</collide_bitmask></contact></surface>",
            "      </collision>",
        ]
    out.append("    </link>")

    plugin = (FORTRESS_PLUGIN_FILENAME, FORTRESS_PLUGIN_NAME) if fortress else \
        (PLUGIN_FILENAME, PLUGIN_NAME)
    out.append(f'    <plugin filename="{plugin[0]}" name="{plugin[1]}">')
    out.append(f"      <link_name>{link}</link_name>")
    out.append("      <!-- linear damping: <fi Vj> = -D_L[i,j] -->")
    out += _sname_tags(dl, linear_tag)     # clean() already zeroed round-off
    out.append("      <!-- quadratic damping: <fi Vj abs Vj> = -D_Q[i,j] (force -D_Q[i,j] |v_j| v_j) -->")
    out += _sname_tags(dq, quadratic_tag)
    lift = clean(view.matrix("lift"))
    if np.any(lift[:, 1:]):
        if np.any(lift[:, 0]):
            trap("gazebo: lift terms on u itself have no tag distinct from X_u|u|; dropped")
        out.append("      <!-- lift (forward-speed terms): <fi Vj abs U> = -L[i,j] (force -|u| L nu; "
                   "equal to -u L nu when moving forward) -->")
        out += [f"      <{quadratic_tag(i, j, 0)}>{fmt(-lift[i, j])}</{quadratic_tag(i, j, 0)}>"
                for i in range(6) for j in range(1, 6) if lift[i, j] != 0.0]
    if model.control_surfaces:
        notes_cs = ", ".join(s.name for s in model.control_surfaces)
        out.append(f"      <!-- control surfaces not exported ({notes_cs}): use one "
                   "gz-sim-lift-drag-system per fin -->")
    if legacy_added_mass:
        _legacy_traps(ma, mrb)
        out.append("      <!-- legacy added mass: <fi Dot Vj> = -M_A[i,j] -->")
        out += _sname_tags(ma, added_mass_tag)
    out.append("    </plugin>")
    out.append("  </model>")
    out.append("</sdf>")
    return "\n".join(out) + "\n"


def _legacy_traps(ma: np.ndarray, mrb: np.ndarray) -> None:
    """Warn about what goes wrong when gz-sim applies added mass explicitly."""
    explicit_added_mass_trap(
        "gazebo --legacy-added-mass", ma, mrb,
        "the plugin applies added mass explicitly from the previous step's acceleration and "
        "this diverges (gz-sim issue #1923); prefer <fluid_added_mass> with DART")
    off = ma - np.diag(np.diag(ma))
    if np.any(off != 0.0):
        i, j = np.unravel_index(int(np.argmax(np.abs(off))), off.shape)
        trap("gazebo --legacy-added-mass: the plugin's added-mass Coriolis uses only the "
             f"diagonal of M_A (HydrodynamicsUtils.hh buildCoriolisMatrix); coupling terms such "
             f"as {FORCE_LETTERS[i]}Dot{VELOCITY_LETTERS[j]} = {-off[i, j]:.4g} enter the inertia "
             "but not C_A(nu)")


#: This format's entry of the registry :data:`stripcoef.export.FORMATS`.
FORMAT = ExportFormat(
    name=NAME,
    description="gz-sim Hydrodynamics system plugin + SDF <fluid_added_mass> (link frame, link origin)",
    suffix=".sdf",
    render=render,
    default_axes="FLU",
    options=("link_name", "legacy_added_mass", "fortress", "buoyancy_volume"))
