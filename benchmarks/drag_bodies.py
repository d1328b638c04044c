"""Whole-body drag of simple bodies against measured values: the table.

The bodies, their meshes, the references and the rows held out are in
``validation.drag_bodies`` (shared with docs/validation.md and the method table); this prints
the model against each reference:

    python -m benchmarks.drag_bodies

A term marked ``astern`` is the model's surge drag going astern (the result's
``conditions.surge_quadratic_damping_astern``), not its |u|u term (validation.drag_bodies.ASTERN).
"""

from __future__ import annotations

import numpy as np

from validation.drag_bodies import BODIES, SPEED, compare


def main():
    from stripcoef.assembly.estimate import estimate
    from stripcoef.conventions import quadratic_damping_name
    from stripcoef.study.shapes import shape_class

    print("| body | class | term | C_D model | C_D reference | ln(model/ref) | area | Re | held out |")
    print("|---|---|---|---|---|---|---|---|---|")
    for name in BODIES:
        veh, _, rows = compare(name, lambda v: estimate(v, added_mass_method="strips",
                                                        speed=SPEED))
        for r in rows:
            term = quadratic_damping_name(r['dof'], r['dof']) + (" astern" if r["astern"] else "")
            print(f"| {name} | {shape_class(veh)} | {term} | "
                  f"{r['cd_model']:.3f} | {r['cd_ref']:.3f} ({r['row']}) | "
                  f"{np.log(r['cd_model'] / r['cd_ref']):+.3f} | {r['area']} | {r['reynolds']:.0e} | "
                  f"{'yes' if r['held_out'] else 'no: ' + r['built_from']} |")


if __name__ == "__main__":
    main()
