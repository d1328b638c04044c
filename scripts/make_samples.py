"""Write the sample data shipped in the wheel: ``src/stripcoef/samples/``.

    python -m scripts.make_samples            # (re)write every sample
    python -m scripts.make_samples --check    # exit 1 if a sample differs from what it would write

- the vehicles: copies of ``geometry/*.yaml`` and of the shipped meshes ``geometry/*.stl``
  (the repository keeps ``geometry/`` for the README's commands; ``tests/test_samples.py``
  checks the copies are identical);
- one small mesh, ``capsule.stl``: a capsule 1.0 m long, 0.2 m in diameter along x, the
  body of revolution of its profile (``stripcoef.geometry.mesh.revolved_mesh``, 32 profile
  points, 24 sections: 1488 faces), for ``coefficients`` and ``compare``;
- logs generated from a known truth with seeded noise (the generators of ``validation/``,
  the same ones the tests use), and ``truth.yaml`` beside them: for each log its
  generator, seed, the true parameters with units, and the command that recovers them.

Deterministic: the same code writes the same bytes (seeded generators).
"""

from __future__ import annotations

import argparse
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

import numpy as np  # noqa: E402
import yaml  # noqa: E402

from stripcoef.files import json_text  # noqa: E402
from stripcoef.logfile import Log  # noqa: E402

SAMPLES = ROOT / "src" / "stripcoef" / "samples"
GEOMETRY = ROOT / "geometry"

#: Diagnose sample: the synthetic ROV (validation/synthetic.py) with an undeclared tether
#: drag, 120 s of manoeuvres (seed fixed).
DIAGNOSE_SEED = 3
DIAGNOSE_DURATION = 120.0


def _log_text(log: Log) -> str:
    return log.to_csv_text()


def build() -> dict[str, bytes]:
    """name -> bytes of every sample."""
    from validation.experiments import (ROMEO_TRUTH, ROV2_BUOYANCY, ROV2_LENGTH, ROV2_MASS,
                                        ROV2_TRUTH, VIDEORAY_IZZ, VIDEORAY_TRUTH,
                                        romeo_experiment, rov2_pendulum_log, videoray_yaw_log)
    from validation.synthetic import generate

    out: dict[str, bytes] = {}
    described: dict[str, str] = {}
    for f in sorted(GEOMETRY.glob("*.yaml")):
        out[f.name] = f.read_bytes()
        described[f.name] = f"vehicle file: {yaml.safe_load(f.read_text())['name']}"
    for f in sorted(GEOMETRY.glob("*.stl")):
        # the shipped meshes (bluerov2_heavy.stl: written by scripts/make_bluerov2_heavy.py)
        out[f.name] = f.read_bytes()
        described[f.name] = f"mesh: {f.stem}, the mesh of geometry/{f.stem}.yaml's parts (metres)"

    from stripcoef.geometry.mesh import revolved_mesh

    # profile: tail hemisphere, cylinder, nose hemisphere (radius 0.1 m, x from -0.5 to 0.5 m)
    tail, nose = np.linspace(np.pi, np.pi / 2, 9), np.linspace(np.pi / 2, 0.0, 9)
    mid = np.linspace(-0.4, 0.4, 17)[1:-1]
    x = np.concatenate([-0.4 + 0.1 * np.cos(tail), mid, 0.4 + 0.1 * np.cos(nose)])
    r = np.concatenate([0.1 * np.sin(tail), np.full(mid.size, 0.1), 0.1 * np.sin(nose)])
    mesh = revolved_mesh(x, r, sections=24)
    out["capsule.stl"] = mesh.export(file_type="stl")
    described["capsule.stl"] = ("mesh: a capsule 1.0 m long, 0.2 m in diameter along x "
                                f"({len(mesh.faces)} faces, metres)")

    truth: dict[str, dict] = {}

    pts, weight = romeo_experiment(2, seed=2)
    out["heave_steady.csv"] = _log_text(Log({"w": pts.velocity, "Z": pts.force,
                                             "n_h": pts.n_h})).encode()
    truth["heave_steady.csv"] = {
        "what": "ROMEO heave, steady-state points (Indiveri 1998, ch. 4, eta model), "
                "columns w [m/s], Z [N] (commanded force), n_h [command]",
        "generator": "validation.experiments.romeo_experiment(2, seed=2)",
        "truth": {"k_w": [ROMEO_TRUTH["k_w"], "N s/m"], "k_ww": [ROMEO_TRUTH["k_ww"], "N s^2/m^2"],
                  "eta": [ROMEO_TRUTH["eta"], "-"], "net_weight": [float(weight), "N"]},
        "recover": "stripcoef identify sample:heave_steady.csv --method steady --dof heave "
                   "--model eta",
    }
    described["heave_steady.csv"] = "log: ROMEO steady heave points (identify --method steady)"

    out["yaw_onestep.csv"] = _log_text(videoray_yaw_log(0)).encode()
    truth["yaw_onestep.csv"] = {
        "what": "VideoRay Pro III on a pivot, sinusoidal yaw torque (Wang & Clark 2006, "
                "sec. III.C, eq. 8), columns t [s], r [rad/s], N [N m]",
        "generator": "validation.experiments.videoray_yaw_log(0)",
        "inertia": [VIDEORAY_IZZ, "kg m^2"],
        "recover": f"stripcoef identify sample:yaw_onestep.csv --method one-step --dof yaw "
                   f"--inertia {VIDEORAY_IZZ}",
    }
    # the eq. 8 parameters' units are those of r_dot = alpha r + beta r|r| + gamma N + delta
    truth["yaw_onestep.csv"]["truth"] = {
        "alpha": [VIDEORAY_TRUTH["alpha"], "1/s"], "beta": [VIDEORAY_TRUTH["beta"], "1/rad"],
        "gamma": [VIDEORAY_TRUTH["gamma"], "1/(kg m^2)"],
        "delta": [VIDEORAY_TRUTH["delta"], "rad/s^2"]}
    described["yaw_onestep.csv"] = "log: VideoRay yaw on a pivot (identify --method one-step)"

    out["pendulum.csv"] = _log_text(rov2_pendulum_log(0)).encode()
    truth["pendulum.csv"] = {
        "what": "ROV II scaled model swinging as a pendulum in water, free decay (Eng et al. "
                "2009, eq. 4), columns t [s], theta_pendulum [rad]",
        "generator": "validation.experiments.rov2_pendulum_log(0)",
        "truth": {"m_a": [ROV2_TRUTH["m_a"], "kg"], "K_L": [ROV2_TRUTH["K_L"], "N s/m"],
                  "K_Q": [ROV2_TRUTH["K_Q"], "N s^2/m^2"]},
        "known": {"mass": [ROV2_MASS, "kg"], "buoyancy": [ROV2_BUOYANCY, "N"],
                  "length": [ROV2_LENGTH, "m"]},
        "recover": f"stripcoef identify sample:pendulum.csv --method pendulum --mass {ROV2_MASS} "
                   f"--buoyancy {ROV2_BUOYANCY} --length {ROV2_LENGTH} --refine",
    }
    described["pendulum.csv"] = "log: ROV II free-decay pendulum (identify --method pendulum)"

    log, prior, t = generate("tether_drag", DIAGNOSE_SEED, duration=DIAGNOSE_DURATION)
    out["rov_tether.csv"] = _log_text(log).encode()
    out["rov_prior.json"] = json_text(prior.to_dict()).encode()
    truth["rov_tether.csv"] = {
        "what": "a VideoRay-like ROV (validation/synthetic.py rov_model) manoeuvring on four "
                "thrusters for 120 s at 10 Hz with a tether paid out (column tether_length "
                "[m]); its true coefficients are the prior's moved within their strip-theory "
                "bands, plus a tether drag F_x = -c_t L u|u| the prior does not have",
        "generator": f"validation.synthetic.generate('tether_drag', {DIAGNOSE_SEED}, "
                     f"duration={DIAGNOSE_DURATION})",
        "truth": {"c_t": [t["magnitude"], "N s^2/m^3"]},
        "prior": "rov_prior.json",
        "recover": "stripcoef diagnose sample:rov_tether.csv --vehicle sample:rov_prior.json "
                   "--dof surge",
    }
    described["rov_tether.csv"] = "log: ROV with an undeclared tether drag (diagnose)"
    described["rov_prior.json"] = "model file: the prior model of rov_tether.csv (diagnose)"

    described["truth.yaml"] = "the truth of each log and the command that recovers it"
    head = ("# The sample logs' generating truth (written by scripts/make_samples.py; do not edit).\n"
            "# Values are [value, unit]; 'recover' is the command that estimates them.\n")
    out["truth.yaml"] = (head + yaml.safe_dump({"samples": described}, sort_keys=False,
                                               width=100)
                         + yaml.safe_dump({"logs": truth}, sort_keys=False, width=100,
                                          default_flow_style=None)).encode()
    return out


def main(argv=None) -> int:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--check", action="store_true",
                        help="exit 1 if a sample differs from what this script writes")
    args = parser.parse_args(argv)
    files = build()
    if args.check:
        bad = [n for n, data in files.items()
               if not (SAMPLES / n).is_file() or (SAMPLES / n).read_bytes() != data]
        for n in bad:
            print(f"differs: {n}")
        return 1 if bad else 0
    for name, data in files.items():
        (SAMPLES / name).write_bytes(data)
        print(f"wrote {SAMPLES.relative_to(ROOT) / name} ({len(data)} bytes)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
