"""``stripcoef coefficients``: a vehicle file or a mesh in, the hydrodynamic model out."""

from __future__ import annotations

from dataclasses import replace

import numpy as np
import yaml

from stripcoef.conventions import DOF
from stripcoef.cli.options import (add_fluid_arguments, add_mesh_arguments,
                                   estimate_from_args)
from stripcoef.files import json_text, write_text
from stripcoef.study.bands import band_lines, warn_uncertain, with_bands



def add_parser(sub):
    p = sub.add_parser("coefficients", help="added mass, damping and rigid-body matrices",
                       description="Strip-theory hydrodynamic model of a vehicle file (YAML) "
                                   "or a CAD mesh (STL/OBJ/PLY/GLB).")
    p.add_argument("vehicle", metavar="VEHICLE", help="vehicle file (.yaml) or mesh file")
    fmt = p.add_mutually_exclusive_group()
    fmt.add_argument("--json", action="store_true", help="print the JSON contract")
    fmt.add_argument("--yaml", action="store_true", help="print YAML (same content)")
    p.add_argument("-o", "--output", metavar="FILE", help="write to FILE (atomically)")
    p.add_argument("--plot", metavar="FILE.png",
                   help="draw the body's strips and sections (.png/.pdf/.svg; matplotlib)")
    p.add_argument("--strips", type=int, metavar="N", help="number of strips")
    p.add_argument("--speed", type=float, metavar="M_S",
                   help="reference speed for Reynolds numbers and damping [m/s]")
    p.add_argument("--no-corrections", action="store_true",
                   help="pure strip theory (no 3D end corrections)")
    p.add_argument("--reference-point", metavar="POINT",
                   help="center_of_buoyancy, center_of_gravity, origin or X,Y,Z [m]")
    p.add_argument("--regime", choices=("auto", "laminar", "turbulent"), default="auto",
                   help="friction line (default: auto, laminar below Re_L = 5e5)")
    add_fluid_arguments(p, "fluid (override the file; defaults for meshes: sea water)")
    m = add_mesh_arguments(p)
    m.add_argument("--method", choices=("strip", "bem"), default="strip",
                   help="strip theory (default) or the Capytaine BEM (needs stripcoef[bem])")
    p.set_defaults(func=run)
    return p














def _pt(point) -> list:
    """A point rounded to 0.1 mm for display, without negative zeros [m]."""
    return (np.round(np.asarray(point, dtype=float), 4) + 0.0).tolist()


def _levels(c) -> str:
    levels = c.get("added_mass_panel_levels")
    return "/".join(str(n) for n in levels) if levels else str(c.get("added_mass_panels"))


def _level_count(c) -> int:
    return len(c.get("added_mass_panel_levels") or ())


def _error_rule(c) -> str:
    """The band the panel method shows (stripcoef.hull.panel_error): Eça & Hoekstra's
    least-squares uncertainty with four levels or more, the extrapolation's step plus its last
    change with three, Roache's grid convergence index with two."""
    n = _level_count(c)
    return ("Eça & Hoekstra 2014's least-squares uncertainty" if n >= 4 else
            "the extrapolation's step plus its last change" if n == 3 else
            "grid convergence index, Roache 1998")


def format_table(model) -> str:
    """A readable summary: mass properties, the three matrices, conditions."""
    bands = band_lines(model)

    def mat(name, m, unit, matrix=None):
        lines = [f"{name} [{unit}] about {_pt(model.reference_point)} m:"]
        lines.append("        " + "".join(f"{d:>11s}" for d in DOF))
        for d, row in zip(DOF, np.asarray(m)):
            lines.append(f"{d:>7s} " + "".join(f"{v:11.4g}" for v in row))
        lines += ["  method " + b for b in bands if matrix and b.startswith(matrix + " ")]
        return "\n".join(lines)

    c = model.conditions
    method = model.provenance.get("method", "strip theory")
    out = [f"{model.name}: {method} ({c.get('strips')} strips, 3D corrections "
           f"{'on' if c.get('corrections') else 'off'})",
           f"  mass {model.mass:.4g} kg, volume {model.volume:.5g} m^3 "
           f"(rho V = {model.density * model.volume:.4g} kg)",
           f"  CG {_pt(model.center_of_gravity)} m, "
           f"CB {_pt(model.center_of_buoyancy)} m",
           f"  fluid: rho = {model.density:.5g} kg/m^3, nu = {model.kinematic_viscosity:.4g} m^2/s",
           "",
           mat("Added mass M_A", model.added_mass, "kg, kg m, kg m^2", "added_mass"),
           "",
           *([mat(f"Estimated error of M_A ({_error_rule(c)}, panel levels {_levels(c)})",
                  model.added_mass_error, "kg, kg m, kg m^2"),
              f"  largest: {100 * c.get('added_mass_error_max', 0.0):.2g} % of the diagonal "
              "scale sqrt(M_ii M_jj)" + ("" if _level_count(c) < 4 else
                                         "; the warning reads the extrapolation's step plus "
                                         "its last change (added_mass_converged)"), ""]
             if model.added_mass_error is not None else []),
           mat("Linear damping D_L", model.linear_damping, "kg/s, kg m/s, kg m^2/s",
               "linear_damping"),
           "",
           mat("Quadratic damping D_Q", model.quadratic_damping, "kg/m, kg, kg m^2",
               "quadratic_damping"),
           "",
           mat("Rigid-body mass M_RB", model.rigid_body_mass, "kg, kg m, kg m^2"),
           ""]
    if np.any(model.lift) or model.control_surfaces:
        out += [mat("Lift L (force -u L nu)", model.total_lift, "kg/m, kg, kg m", "lift"), ""]
        coeffs = model.coefficients()
        lift_names = [k for k in ("Y_uv", "Y_ur", "Z_uw", "Z_uq", "K_up", "M_uw", "M_uq",
                                  "N_uv", "N_ur") if k in coeffs]
        if lift_names:
            out.append("Lift derivatives (SNAME): " + ", ".join(
                f"{k} = {coeffs[k]:.4g}" for k in lift_names))
        for s in model.control_surfaces:
            d = s.derivative
            out.append(f"Control surface {s.name} ({s.kind}, +-{np.degrees(s.max_deflection):.3g} "
                       f"deg, stall {np.degrees(s.stall_angle):.3g} deg): force u^2 b delta, b = "
                       + "[" + ", ".join(f"{x:.4g}" for x in d) + "]")
        ctrl = {k: v for k, v in coeffs.items() if "_uud" in k}
        if ctrl:
            out.append("Control derivatives (SNAME): " + ", ".join(
                f"{k} = {v:.4g}" for k, v in ctrl.items()))
            out += ["  method " + b for b in bands if b.startswith("control ")]
        out.append("")
    torques = [t for t in model.thrusters if getattr(t, "torque_ratio", 0.0)]
    for t in torques:
        out.append(f"Thruster {t.name}: propeller torque k_Q = {t.torque_ratio:.4g} m "
                   "(moment k_Q T along its axis)")
    if torques:
        out.append("")
    out.append("Conditions:")
    keys = ("reference_speed", "reynolds_length", "regime", "cf_laminar", "cf_turbulent",
            "cf_used", "form_factor", "axial_drag_coefficient_frontal", "hull_reynolds_diameter",
            "hull_crossflow_cd_y", "hull_length_factor", "axial_added_mass",
            "end_correction_sway", "end_correction_heave", "end_correction_pitch",
            "end_correction_yaw", "correction_method", "added_mass_method",
            "added_mass_panel_levels", "added_mass_converged", "added_mass_error_max",
            "mirror_planes")
    for k in keys:
        if k in c:
            v = c[k]
            out.append(f"  {k:32s} {v:.4g}" if isinstance(v, float) else f"  {k:32s} {v}")
    lift = c.get("lift", {})
    if "body_lift" in lift:
        b = lift["body_lift"]
        where = (f"x_0 = {b['separation_x']:.4g} m (slender body)" if "separation_x" in b
                 else f"x_cp = {b['center_of_pressure_x']:.4g} m")
        out.append(f"  {'body_lift':32s} l = {b['length']:.4g} m, d = {b['diameter']:.4g} m, "
                   + where)
    for f in lift.get("fin_lift", []):
        out.append(f"  {'fin_lift ' + f['name']:32s} AR_e = {f['aspect_ratio']:.4g}, "
                   f"c_La = {f['lift_slope']:.4g} /rad, S = {f['area']:.4g} m^2"
                   + (f", hull interference x{f['interference']:.4g}"
                      if f.get("interference", 1.0) != 1.0 else "")
                   + (f" (K_W(B) {f['K_WB']:.3g}, k_W(B) {f['k_WB']:.3g}, tau {f['tau']:.3g}, "
                      f"body upwash {'yes' if f['body_upwash'] else 'no'}), dynamic pressure "
                      f"x{f['pressure_ratio']:.4g} (body's axial flow {f['stream_ratio']:.4g}, boundary "
                      f"layer {f['boundary_layer']:.3g} m)" if "pressure_ratio" in f else ""))
    if lift.get("fins_without_lift"):
        out.append(f"  {'fins_without_lift':32s} " + ", ".join(lift["fins_without_lift"])
                   + " (not on the hull)")
    return "\n".join(out) + "\n"


def write_body_plot(vehicle, model, args) -> None:
    """``--plot``: the strips and sections the model was computed from."""
    from stripcoef.figures import save_figure
    from stripcoef.geometry.plots import body_figure

    strips = vehicle.cut(args.strips)
    fig = body_figure(strips, name=model.name, key="--plot",
                      points={"CB": model.center_of_buoyancy, "CG": model.center_of_gravity,
                              "reference point": model.reference_point})
    save_figure(fig, args.plot, key="--plot")


def run(args) -> int:
    if args.plot:
        from stripcoef.figures import check_plot_path
        check_plot_path(args.plot, key="--plot")
    vehicle, model = estimate_from_args(args)
    model = with_bands(model, vehicle)
    if args.method == "bem":
        from stripcoef.assembly.methods import with_added_mass_of  # the BEM: optional extra

        model = with_added_mass_of(model, vehicle, "bem")
        # the added mass is the BEM's: the strip method's added-mass bands do not apply
        model = replace(model, bands=tuple(b for b in model.bands if b.matrix != "added_mass"))
    warn_uncertain(model)
    data = model.to_dict()
    if args.json:
        text = json_text(data)
    elif args.yaml:
        text = yaml.safe_dump(data, sort_keys=False)
    else:
        text = format_table(model)
    if args.plot:
        write_body_plot(vehicle, model, args)
    if args.output:
        write_text(args.output, text if text.endswith("\n") else text + "\n", key="--output")
    else:
        print(text, end="" if text.endswith("\n") else "\n")
    return 0
