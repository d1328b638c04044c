r"""An OpenFOAM case for the drag of a body in one degree of freedom (steady RANS).

Translation (surge, sway, heave): the body is held still in a box and the water flows onto it
at the speed ``U`` against the direction of motion, an inlet on the upstream face, an outlet
on the downstream face and slip (``symmetryPlane``) sides. Rotation (roll, pitch, yaw): the
body turns at the rate ``Omega`` in still water, by a multiple-reference-frame (MRF) zone, a
cylinder about the rotation axis through the reference point that holds the body (Wilhelm,
"Rotating flow simulations with OpenFOAM", 2015; OpenFOAM's ``MRFProperties``); the tank's
walls are far and still.

Steady incompressible RANS (``simpleFoam``, SIMPLEC) with the k-omega SST model (Menter,
AIAA J. 32(8), 1994) and wall functions; the mesh by ``blockMesh`` (a background box) and
``snappyHexMesh`` (surface refinement to the target level, distance shells around the body,
a wake box downstream). The box follows the best practice for bluff bodies of COST Action 732
(Franke et al., "Best practice guideline for the CFD simulation of flows in the urban
environment", 2007, sec. 5.1): 5 body lengths upstream and to each side, 15 downstream; the
blockage (frontal area over the box's cross-section) is well under its 3 %.

Every dictionary is written by :mod:`stripcoef.cfd.foamdict` (no GPL helper). The case holds
an ``Allrun`` script that runs it unchanged on another machine or a cluster node
(``./Allrun`` for the ranks it was decomposed for).
"""

from __future__ import annotations

import shlex
import shutil
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from stripcoef.cfd.foamdict import NamedList, foam_file
from stripcoef.errors import InputError

#: Degrees of freedom, their axis (0, 1, 2 = body x, y, z) and whether they rotate.
DOFS = {"surge": (0, False), "sway": (1, False), "heave": (2, False),
        "roll": (0, True), "pitch": (1, True), "yaw": (2, True)}

#: Box clearances [body lengths] (Franke et al. 2007, COST Action 732, sec. 5.1).
UPSTREAM = 5.0
DOWNSTREAM = 15.0
LATERAL = 5.0
#: Clearance of the still tank around a turning body [body lengths] (as LATERAL).
TANK = 5.0
#: Most background cells of the blockMesh box before its cells are doubled in size.
MAX_BACKGROUND_CELLS = 8000
#: Freestream turbulence (Menter 1994, sec. "boundary conditions"): omega_inf = OMEGA_FACTOR
#: U / L (1 to 10) and nu_t,inf = NUT_RATIO nu (1e-5 to 1e-2).
OMEGA_FACTOR = 5.0
NUT_RATIO = 1e-3
#: Iterations of simpleFoam unless the residuals fall below RESIDUALS first.
ITERATIONS = 1000
RESIDUALS = {"p": 1e-4, "U": 1e-5, "(k|omega)": 1e-5}


@dataclass(frozen=True)
class CaseSpec:
    """What one OpenFOAM run computes.

    Attributes
    ----------
    dof : str
        One of :data:`DOFS`.
    speed : float
        Speed [m/s] of a translation, rate [rad/s] of a rotation (positive: along or about
        the body axis).
    level : int
        Refinement: the cells at the surface are ``size / 2**level`` [m].
    length, size : float
        Body length (largest extent) [m]; cell reference size (the middle extent) [m].
    bounds : (2, 3) array
        Body bounding box in body axes [m].
    density, viscosity : float
        Water density [kg/m^3], kinematic viscosity [m^2/s].
    reference_area : float
        Frontal area normal to the motion [m^2] (force coefficients).
    ranks : int
        MPI ranks the case is decomposed for (1: not decomposed).
    iterations : int
        Most simpleFoam iterations.
    reference_point : (3,) array
        Moment reference point and rotation centre [m] (the body origin).
    """

    dof: str
    speed: float
    level: int
    length: float
    size: float
    bounds: tuple
    density: float
    viscosity: float
    reference_area: float
    ranks: int = 1
    iterations: int = ITERATIONS
    reference_point: tuple = (0.0, 0.0, 0.0)
    mrf_radius: float = 0.0
    mrf_half_length: float = 0.0

    def __post_init__(self):
        if self.dof not in DOFS:
            raise InputError("unknown degree of freedom", key="dofs", value=self.dof,
                             expected="surge, sway, heave, roll, pitch or yaw")
        for key, val in (("speed", self.speed), ("ranks", self.ranks),
                         ("iterations", self.iterations), ("length", self.length)):
            if not (np.isfinite(val) and val > 0):
                raise InputError("must be positive", key=key, value=val,
                                 expected="a number > 0")

    @property
    def axis(self) -> int:
        return DOFS[self.dof][0]

    @property
    def rotation(self) -> bool:
        return DOFS[self.dof][1]

    @property
    def cell(self) -> float:
        """Surface cell size [m]."""
        return self.size / 2 ** self.level


@dataclass(frozen=True)
class Background:
    """The blockMesh box: corners [m], cells per axis, cell size [m], and the levels of
    snappyHexMesh that reach the target surface cell."""

    lo: tuple
    hi: tuple
    cells: tuple
    h0: float
    surface_level: int
    inlet_side: str | None = None       # "max" face of the axis (translation)


@dataclass(frozen=True)
class CaseFiles:
    """A written case: its folder, the command lines in order, the background box."""

    folder: Path
    commands: tuple
    background: Background
    spec: CaseSpec = field(repr=False)


def background(spec: CaseSpec) -> Background:
    """The background box: the clearances around the body's bounding box, rounded out to
    whole cells; the cells doubled until at most :data:`MAX_BACKGROUND_CELLS` (the levels of
    snappyHexMesh raised to keep the surface cell ``size / 2**level``)."""
    b = np.asarray(spec.bounds, float)
    L = spec.length
    lo, hi = b[0].copy(), b[1].copy()
    if spec.rotation:
        c = np.asarray(spec.reference_point, float)
        lo = np.minimum(lo, c) - TANK * L
        hi = np.maximum(hi, c) + TANK * L
    else:
        lo -= LATERAL * L
        hi += LATERAL * L
        a = spec.axis
        lo[a] = b[0][a] - DOWNSTREAM * L     # the body moves towards +axis: water flows -axis
        hi[a] = b[1][a] + UPSTREAM * L
    h0 = spec.size
    extra = 0
    while np.prod(np.ceil((hi - lo) / h0)) > MAX_BACKGROUND_CELLS:
        h0 *= 2.0
        extra += 1
    n = np.ceil((hi - lo) / h0 - 1e-9).astype(int)
    centre = 0.5 * (lo + hi)
    lo = centre - 0.5 * n * h0
    hi = centre + 0.5 * n * h0
    return Background(lo=tuple(float(v) for v in lo), hi=tuple(float(v) for v in hi), cells=tuple(int(v) for v in n), h0=h0,
                      surface_level=spec.level + extra,
                      inlet_side=None if spec.rotation else "max")


def _patch_faces(axis: int):
    """blockMesh faces (vertex indices of the hex 0..7) of the min and max face of ``axis``."""
    faces = {0: ((0, 4, 7, 3), (1, 2, 6, 5)), 1: ((0, 1, 5, 4), (3, 7, 6, 2)),
             2: ((0, 3, 2, 1), (4, 5, 6, 7))}
    return faces[axis]


def block_mesh_dict(spec: CaseSpec, bg: Background) -> str:
    lo, hi = bg.lo, bg.hi
    verts = [(lo[0], lo[1], lo[2]), (hi[0], lo[1], lo[2]), (hi[0], hi[1], lo[2]),
             (lo[0], hi[1], lo[2]), (lo[0], lo[1], hi[2]), (hi[0], lo[1], hi[2]),
             (hi[0], hi[1], hi[2]), (lo[0], hi[1], hi[2])]
    if spec.rotation:
        boundary = NamedList(tank={"type": "patch", "faces": [list(f) for a in range(3)
                                                              for f in _patch_faces(a)]})
    else:
        a = spec.axis
        boundary = NamedList(inlet={"type": "patch", "faces": [list(_patch_faces(a)[1])]},
                             outlet={"type": "patch", "faces": [list(_patch_faces(a)[0])]})
        for b in range(3):          # a symmetryPlane patch must be one plane: one per side
            if b != a:
                for side, face in zip(("min", "max"), _patch_faces(b)):
                    boundary[f"{'xyz'[b]}{side}"] = {"type": "symmetryPlane",
                                                     "faces": [list(face)]}
    body = {"convertToMeters": 1, "vertices": [list(v) for v in verts],
            "blocks": ["hex", list(range(8)), list(bg.cells), "simpleGrading", [1, 1, 1]],
            "boundary": boundary}
    return foam_file("blockMeshDict", body)


def location_in_mesh(bg: Background) -> tuple:
    """A point in the water: half a background cell inside the box's low corner, off the
    cell faces."""
    return tuple(float(v) + bg.h0 * f for v, f in zip(bg.lo, (0.5123, 0.4871, 0.5347)))


def snappy_dict(spec: CaseSpec, bg: Background) -> str:
    """snappyHexMesh: surface level, feature edges, distance shells (the slender body
    thinner than a background cell is still refined), a wake box downstream."""
    n = bg.surface_level
    s = spec.size
    b = np.asarray(spec.bounds, float)
    regions = {"body": {"mode": "distance",
                        "levels": [[spec.cell, n], [0.5 * s, max(n - 1, 0)],
                                   [1.5 * s, max(n - 2, 0)]]}}
    geometry = {"body.stl": {"type": "triSurfaceMesh", "name": "body"}}
    if not spec.rotation:
        a = spec.axis
        wlo, whi = b[0] - 0.5 * s, b[1] + 0.5 * s
        wlo[a] = b[0][a] - 2.0 * spec.length
        whi[a] = b[0][a]
        geometry["wake"] = {"type": "searchableBox", "min": list(wlo), "max": list(whi)}
        regions["wake"] = {"mode": "inside", "levels": [[1e15, max(n - 2, 0)]]}
    body = {
        "castellatedMesh": True, "snap": True, "addLayers": False,
        "geometry": geometry,
        "castellatedMeshControls": {
            "maxLocalCells": 2000000, "maxGlobalCells": 20000000, "minRefinementCells": 0,
            "maxLoadUnbalance": 0.10, "nCellsBetweenLevels": 3,
            "features": [{"file": '"body.eMesh"', "level": n}],
            "refinementSurfaces": {"body": {"level": [n, n],
                                            "patchInfo": {"type": "wall"}}},
            "resolveFeatureAngle": 30,
            "refinementRegions": regions,
            "locationInMesh": list(location_in_mesh(bg)),
            "allowFreeStandingZoneFaces": True},
        "snapControls": {"nSmoothPatch": 3, "tolerance": 2.0, "nSolveIter": 50,
                         "nRelaxIter": 5, "nFeatureSnapIter": 10, "implicitFeatureSnap": False,
                         "explicitFeatureSnap": True, "multiRegionFeatureSnap": False},
        "addLayersControls": {"relativeSizes": True, "layers": {}, "expansionRatio": 1.0,
                              "finalLayerThickness": 0.3, "minThickness": 0.1,
                              "nGrow": 0, "featureAngle": 60, "nRelaxIter": 3,
                              "nSmoothSurfaceNormals": 1, "nSmoothNormals": 3,
                              "nSmoothThickness": 10, "maxFaceThicknessRatio": 0.5,
                              "maxThicknessToMedialRatio": 0.3, "minMedialAxisAngle": 90,
                              "nBufferCellsNoExtrude": 0, "nLayerIter": 50},
        "meshQualityControls": {"#includeEtc": '"caseDicts/meshQualityDict"',
                                "relaxed": {"maxNonOrtho": 75}, "nSmoothScale": 4,
                                "errorReduction": 0.75},
        "mergeTolerance": 1e-6,
    }
    return foam_file("snappyHexMeshDict", body)


def _ufield(spec: CaseSpec) -> list:
    if spec.rotation:
        return [0.0, 0.0, 0.0]
    u = [0.0, 0.0, 0.0]
    u[spec.axis] = -spec.speed          # the water flows against the motion
    return u


def inflow_vector(spec: CaseSpec) -> tuple:
    """The water's velocity far from the body [m/s] (zero for a rotation)."""
    return tuple(_ufield(spec))


def freestream_turbulence(spec: CaseSpec) -> tuple[float, float]:
    r"""Freestream k [m^2/s^2] and omega [1/s] of the k-omega SST model.

    .. math:: \omega_\infty = c_\omega U / L, \qquad k_\infty = r_t \nu \omega_\infty

    with :math:`c_\omega` = :data:`OMEGA_FACTOR` and :math:`r_t` = :data:`NUT_RATIO`
    (Menter, AIAA J. 32(8), 1994: omega 1 to 10 U/L, nu_t 1e-5 to 1e-2 nu). For a rotation
    U is the tip speed ``Omega L / 2``.
    """
    u = spec.speed * (0.5 * spec.length if spec.rotation else 1.0)
    omega = OMEGA_FACTOR * u / spec.length
    return NUT_RATIO * spec.viscosity * omega, omega


def field_files(spec: CaseSpec) -> dict[str, str]:
    """The initial fields 0/U, p, k, omega, nut (kinematic pressure [m^2/s^2])."""
    u = "uniform (" + " ".join(f"{v:.10g}" for v in _ufield(spec)) + ")"
    k, om = freestream_turbulence(spec)
    inc = {"#includeEtc": '"caseDicts/setConstraintTypes"'}
    wall = {"U": {"type": "fixedValue", "value": "uniform (0 0 0)"},
            "p": {"type": "zeroGradient"},
            "k": {"type": "kqRWallFunction", "value": f"uniform {k:.10g}"},
            "omega": {"type": "omegaWallFunction", "value": f"uniform {om:.10g}"},
            "nut": {"type": "nutkWallFunction", "value": "uniform 0"}}
    if spec.rotation:
        outer = {"tank": {"U": {"type": "fixedValue", "value": "uniform (0 0 0)"},
                          "p": {"type": "zeroGradient"},
                          "k": {"type": "zeroGradient"}, "omega": {"type": "zeroGradient"},
                          "nut": {"type": "calculated", "value": "uniform 0"}}}
    else:
        outer = {"inlet": {"U": {"type": "fixedValue", "value": u},
                           "p": {"type": "zeroGradient"},
                           "k": {"type": "fixedValue", "value": f"uniform {k:.10g}"},
                           "omega": {"type": "fixedValue", "value": f"uniform {om:.10g}"},
                           "nut": {"type": "calculated", "value": "uniform 0"}},
                 "outlet": {"U": {"type": "inletOutlet", "inletValue": "uniform (0 0 0)",
                                  "value": u},
                            "p": {"type": "fixedValue", "value": "uniform 0"},
                            "k": {"type": "inletOutlet", "inletValue": f"uniform {k:.10g}",
                                  "value": f"uniform {k:.10g}"},
                            "omega": {"type": "inletOutlet",
                                      "inletValue": f"uniform {om:.10g}",
                                      "value": f"uniform {om:.10g}"},
                            "nut": {"type": "calculated", "value": "uniform 0"}}}
    internal = {"U": u, "p": "uniform 0", "k": f"uniform {k:.10g}",
                "omega": f"uniform {om:.10g}", "nut": "uniform 0"}
    dims = {"U": "[0 1 -1 0 0 0 0]", "p": "[0 2 -2 0 0 0 0]", "k": "[0 2 -2 0 0 0 0]",
            "omega": "[0 0 -1 0 0 0 0]", "nut": "[0 2 -1 0 0 0 0]"}
    out = {}
    for name in ("U", "p", "k", "omega", "nut"):
        bf = dict(inc)
        for patch, fields in outer.items():
            bf[patch] = fields[name]
        bf["body"] = wall[name]
        cls = "volVectorField" if name == "U" else "volScalarField"
        out[name] = foam_file(name, {"dimensions": dims[name], "internalField": internal[name],
                                     "boundaryField": bf}, cls=cls, location="0")
    return out


def control_dict(spec: CaseSpec) -> str:
    """simpleFoam's controls and the forces and forceCoeffs function objects."""
    a = spec.axis
    e = [0, 0, 0]
    e[a] = 1
    lift = [0, 0, 0]
    lift[(a + 2) % 3] = 1
    pitch = [0, 0, 0]
    pitch[(a + 1) % 3] = 1
    cofr = list(spec.reference_point)
    functions = {
        "forces": {"type": "forces", "libs": ['"libforces.so"'], "writeControl": "timeStep",
                   "writeInterval": 1, "log": True, "patches": ["body"], "rho": "rhoInf",
                   "rhoInf": spec.density, "CofR": cofr},
        # y+ of the wall cells when the fields are written (the wall functions' range)
        "yPlus": {"type": "yPlus", "libs": ['"libfieldFunctionObjects.so"'],
                  "writeControl": "writeTime", "log": False},
    }
    if not spec.rotation:
        functions["forceCoeffs"] = {
            "type": "forceCoeffs", "libs": ['"libforces.so"'], "writeControl": "timeStep",
            "writeInterval": 1, "log": False, "patches": ["body"], "rho": "rhoInf",
            "rhoInf": spec.density, "CofR": cofr, "dragDir": [-v for v in e],
            "liftDir": lift, "pitchAxis": pitch, "magUInf": spec.speed, "lRef": spec.length,
            "Aref": spec.reference_area}
    body = {"application": "simpleFoam", "startFrom": "startTime", "startTime": 0,
            "stopAt": "endTime", "endTime": spec.iterations, "deltaT": 1,
            "writeControl": "timeStep", "writeInterval": spec.iterations, "purgeWrite": 1,
            "writeFormat": "ascii", "writePrecision": 8, "writeCompression": False,
            "timeFormat": "general", "timePrecision": 6, "runTimeModifiable": True,
            "functions": functions}
    return foam_file("controlDict", body, location="system")


def fv_schemes() -> str:
    body = {"ddtSchemes": {"default": "steadyState"},
            "gradSchemes": {"default": "Gauss linear",
                            "grad(U)": "cellLimited Gauss linear 1"},
            "divSchemes": {"default": "none",
                           "div(phi,U)": "bounded Gauss linearUpwind grad(U)",
                           "div(phi,k)": "bounded Gauss upwind",
                           "div(phi,omega)": "bounded Gauss upwind",
                           "div((nuEff*dev2(T(grad(U)))))": "Gauss linear",
                           "div(div(phi,U))": "Gauss linear"},        # potentialFoam -writep
            "laplacianSchemes": {"default": "Gauss linear limited corrected 0.33"},
            "interpolationSchemes": {"default": "linear"},
            "snGradSchemes": {"default": "limited corrected 0.33"},
            "wallDist": {"method": "meshWave"}}
    return foam_file("fvSchemes", body, location="system")


def fv_solution(spec: CaseSpec, bg: Background) -> str:
    simple = {"nNonOrthogonalCorrectors": 0, "consistent": True,
              "residualControl": dict(RESIDUALS)}
    if spec.rotation:                       # a closed tank: the pressure needs a reference
        simple["pRefPoint"] = list(location_in_mesh(bg))
        simple["pRefValue"] = 0
    body = {"solvers": {
                "p": {"solver": "GAMG", "smoother": "GaussSeidel", "tolerance": 1e-7,
                      "relTol": 0.01},
                "Phi": {"solver": "GAMG", "smoother": "GaussSeidel", "tolerance": 1e-7,
                        "relTol": 0.01},
                "(U|k|omega)": {"solver": "smoothSolver", "smoother": "GaussSeidel",
                                "tolerance": 1e-8, "relTol": 0.1, "nSweeps": 1}},
            "SIMPLE": simple,
            "potentialFlow": {"nNonOrthogonalCorrectors": 5},
            "relaxationFactors": {"equations": {"U": 0.7, "(k|omega)": 0.5}}}
    return foam_file("fvSolution", body, location="system")


def decompose_dict(ranks: int, bg: Background) -> str:
    """Hierarchical decomposition (Debian's scotch library is a stub): the ranks split along
    the box's longest axes first."""
    n = [1, 1, 1]
    order = np.argsort(bg.cells)[::-1]
    left = ranks
    for p in _prime_factors(ranks):
        n[int(order[0])] *= p
        left //= p
        order = np.argsort([c / m for c, m in zip(bg.cells, n)])[::-1]
    body = {"numberOfSubdomains": ranks, "method": "hierarchical",
            "coeffs": {"n": n, "order": "xyz"}}
    return foam_file("decomposeParDict", body, location="system")


def _prime_factors(n: int) -> list[int]:
    out, p = [], 2
    while n > 1:
        while n % p == 0:
            out.append(p)
            n //= p
        p += 1
    return sorted(out, reverse=True)


def mrf_files(spec: CaseSpec) -> dict[str, str]:
    """constant/MRFProperties and system/topoSetDict: a cylinder about the rotation axis
    through the reference point, holding the body, turning at ``speed`` [rad/s]."""
    e = [0.0, 0.0, 0.0]
    e[spec.axis] = 1.0
    c = np.asarray(spec.reference_point, float)
    ev = np.asarray(e)
    p1, p2 = c - spec.mrf_half_length * ev, c + spec.mrf_half_length * ev
    topo = {"actions": [{"name": "rotor", "type": "cellZoneSet", "action": "new",
                         "source": "cylinderToCell", "p1": list(p1), "p2": list(p2),
                         "radius": spec.mrf_radius}]}
    mrf = {"rotor": {"cellZone": "rotor", "active": True, "nonRotatingPatches": [],
                     "origin": list(c), "axis": e, "omega": spec.speed}}
    return {"constant/MRFProperties": foam_file("MRFProperties", mrf, location="constant"),
            "system/topoSetDict": foam_file("topoSetDict", topo, location="system")}


def commands(spec: CaseSpec) -> tuple:
    """The command lines of the run, in order (each a tuple of arguments)."""
    par = spec.ranks > 1
    mpi = ("mpirun", "-np", str(spec.ranks)) if par else ()
    pflag = ("-parallel",) if par else ()
    out = [("blockMesh",), ("surfaceFeatureExtract",)]
    if par:
        out.append(("decomposePar", "-force"))
    out.append(mpi + ("snappyHexMesh", "-overwrite") + pflag)
    out.append(mpi + ("checkMesh", "-constant") + pflag)
    if spec.rotation:
        out.append(mpi + ("topoSet",) + pflag)
    out.append(("stripcoef-copy-fields",))
    if not spec.rotation:
        out.append(mpi + ("potentialFoam", "-writep") + pflag)
    out.append(mpi + ("simpleFoam",) + pflag)
    return tuple(out)


def copy_fields_shell(ranks: int) -> str:
    """The shell lines that put the initial fields (0.orig) in place after meshing."""
    if ranks > 1:
        return ("for d in processor*; do rm -rf \"$d/0\"; cp -r 0.orig \"$d/0\"; done")
    return "rm -rf 0 && cp -r 0.orig 0"


def allrun(spec: CaseSpec) -> str:
    """A bash script that runs the case as :func:`commands` lists it (each log in
    ``log.<application>``); OpenFOAM's environment from Debian's package (v1912) unless one
    is set already."""
    lines = ["#!/bin/bash", f"{MARK}: runs this case as `stripcoef cfd` did",
             "set -e", "cd \"$(dirname \"$0\")\"",
             ': "${WM_PROJECT_DIR:=/usr/share/openfoam}"', "export WM_PROJECT_DIR"]
    for cmd in commands(spec):
        if cmd[0] == "stripcoef-copy-fields":
            lines.append(copy_fields_shell(spec.ranks))
            continue
        app = cmd[3] if cmd[0] == "mpirun" else cmd[0]
        lines.append(" ".join(shlex.quote(c) for c in cmd) + f" > log.{app} 2>&1")
    return "\n".join(lines) + "\n"


def feature_dict() -> str:
    body = {"body.stl": {"extractionMethod": "extractFromSurface",
                         "extractFromSurfaceCoeffs": {"includedAngle": 150},
                         "writeObj": False}}
    return foam_file("surfaceFeatureExtractDict", body, location="system")


def transport(spec: CaseSpec) -> dict[str, str]:
    return {"constant/transportProperties": foam_file(
                "transportProperties", {"transportModel": "Newtonian",
                                        "nu": spec.viscosity}, location="constant"),
            "constant/turbulenceProperties": foam_file(
                "turbulenceProperties", {"simulationType": "RAS",
                                         "RAS": {"RASModel": "kOmegaSST", "turbulence": True,
                                                 "printCoeffs": False}},
                location="constant")}


def write_case(folder, spec: CaseSpec, surface) -> CaseFiles:
    """Write the case for ``spec`` into ``folder`` (created; the files it holds replaced).

    ``surface`` is the closed body (a ``trimesh.Trimesh`` in body axes [m]), written as
    ``constant/triSurface/body.stl``.
    """
    folder = Path(folder)
    _clear(folder)
    bg = background(spec)
    files = {"system/blockMeshDict": block_mesh_dict(spec, bg),
             "system/snappyHexMeshDict": snappy_dict(spec, bg),
             "system/surfaceFeatureExtractDict": feature_dict(),
             "system/controlDict": control_dict(spec),
             "system/fvSchemes": fv_schemes(),
             "system/fvSolution": fv_solution(spec, bg),
             **transport(spec)}
    if spec.ranks > 1:
        files["system/decomposeParDict"] = decompose_dict(spec.ranks, bg)
    if spec.rotation:
        files.update(mrf_files(spec))
    for name, text in field_files(spec).items():
        files[f"0.orig/{name}"] = text
    try:
        for name, text in files.items():
            path = folder / name
            path.parent.mkdir(parents=True, exist_ok=True)
            path.write_text(text)
        tri = folder / "constant" / "triSurface"
        tri.mkdir(parents=True, exist_ok=True)
        stl = surface.export(file_type="stl_ascii")
        (tri / "body.stl").write_text(stl if isinstance(stl, str) else stl.decode())
        run = folder / "Allrun"
        run.write_text(allrun(spec))
        run.chmod(0o755)
    except OSError as exc:
        raise InputError(f"cannot write the case ({exc.strerror or exc})", key="case_dir",
                         value=str(folder), expected="a writable folder") from None
    return CaseFiles(folder=folder, commands=commands(spec), background=bg, spec=spec)


#: The first line of the Allrun script that marks a folder as a case stripcoef wrote.
MARK = "# written by stripcoef"


def _clear(folder: Path) -> None:
    """Remove an earlier case of stripcoef at ``folder`` (its meshes, times and force files
    would mix with the new run's); a folder that is not one is left alone and refused."""
    if not folder.exists():
        return
    run = folder / "Allrun"
    if folder.is_dir() and not any(folder.iterdir()):
        return
    if not (folder.is_dir() and run.is_file() and MARK in run.read_text(errors="replace")):
        raise InputError("exists and is not a case stripcoef wrote", key="case_dir",
                         value=str(folder), expected="a new folder, or one an earlier "
                         "`stripcoef cfd` wrote (it is replaced)")
    try:
        shutil.rmtree(folder)
    except OSError as exc:
        raise InputError(f"cannot replace the earlier case ({exc.strerror or exc})",
                         key="case_dir", value=str(folder),
                         expected="a folder this user may write") from None


def mrf_extent(vertices, reference_point, axis: int, margin: float) -> tuple[float, float]:
    """Radius and half-length [m] of the MRF cylinder that holds the body with ``margin``."""
    v = np.asarray(vertices, float) - np.asarray(reference_point, float)
    radial = np.delete(v, axis, axis=1)
    r = float(np.max(np.hypot(radial[:, 0], radial[:, 1])))
    h = float(np.max(np.abs(v[:, axis])))
    return r + margin, h + margin


__all__ = ["CaseSpec", "CaseFiles", "Background", "DOFS", "write_case", "background",
           "commands", "inflow_vector", "freestream_turbulence", "mrf_extent"]
