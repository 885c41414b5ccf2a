"""A hull's hydrodynamic database from potential flow, computed offline with capytaine.

    ocean-warp bem                                               # the E-Boat's physics hull at its rest
    ocean-warp bem --hull hull.stl --mass 160 --out out/bem/hull.json
    ocean-warp bem --hull hull.obj --rest-height 0.05            # its body origin 5 cm above still water

The hull floats upright, its body origin at the rest height above still water (given, or where it displaces
--mass; without --hull, the E-Boat's hull displacing the boat's mass less what its keel, bulb and rudder
displace). Its mesh is cut at the free surface, a lid on the inner waterplane removes the irregular
frequencies, and at each frequency (by default 50, log-spaced from 0.3 to 30 rad/s) capytaine solves the six
radiation problems of the rigid body about the body origin, at zero speed in deep water, and the diffraction
problems of the --headings (head and beam seas) and of waves from every 15 deg (for the diffraction weights of
the wave points, ocean_warp.seakeeping.diffraction_fit); then the radiation problems at infinite frequency. The
radiation kernels K(jw) = B(w) + jw (A(w) - A_inf) that matter are fitted by stable state-space models of
order 2 to 6 over the frequencies the panels resolve (Perez and Fossen's frequency-domain identification).

Writes one JSON file of tens of kilobytes (default out/bem/<hull name>.json): A(w), B(w), A_inf, the fits, the
excitation forces and how they were computed; ocean_warp.seakeeping.HydroDatabase.load reads it back and
checks it against the hull. Prints the panels, the time taken, A_inf, the heave damping's peak, the natural
period in heave and each fit's error.

Needs capytaine (pip install -e '.[bem]'). A hull of about 1 000 panels takes about a minute of CPU time (30 s
to 2 min on two cores); a progress bar shows the frequencies where stderr is a terminal. A mesh that is not
closed, a hull that would sink or float out of the water, and a missing capytaine are one line each, exit
status 2, and nothing is written.
"""

from __future__ import annotations

import math
import os
import sys

import numpy as np

from ocean_warp.cli_support import check_options, checked_output_file, fail, finite_above
from ocean_warp.seakeeping.bem_options import DEFAULT_OUT_FOLDER
from ocean_warp.seakeeping.bem_options import parser as _parser

__all__ = ["main"]


def _open_edges(mesh) -> int:
    """Edges of a triangle mesh used by one triangle only."""
    edges = np.sort(np.asarray(mesh.edges), axis=1)
    _, counts = np.unique(edges, axis=0, return_counts=True)
    return int(np.sum(counts == 1))


def _hull_from_file(parser, path: str, scale: float):
    """The hull in ``path``, or :func:`fail` with one line: no file, not a mesh, not closed."""
    from ocean_warp.hull import Hull
    from ocean_warp.mesh_files import read_mesh_file

    try:
        mesh = read_mesh_file("--hull", path)
    except (FileNotFoundError, ValueError) as error:
        fail(parser, str(error))
    open_edges = _open_edges(mesh)
    name = os.path.splitext(os.path.basename(path))[0]
    try:
        return Hull.from_trimesh(mesh, name=name, scale=scale)  # small holes are closed, with a warning
    except ValueError as error:
        if open_edges:
            fail(parser, f"--hull {path} is not closed: {open_edges} open edges that trimesh could not close (the "
                         "water needs a watertight hull)")
        fail(parser, f"--hull {path}: {error}")


def _eboat_hull_and_masses(density: float):
    """The E-Boat's default physics hull, the mass [kg] its mesh carries at rest in water of ``density`` (the
    boat's, less what the keel fin, bulb and rudder outside the mesh displace) and the boat's mass [kg]."""
    from ocean_warp.eboat import EBoat

    eboat = EBoat()
    return eboat.hull, float(eboat.hull_load(density)), float(eboat.mass_properties.mass)


def _summary(result, hull, mass: float) -> list[str]:
    """What the run found, a line each (``mass`` [kg]: what the hull holds at its rest height)."""
    from ocean_warp.seakeeping.response import hydrostatic_stiffness, natural_period

    db = result.database
    w = db.frequencies
    lines = [f"{db.hull_name}: {result.hull_panels} panels below water and {result.lid_panels} on the lid, "
             f"rest height {db.rest_height:+.4f} m, {len(w)} frequencies {w[0]:g}-{w[-1]:g} rad/s, "
             f"{result.wall_time:.1f} s",
             "A_inf diagonal [kg, kg, kg, kg m^2, kg m^2, kg m^2]: "
             + " ".join(f"{v:.4g}" for v in np.diag(db.added_mass_infinite)),
             f"heave: A33 {db.added_mass[:, 2, 2].min():.4g} to {db.added_mass[:, 2, 2].max():.4g} kg; B33 peak "
             f"{db.damping[:, 2, 2].max():.4g} N s/m at {w[np.argmax(db.damping[:, 2, 2])]:.3g} rad/s"]
    heave_stiffness = float(hydrostatic_stiffness(hull, db.rest_height, mass, (0.0, 0.0, 0.0),
                                                  water_density=db.water_density, gravity=db.gravity)[2, 2])
    period = natural_period(db, mass, heave_stiffness, 2)
    lines.append(f"heave natural period 2 pi sqrt((m + A33) / C33): {period:.3g} s (m {mass:.4g} kg, C33 "
                 f"{heave_stiffness:.4g} N/m)")
    lines.append(f"state-space fits over {result.fit.band[0]:g}-{result.fit.band[1]:.3g} rad/s (the panels resolve "
                 f"waves up to {result.resolved_frequency:.3g} rad/s):")
    lines.append(result.fit.describe())
    if db.diffraction is not None:
        lines.append(f"diffraction weights of {db.diffraction.points.shape[0]} wave points: RMS relative error of the "
                     f"excitation (heave, roll, pitch, waves from every 15 deg) {100 * db.diffraction.fit_error:.1f} %")
    return lines


def main(argv=None) -> int:
    """``ocean-warp bem``: returns 0; bad options and inputs exit with status 2 and one line."""
    parser = _parser()
    args = parser.parse_args(argv)
    low, high, count = args.frequencies
    check_options(parser, (
        ("--scale", args.scale, finite_above(args.scale, 0.0), "a number > 0"),
        ("--mass", args.mass, args.mass is None or finite_above(args.mass, 0.0), "a number > 0 [kg]"),
        ("--rest-height", args.rest_height, args.rest_height is None or math.isfinite(args.rest_height),
         "a finite number [m]"),
        ("--frequencies", " ".join(f"{v:g}" for v in args.frequencies),
         finite_above(low, 0.0) and finite_above(high, low) and count == int(count) and 4 <= count <= 400,
         "LOW > 0, HIGH > LOW [rad/s] and a whole COUNT from 4 to 400"),
        ("--headings", args.headings, all(math.isfinite(h) for h in args.headings), "finite angles [deg]"),
        ("--density", args.density, finite_above(args.density, 0.0), "a number > 0 [kg/m^3]"),
        ("--gravity", args.gravity, finite_above(args.gravity, 0.0), "a number > 0 [m/s^2]"),
    ))
    if args.hull is not None and args.mass is None and args.rest_height is None:
        fail(parser, "--hull needs --mass KG or --rest-height M: where the hull floats")
    from ocean_warp.seakeeping.bem import INSTALL_HINT, compute_database, require_capytaine

    try:
        require_capytaine()
    except ImportError:
        fail(parser, f"capytaine is not installed: {INSTALL_HINT}")
    inertial_mass = None  # what moves with the hull, where it is not the mass it floats (the E-Boat's appendages)
    if args.hull is None:
        hull, load, inertial_mass = _eboat_hull_and_masses(args.density)
        mass = args.mass if args.mass is not None or args.rest_height is not None else load
    else:
        hull, mass = _hull_from_file(parser, args.hull, args.scale), args.mass
    out = args.out if args.out is not None else os.path.join(DEFAULT_OUT_FOLDER, f"{hull.name}.json")
    checked_output_file(parser, out, suffixes=(".json",))
    from ocean_warp.seakeeping.bem import check_rest_height, rest_height_for_mass

    try:
        rest_height = (rest_height_for_mass(hull, mass, args.density) if args.rest_height is None
                       else check_rest_height(hull, args.rest_height))
    except ValueError as error:
        fail(parser, str(error))
    result = compute_database(hull, rest_height=rest_height, frequencies=np.geomspace(low, high, int(count)),
                              water_density=args.density, gravity=args.gravity, lid=not args.no_lid,
                              headings_deg=args.headings, progress=None)
    result.database.save(out)
    if mass is None:  # --rest-height: the mass it floats
        from ocean_warp.hull_form import displaced_volume

        mass = displaced_volume(hull, -rest_height) * args.density
    print("\n".join(_summary(result, hull, inertial_mass if inertial_mass is not None else mass)))
    print(f"wrote {out} ({os.path.getsize(out) / 1024:.0f} kB)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
