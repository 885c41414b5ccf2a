"""A hull's hydrodynamic database from potential flow: capytaine's boundary-element method, offline.

    ocean-warp bem --hull hull.stl --mass 160 --out out/bem/hull.json

The hull floats upright with its body origin ``rest_height`` above still water (given, or found from a mass:
the height at which it displaces that mass). Its mesh is cut at the free surface, and a lid on the inner
waterplane (a little below it, at capytaine's lowest position for the highest frequency) removes the irregular
frequencies. At zero speed in deep water, capytaine solves at each frequency (by default 50 from 0.3 to
30 rad/s, log-spaced) the six radiation problems of the rigid body about the body origin, and the diffraction
problems of head seas (heading 180 deg, the waves travelling toward -x) and beam seas (90 deg, travelling toward
+y); then at infinite frequency the radiation problems again, for A_inf. The radiation kernels are fitted by
state-space blocks (:mod:`ocean_warp.seakeeping.radiation_fit`) over the frequencies that the panels resolve
(a panel no larger than an eighth of the wavelength), and so are the diffraction weights of the hull's wave points
(:mod:`ocean_warp.seakeeping.diffraction_fit`), to the excitation of waves from every 15 deg; the whole is a
:class:`HydroDatabase`.

capytaine is an optional dependency (``pip install -e '.[bem]'``), imported only when a run starts. Its solver
uses every core it is given (OMP_NUM_THREADS); a hull of about 1 000 panels (and a lid of about 350) at the 50
default frequencies takes about a minute of CPU time: 30 s to 2 min on two cores (2026-11-27).
"""

from __future__ import annotations

import contextlib
import dataclasses
import logging
import math
import sys
import time

import numpy as np

from ..hull import Hull
from ..hull_form import displaced_volume
from .database import HydroDatabase, RadiationTerm, hull_fingerprint
from .diffraction_fit import FIT_HEADINGS_DEG, fit_diffraction_weights
from .panel_pressure import panel_froude_krylov
from .radiation_fit import RadiationFit, fit_radiation
from .wave_points import wave_point_grid

__all__ = ["BemResult", "DEFAULT_FREQUENCY_RANGE", "INSTALL_HINT", "default_frequencies", "rest_height_for_mass",
           "check_rest_height", "compute_database", "require_capytaine"]

DEFAULT_FREQUENCY_RANGE = (0.3, 30.0, 50)
"""Lowest and highest frequency [rad/s] and how many, log-spaced."""
DEFAULT_PRESSURE_DEPTHS = (0.05, 0.15, 0.35)
"""The ocean's pressure depths [m] (``OceanConfig.pressure_depths``' default) the diffraction weights are fitted
for: the wave points read velocities at the middle one and pressure heads at the deepest."""
DEFAULT_HEADINGS_DEG = (180.0, 90.0)
"""Wave headings of the excitation forces [deg]: head seas and beam seas."""
MIN_DRAFT_FRACTION = 0.01
"""A hull drawing less than this fraction of its depth is taken to float out of the water."""
INSTALL_HINT = "pip install -e '.[bem]'"
DOFS = ("Surge", "Sway", "Heave", "Roll", "Pitch", "Yaw")
"""capytaine's names of the rigid degrees of freedom, in the database's order."""


@dataclasses.dataclass(frozen=True)
class BemResult:
    """A BEM run: its database and how it was made."""

    database: HydroDatabase
    fit: RadiationFit
    """The state-space fits (their errors per term) that the database holds as ``radiation``."""
    hull_panels: int
    """Panels of the hull below the free surface."""
    lid_panels: int
    """Panels of the lid (0 without one)."""
    resolved_frequency: float
    """Highest frequency [rad/s] whose wavelength is at least eight times the largest panel's radius."""
    wall_time: float
    """Seconds the run took."""


def default_frequencies() -> np.ndarray:
    """(50,) frequencies [rad/s], 0.3 to 30 log-spaced (``DEFAULT_FREQUENCY_RANGE``)."""
    low, high, count = DEFAULT_FREQUENCY_RANGE
    return np.geomspace(low, high, count)


def require_capytaine():
    """capytaine, imported; ``ImportError`` with the install command where it is missing."""
    try:
        import capytaine
    except ImportError:
        raise ImportError(f"capytaine is not installed: {INSTALL_HINT}") from None
    return capytaine


def rest_height_for_mass(hull: Hull, mass: float, density: float = 1025.0) -> float:
    """Height [m] of ``hull``'s body origin above still water where it floats upright holding ``mass`` [kg] in
    water of ``density`` [kg/m^3]: ``ValueError`` where it would sink (its whole volume holds less) or float out
    (it would draw less than 1 % of its depth)."""
    if isinstance(mass, bool) or not isinstance(mass, (int, float)) or not (math.isfinite(mass) and mass > 0):
        raise ValueError(f"mass must be a finite number > 0 [kg], got {mass!r}")
    low, high = (float(v) for v in hull.bounds[:, 2])
    target = mass / density
    most = displaced_volume(hull, high - 1e-9)
    if target >= most:
        raise ValueError(f"hull {hull.name!r} sinks at {mass:g} kg: its whole volume floats at most "
                         f"{most * density:.4g} kg in water of {density:g} kg/m^3")
    bottom, top = low, high
    while top - bottom > 1e-7:
        middle = 0.5 * (bottom + top)
        bottom, top = (middle, top) if displaced_volume(hull, middle) < target else (bottom, middle)
    waterline = 0.5 * (bottom + top)
    if waterline - low < MIN_DRAFT_FRACTION * (high - low):
        raise ValueError(f"hull {hull.name!r} floats out of the water at {mass:g} kg: it would draw "
                         f"{1000 * (waterline - low):.3g} mm, less than {100 * MIN_DRAFT_FRACTION:g} % of its depth "
                         f"({high - low:.3g} m)")
    return -waterline


def check_rest_height(hull: Hull, rest_height: float) -> float:
    """``rest_height`` [m] as a float, or ``ValueError`` where the still water would not cut ``hull`` with its
    deck above water and a draft of at least 1 % of its depth."""
    if isinstance(rest_height, bool) or not isinstance(rest_height, (int, float)) or not math.isfinite(rest_height):
        raise ValueError(f"rest height must be a finite number [m], got {rest_height!r}")
    low, high = (float(v) for v in hull.bounds[:, 2])
    if high + rest_height <= 0.0:
        raise ValueError(f"hull {hull.name!r} sinks at rest height {rest_height:g} m: its deck (z = {high:.4g} m) "
                         "would be under water")
    if -rest_height - low < MIN_DRAFT_FRACTION * (high - low):
        depth = -rest_height - low
        where = (f"{1000 * depth:.3g} mm under water, less than {100 * MIN_DRAFT_FRACTION:g} % of its depth"
                 if depth > 0 else f"{-depth:.4g} m above the water")
        raise ValueError(f"hull {hull.name!r} floats out of the water at rest height {rest_height:g} m: its lowest "
                         f"point (z = {low:.4g} m) would be {where}")
    return float(rest_height)


@contextlib.contextmanager
def _quiet_capytaine():
    """capytaine's warnings (tabulation, mesh quality, wavelength checks) are logged; this run reports its own."""
    logger = logging.getLogger("capytaine")
    level = logger.level
    logger.setLevel(logging.ERROR)
    try:
        yield
    finally:
        logger.setLevel(level)


def _checked_frequencies(frequencies) -> np.ndarray:
    w = default_frequencies() if frequencies is None else np.asarray(frequencies, dtype=np.float64)
    if w.ndim != 1 or len(w) < 2 or not np.all(np.isfinite(w)) or w[0] <= 0 or np.any(np.diff(w) <= 0):
        raise ValueError(f"frequencies must be at least two finite, increasing numbers > 0 [rad/s], got {w!r}")
    return w


def _immersed_body(cpt, hull: Hull, rest_height: float, lid: bool, omega_max: float, gravity: float):
    """capytaine's body: the hull in still-water coordinates (origin at height ``rest_height``), cut at z = 0,
    with the rigid DOFs about the body origin and an optional lid."""
    vertices = np.asarray(hull.vertices, dtype=np.float64) + np.array([0.0, 0.0, rest_height])
    mesh = cpt.Mesh(vertices=vertices, faces=np.asarray(hull.triangles), name=hull.name)
    wet = mesh.immersed_part()
    lid_mesh = None
    if lid:
        draft = -float(wet.vertices[:, 2].min())
        with np.errstate(invalid="ignore"):  # no irregular frequency below omega_max at any depth: NaN, then 0
            lowest = float(wet.lowest_lid_position(omega_max, g=gravity))
        lid_z = max(lowest if math.isfinite(lowest) else 0.0, -0.5 * draft)
        lid_mesh = wet.generate_lid(z=lid_z)
        if lid_mesh.nb_faces == 0:
            lid_mesh = None
    dofs = cpt.rigid_body_dofs(rotation_center=np.array([0.0, 0.0, rest_height]))
    return cpt.FloatingBody(mesh=wet, lid_mesh=lid_mesh, dofs=dofs, name=hull.name)


def _radiation_matrices(cpt, solver, body, omega: float, density: float, gravity: float):
    """(6, 6) added mass and damping at ``omega`` [rad/s] (np.inf: infinite frequency): [i, j] is the force in
    DOF i of a motion in DOF j."""
    added, damping = np.zeros((6, 6)), np.zeros((6, 6))
    for j, dof in enumerate(DOFS):
        problem = cpt.RadiationProblem(body=body, radiating_dof=dof, omega=omega, rho=density, g=gravity)
        result = solver.solve(problem, keep_details=False, _check_wavelength=False)
        added[:, j] = [result.added_mass[name] for name in DOFS]
        damping[:, j] = [result.radiation_damping[name] for name in DOFS]
    return added, damping


def _excitation(cpt, solver, body, omega: float, headings: np.ndarray, density: float, gravity: float) -> np.ndarray:
    """(H, 6) complex excitation per metre of wave amplitude, in the convention x(t) = Re(X e^(i w t))
    (capytaine's is e^(-i w t): its amplitudes are conjugated)."""
    from capytaine.bem.airy_waves import froude_krylov_force

    forces = np.zeros((len(headings), 6), dtype=np.complex128)
    for h, heading in enumerate(headings):
        problem = cpt.DiffractionProblem(body=body, wave_direction=float(heading), omega=omega, rho=density,
                                         g=gravity)
        result = solver.solve(problem, keep_details=False, _check_wavelength=False)
        froude_krylov = froude_krylov_force(problem)
        forces[h] = [np.conj(result.forces[name] + froude_krylov[name]) for name in DOFS]
    return forces


def _diffraction_weights(hull: Hull, database: HydroDatabase, excitation: np.ndarray, headings: np.ndarray,
                         chosen: np.ndarray, pressure_depths):
    """The wave points' weights fitted to ``excitation`` (F, H, 6) at the database's ``chosen`` frequencies."""
    w = database.frequencies[chosen]
    vertices = np.asarray(hull.vertices, dtype=np.float64) + np.array([0.0, 0.0, database.rest_height])
    froude_krylov = np.array([panel_froude_krylov(vertices, hull.triangles, omega, headings, pressure_depths,
                                                  density=database.water_density, gravity=database.gravity)
                              for omega in w])
    impedance = 1j * w[:, None, None] * database.added_mass_infinite[None] + database.radiation_force_response(w)
    return fit_diffraction_weights(wave_point_grid(hull), w, impedance, excitation[chosen], froude_krylov, headings,
                                   pressure_depths=pressure_depths, gravity=database.gravity)


def compute_database(hull: Hull, *, rest_height: float | None = None, mass: float | None = None,
                     frequencies=None, water_density: float = 1025.0, gravity: float = 9.81, lid: bool = True,
                     headings_deg=DEFAULT_HEADINGS_DEG, diffraction: bool = True,
                     pressure_depths=DEFAULT_PRESSURE_DEPTHS, progress: bool | None = None) -> BemResult:
    """Run the BEM on ``hull`` (see the module's docstring) and fit its radiation memory.

    Args:
        hull: the hull mesh; its body origin is the reference point of every matrix.
        rest_height: height [m] of the body origin above still water; or give ``mass`` [kg] instead.
        frequencies: (F,) [rad/s], increasing (default :func:`default_frequencies`).
        water_density, gravity: rho [kg/m^3] and g [m/s^2].
        lid: put a lid on the inner waterplane against irregular frequencies.
        headings_deg: wave headings of the excitation forces [deg] (may be empty).
        diffraction: fit the diffraction weights of the wave points (waves from every 15 deg, more solves of the
            diffraction problem); False: none (the simulator falls back to the rigid-motion fit).
        pressure_depths: the ocean's three pressure depths [m] the simulator will run with.
        progress: a progress bar on stderr; None: where stderr is a terminal.
    """
    for name, value in (("water_density", water_density), ("gravity", gravity)):
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not (math.isfinite(value) and value > 0):
            raise ValueError(f"{name} must be a finite number > 0, got {value!r}")
    if (rest_height is None) == (mass is None):
        raise ValueError("give the hull's rest_height [m] or its mass [kg], not both or neither")
    if rest_height is None:
        rest_height = rest_height_for_mass(hull, mass, water_density)
    rest_height = check_rest_height(hull, rest_height)
    w = _checked_frequencies(frequencies)
    headings = np.radians(np.asarray(headings_deg, dtype=np.float64).reshape(-1))
    cpt = require_capytaine()
    from tqdm import tqdm

    start = time.perf_counter()
    with _quiet_capytaine():
        body = _immersed_body(cpt, hull, rest_height, lid, float(w.max()), gravity)
        solver = cpt.BEMSolver()
        added, damping = np.zeros((len(w), 6, 6)), np.zeros((len(w), 6, 6))
        excitation = np.zeros((len(w), len(headings), 6), dtype=np.complex128)
        fit_headings = np.radians(FIT_HEADINGS_DEG) if diffraction else np.zeros(0)
        all_round = np.zeros((len(w), len(fit_headings), 6), dtype=np.complex128)
        steps = tqdm(range(len(w) + 1), desc="bem", unit="frequency", file=sys.stderr, dynamic_ncols=True,
                     disable=None if progress is None else not progress)
        for k in steps:
            if k == len(w):
                added_infinite, _ = _radiation_matrices(cpt, solver, body, np.inf, water_density, gravity)
                continue
            added[k], damping[k] = _radiation_matrices(cpt, solver, body, float(w[k]), water_density, gravity)
            if len(headings):
                excitation[k] = _excitation(cpt, solver, body, float(w[k]), headings, water_density, gravity)
            if len(fit_headings):
                all_round[k] = _excitation(cpt, solver, body, float(w[k]), fit_headings, water_density, gravity)
        radius = float(body.mesh_including_lid.faces_radiuses.max())
        hull_panels = int(body.mesh.nb_faces)
        lid_panels = 0 if body.lid_mesh is None else int(body.lid_mesh.nb_faces)
    for name, array in (("added mass", added), ("damping", damping), ("infinite-frequency added mass",
                                                                        added_infinite), ("excitation", excitation),
                        ("excitation all round", all_round)):
        if not np.all(np.isfinite(array)):
            raise RuntimeError(f"capytaine returned NaN or infinite {name} for hull {hull.name!r}")
    # The wavelength 2 pi g / w^2 is resolved while it is at least eight panel radii; the fits take those
    # frequencies, and at least the lowest eight.
    resolved = math.sqrt(2.0 * math.pi * gravity / (8.0 * radius))
    band_high = max(w[w <= resolved].max(initial=w[0]), w[min(len(w), 8) - 1])
    asymmetry = float(np.max(np.abs(added_infinite - added_infinite.T)) / np.max(np.abs(np.diag(added_infinite))))
    added_infinite = 0.5 * (added_infinite + added_infinite.T)
    length = displaced_volume(hull, -rest_height) ** (1.0 / 3.0)  # rotational kernels ~ translational x length^2
    fit = fit_radiation(w, added, damping, added_infinite, length=length, band=(w.min(), band_high))
    terms = tuple(RadiationTerm(row=f.row, col=f.col, a=f.a, b=f.b, c=f.c, fit_error=f.error) for f in fit.fits)
    elapsed = time.perf_counter() - start
    from capytaine import __version__ as capytaine_version

    provenance = {
        "solver": f"capytaine {capytaine_version}", "water_depth": "infinite", "forward_speed": 0.0,
        "hull_panels": hull_panels, "lid_panels": lid_panels, "largest_panel_radius_m": round(radius, 6),
        "resolved_up_to_rad_s": round(resolved, 4), "fit_band_rad_s": [round(v, 6) for v in fit.band],
        "added_mass_infinite_asymmetry": float(f"{asymmetry:.3g}"),
    }
    database = HydroDatabase(hull_name=hull.name, hull_fingerprint=hull_fingerprint(hull),
                             water_density=float(water_density), gravity=float(gravity), rest_height=rest_height,
                             frequencies=w, added_mass=added, damping=damping, added_mass_infinite=added_infinite,
                             radiation=terms, excitation_headings=headings if len(headings) else None,
                             excitation=excitation if len(headings) else None, provenance=provenance)
    if diffraction:
        weights = _diffraction_weights(hull, database, all_round, fit_headings, w <= band_high, pressure_depths)
        provenance["diffraction_fit_error"] = float(f"{weights.fit_error:.3g}")
        database = dataclasses.replace(database, diffraction=weights, provenance=provenance)
    return BemResult(database=database, fit=fit, hull_panels=hull_panels, lid_panels=lid_panels,
                     resolved_frequency=resolved, wall_time=elapsed)
