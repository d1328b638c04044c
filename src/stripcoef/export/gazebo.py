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

import re
from xml.sax.saxutils import escape

import numpy as np

from stripcoef.conventions import skew
from stripcoef.export._common import (ExportFormat, ExportView, clean, explicit_added_mass_trap,
                                      fmt, header_lines, is_symmetric, trap, xml_comment)

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
#: The Thruster system (gz-sim src/systems/thruster/Thruster.cc) and its Fortress name.
THRUSTER_PLUGIN = ("gz-sim-thruster-system", "gz::sim::systems::Thruster")
FORTRESS_THRUSTER_PLUGIN = ("ignition-gazebo-thruster-system",
                            "ignition::gazebo::systems::Thruster")
#: The world's systems: physics, user commands, scene broadcaster, buoyancy (gz-sim, Fortress).
WORLD_SYSTEMS = {
    False: (("gz-sim-physics-system", "gz::sim::systems::Physics"),
            ("gz-sim-user-commands-system", "gz::sim::systems::UserCommands"),
            ("gz-sim-scene-broadcaster-system", "gz::sim::systems::SceneBroadcaster"),
            ("gz-sim-buoyancy-system", "gz::sim::systems::Buoyancy")),
    True: (("ignition-gazebo-physics-system", "ignition::gazebo::systems::Physics"),
           ("ignition-gazebo-user-commands-system", "ignition::gazebo::systems::UserCommands"),
           ("ignition-gazebo-scene-broadcaster-system",
            "ignition::gazebo::systems::SceneBroadcaster"),
           ("ignition-gazebo-buoyancy-system", "ignition::gazebo::systems::Buoyancy")),
}
#: Nominal propeller diameter written for the Thruster system [m]: with the thrust
#: coefficient C_t,gz = eta C_t / (rho D^4) the joint's angular velocity command equals the
#: vehicle's thruster command (module docstring); D itself does not change the thrust.
PROPELLER_DIAMETER = 0.1


def lumped_added_mass_split(added_mass, rigid_body_mass, r_g):
    r"""Split M_A into a part carried by the link's own inertia and an explicit remainder.

    The link takes a translational mass :math:`m_t` at its CG (the mean of the translational
    diagonal of M_A) and rotational inertias :math:`J` (what stays of the rotational diagonal),
    so that its rigid-body matrix about the link origin grows by

    .. math::
        M_{lump} = m_t \begin{bmatrix} I & -S(r_g) \\ S(r_g) & -S(r_g)^2 \end{bmatrix}
                 + \operatorname{diag}(0, 0, 0, J)

    (Fossen 2011, eq. 3.44: a mass at the CG) and the plugin applies only
    :math:`M_A - M_{lump}` explicitly. The physics engine integrates the lumped part
    implicitly, with its exact rigid-body Coriolis (equal to C_A for an isotropic
    translational and a diagonal rotational added mass). The explicit feedback
    :math:`\dot\nu_{k+1} = M'^{-1}(F - (M_A - M_{lump})\dot\nu_k)`,
    :math:`M' = M_{RB} + M_{lump}`, is stable when the spectral radius
    :math:`\rho(M'^{-1}(M_A - M_{lump})) < 1` (the explicit form's divergence: gz-sim issue
    #1923); it is returned so that the caller can say so.

    Parameters
    ----------
    added_mass, rigid_body_mass : (6, 6) arrays
        M_A and M_RB about the link origin, in the link axes [kg, kg m, kg m^2]
    r_g : (3,) array
        CG relative to the link origin, link axes [m]

    Returns
    -------
    m_t : float
        Lumped translational mass [kg] (added to the link's mass; its weight needs a
        buoyancy of the same size at the CG)
    j : (3,) array
        Lumped rotational inertias [kg m^2] (added to the inertia's diagonal about the CG)
    rest : (6, 6) array
        The explicit remainder M_A - M_lump [kg, kg m, kg m^2]
    radius : float
        Spectral radius of the explicit feedback [-] (stable below 1)
    """
    ma = np.asarray(added_mass, dtype=float)
    mrb = np.asarray(rigid_body_mass, dtype=float)
    m_t = max(float(np.mean(np.diag(ma)[:3])), 0.0)
    s = skew(np.asarray(r_g, dtype=float))
    lump = np.zeros((6, 6))
    lump[:3, :3] = m_t * np.eye(3)
    lump[:3, 3:] = -m_t * s
    lump[3:, :3] = m_t * s
    lump[3:, 3:] = -m_t * s @ s
    j = np.maximum(np.diag(ma)[3:] - np.diag(lump)[3:], 0.0)
    lump[3:, 3:] += np.diag(j)
    rest = ma - lump
    radius = float(np.max(np.abs(np.linalg.eigvals(np.linalg.solve(mrb + lump, rest)))))
    return m_t, j, rest, radius



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
           buoyancy_volume: bool = True, lumped_added_mass: bool | None = None,
           thrusters: bool = True, world: bool = False) -> str:
    """SDF text: a model with the link's inertial (and added mass), the Hydrodynamics plugin
    block and one Thruster system per thruster; with ``world``, a world that holds it.

    All matrices come from ``view`` (the model about the link origin, in the link's axes).
    ``fortress``: SDF 1.9 and the Ignition plugin names for Fortress, whose sdformat 12 has
    no ``<fluid_added_mass>`` (it would be dropped without a word), hence the legacy added-mass
    tags, which Fortress's plugin reads with the same grammar (ign-gazebo6 Hydrodynamics.cc).
    ``lumped_added_mass`` (default: with ``fortress``): the explicit legacy form is kept stable
    by carrying part of M_A in the link's own mass and inertia (:func:`lumped_added_mass`),
    its weight balanced by a box of the same buoyancy at the CG.
    ``buoyancy_volume``: the box of the displaced volume for the Buoyancy system, which sums
    the volume of every collision of a link (gz-sim Buoyancy.cc): with it, a trap warning
    says to keep it the link's only collision.
    ``thrusters``: each thruster as a propeller link on a revolute joint along its direction
    with a Thruster system (gz-sim Thruster.cc, T = C_t rho D^4 omega|omega|) whose joint
    angular-velocity command is the vehicle's thruster command (``use_angvel_cmd``).
    """
    if fortress:
        legacy_added_mass = True
    if lumped_added_mass is None:
        lumped_added_mass = fortress
    if lumped_added_mass:
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
    mass = model.mass
    explicit = ma
    if lumped_added_mass:
        m_t, j, explicit, radius = lumped_added_mass_split(ma, mrb, r_g)
        explicit = clean(explicit)
        mass = model.mass + m_t
        ig = ig + np.diag(j)
        if radius >= 1.0:
            trap(f"gazebo: the explicit remainder of the lumped added mass still diverges "
                 f"(spectral radius {radius:.3g} >= 1, gz-sim issue #1923)")

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
    if lumped_added_mass:
        notes += [
            f"Added mass kept stable: {fmt(m_t)} kg of translational added mass (the mean of",
            "the translational diagonal) and the rotational diagonal "
            f"[{', '.join(fmt(v) for v in j)}] kg m^2",
            "are carried by the link's own <mass> and <inertia> (integrated implicitly by the",
            "engine); the legacy tags hold only the rest, M_A - M_lump, whose explicit feedback",
            f"has spectral radius {radius:.3g} (stable below 1; the full M_A explicitly: unstable",
            "where M_A > M_RB, gz-sim issue #1923). The lumped mass's weight is balanced by the",
            "'added_mass_weight' box, a buoyancy of the same size at the CG.",
        ]
    if buoyancy_volume:
        notes += [
            "Buoyancy: the 'buoyancy_volume' collision is a non-colliding box of the displaced volume",
            "centred on the CB, for the world plugin gz-sim-buoyancy-system (add it to the world with",
            f"<uniform_fluid_density>{fmt(model.density)}</uniform_fluid_density>). That system sums",
            "the volume of EVERY collision of the link: keep this box (and 'added_mass_weight', if",
            "written) the link's only collisions, or export without them and let the hull's own",
            "collisions carry the volume.",
        ]
    else:
        notes += [
            "Buoyancy: no volume box written; gz-sim-buoyancy-system takes the link's volume from",
            f"its own collisions (they must displace {fmt(model.volume)} m^3 centred on the CB).",
        ]
    if model.thrusters and thrusters:
        notes += [
            "Thrusters: one propeller link on a revolute joint along the thrust direction and one",
            "Thruster system each; its angular-velocity command (use_angvel_cmd) is the vehicle's",
            "thruster command n, the thrust C_t rho D^4 n|n| = eta C_t n|n| [N] (the forward",
            f"branch; D = {fmt(PROPELLER_DIAMETER)} m is nominal). Commands: the topic",
            f"/model/{topic_namespace(model.name)}/joint/<joint>/cmd_thrust.",
        ]
    elif model.thrusters:
        notes.append("Thrusters not exported here: " + ", ".join(t.name for t in model.thrusters)
                     + " (use gz-sim-thruster-system per thruster).")

    out = [f'  <model name="{escape(model.name, {chr(34): "&quot;"})}">']
    out.append(f'    <link name="{link}">')
    out.append("      <inertial>")
    out.append(f"        <pose>{fmt(r_g[0])} {fmt(r_g[1])} {fmt(r_g[2])} 0 0 0</pose>")
    out.append(f"        <mass>{fmt(mass)}</mass>")
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
        out += _box("buoyancy_volume", r_b, model.volume)
    if lumped_added_mass and m_t > 0.0:
        if buoyancy_volume:
            out += _box("added_mass_weight", r_g, m_t / model.density)
        else:
            trap(f"gazebo: the lumped added mass ({m_t:.4g} kg) weighs in the link; without the "
                 "buoyancy boxes the link's collisions must also displace "
                 f"{m_t / model.density:.4g} m^3 at the CG, or the vehicle sinks")
    out.append("    </link>")
    if thrusters:
        out += _thruster_lines(view, link)

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
    if legacy_added_mass and lumped_added_mass:
        out.append("      <!-- legacy added mass, the explicit remainder: <fi Dot Vj> = "
                   "-(M_A - M_lump)[i,j] -->")
        out += _sname_tags(explicit, added_mass_tag)
    elif legacy_added_mass:
        _legacy_traps(ma, mrb)
        out.append("      <!-- legacy added mass: <fi Dot Vj> = -M_A[i,j] -->")
        out += _sname_tags(ma, added_mass_tag)
    out.append("    </plugin>")
    out += _thruster_plugins(view, fortress) if thrusters else []
    out.append("  </model>")
    version = FORTRESS_SDF_VERSION if fortress else SDF_VERSION
    head = ['<?xml version="1.0" ?>', *xml_comment(notes), f'<sdf version="{version}">']
    if world:
        return "\n".join(head + _world(model, fortress, out) + ["</sdf>"]) + "\n"
    return "\n".join(head + out + ["</sdf>"]) + "\n"


def _box(name: str, centre, volume: float) -> list[str]:
    """A non-colliding cube of ``volume`` [m^3] centred at ``centre`` [m] (link axes): a
    volume for the Buoyancy system, which sums the link's collisions (gz-sim Buoyancy.cc)."""
    side = volume ** (1.0 / 3.0)
    return [
        f'      <collision name="{name}">',
        f"        <pose>{fmt(centre[0])} {fmt(centre[1])} {fmt(centre[2])} 0 0 0</pose>",
        f"        <geometry><box><size>{fmt(side)} {fmt(side)} {fmt(side)}</size></box></geometry>",
        "        <surface><contact><collide_bitmask>0</collide_bitmask></contact></surface>",
        "      </collision>",
    ]


def _thruster_joint(t) -> str:
    return f"thruster_{t.name}_joint"


def topic_namespace(name: str) -> str:
    """A model name as a gz-transport topic segment (letters, digits and ``_`` only)."""
    return re.sub(r"[^A-Za-z0-9_]+", "_", name).strip("_") or "vehicle"


def _thruster_lines(view: ExportView, link: str) -> list[str]:
    """A propeller link (1 g, a small inertia so that the engine can spin it) on a revolute
    joint along the thrust direction, at each thruster's position (link axes)."""
    out = []
    for t in view.model.thrusters:
        p, d = view.relative(t.position), view.vector(t.direction)
        d = d / np.linalg.norm(d)
        name = escape(f"thruster_{t.name}")
        out += [
            f'    <link name="{name}">',
            f"      <pose>{fmt(p[0])} {fmt(p[1])} {fmt(p[2])} 0 0 0</pose>",
            "      <inertial><mass>0.001</mass><inertia><ixx>1e-06</ixx><iyy>1e-06</iyy>"
            "<izz>1e-06</izz></inertia></inertial>",
            "    </link>",
            f'    <joint name="{escape(_thruster_joint(t))}" type="revolute">',
            f"      <parent>{link}</parent>",
            f"      <child>{name}</child>",
            f"      <axis><xyz>{fmt(d[0])} {fmt(d[1])} {fmt(d[2])}</xyz>"
            "<limit><lower>-1e+16</lower><upper>1e+16</upper></limit></axis>",
            "    </joint>",
        ]
    return out


def _thruster_plugins(view: ExportView, fortress: bool) -> list[str]:
    """One Thruster system per thruster: thrust C_t,gz rho D^4 omega|omega| with
    C_t,gz = eta_f C_t,f / (rho D^4), so that omega = the vehicle's command n gives the
    vehicle's forward thrust map (Wang & Clark 2006, eq. 6; gz-sim Thruster.cc)."""
    filename, cls = FORTRESS_THRUSTER_PLUGIN if fortress else THRUSTER_PLUGIN
    rho, dia = view.model.density, PROPELLER_DIAMETER
    out = []
    lost = [f"{t.name} (backward {t.eta_backward * t.ct_backward:.4g} vs forward "
            f"{t.eta_forward * t.ct_forward:.4g}, dead band {t.deadband:.4g})"
            for t in view.model.thrusters
            if t.eta_backward * t.ct_backward != t.eta_forward * t.ct_forward or t.deadband > 0]
    if lost:
        trap("gazebo: the Thruster system has one coefficient and no dead band; the forward "
             "branch is written for " + ", ".join(lost))
    for t in view.model.thrusters:
        ct = t.eta_forward * t.ct_forward / (rho * dia ** 4)
        out += [
            f'    <plugin filename="{filename}" name="{cls}">',
            f"      <namespace>{topic_namespace(view.model.name)}</namespace>",
            f"      <joint_name>{escape(_thruster_joint(t))}</joint_name>",
            f"      <thrust_coefficient>{fmt(ct)}</thrust_coefficient>",
            f"      <fluid_density>{fmt(rho)}</fluid_density>",
            f"      <propeller_diameter>{fmt(dia)}</propeller_diameter>",
            "      <use_angvel_cmd>true</use_angvel_cmd>",
            f"      <!-- thrust limits [N]: forward {fmt(t.max_forward)}, backward "
            f"{fmt(t.max_backward)} (clip the commands) -->",
            "    </plugin>",
        ]
    return out


def _world(model, fortress: bool, model_lines: list[str]) -> list[str]:
    """A minimal world around the model: physics, user commands, scene broadcaster and the
    Buoyancy system with the model's water density (gz-sim Buoyancy.cc), gravity g."""
    out = ['  <world name="stripcoef">',
           f"    <gravity>0 0 {fmt(-model.gravity)}</gravity>",
           '    <physics name="1ms" type="dart"><max_step_size>0.001</max_step_size>'
           "<real_time_factor>1</real_time_factor></physics>"]
    for filename, cls in WORLD_SYSTEMS[fortress]:
        if "uoyancy" in cls:
            out += [f'    <plugin filename="{filename}" name="{cls}">',
                    f"      <uniform_fluid_density>{fmt(model.density)}</uniform_fluid_density>",
                    "    </plugin>"]
        else:
            out.append(f'    <plugin filename="{filename}" name="{cls}"/>')
    out += ["  " + line for line in model_lines]
    out.append("  </world>")
    return out


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
    options=("link_name", "legacy_added_mass", "fortress", "buoyancy_volume",
             "lumped_added_mass", "thrusters", "world"))
