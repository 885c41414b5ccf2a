"""An independent velocity prediction (VPP) of the E-Boat, to check the simulator's sailing against.

The E-Boat is a 2.5 m sailing robot with a main sail alone (no jib). This script runs the ORC-model VPP
of the PyPI package ``python-vpp`` (1.0.0, import name ``python_vpp``; MIT-licensed, used only by this
benchmark and never by the ``ocean_warp`` core) in flat water, by default on the real boat measured from
the seed team's CAD: ``shared/eboat/vpp_inputs_real.json`` (``shared/eboat/README.md``, "An independent
VPP of the real boat" and "The real geometry"). Its cases are the sail plans: ``R`` the full main
(3.19 m2), ``R1`` the main reefed to 2.04 m2, ``R2`` reefed to 1.15 m2; hull, appendages, mass and
righting arm are the same in all three. Per case, in ``<out>`` (default ``benchmarks/data/real_boat/``):

- ``vpp_reference_polar_<case>.csv``: true_wind_speed_mps, true_wind_angle_deg, boat_speed_mps, heel_deg,
  leeway_deg, flat, reef, vmg_mps for true wind speeds 3, 5, 7, 10 m/s and true wind angles 30-180 deg in
  5 deg steps; NaN where the VPP finds no equilibrium. flat is the package's sail flattening factor
  (1 = full power), reef its main reef factor (1 = the case's whole main, area x reef^2); vmg_mps = boat
  speed x cos(true wind angle), positive toward the wind.
- ``vpp_reference_vmg.csv`` (one row per case and wind speed): the best upwind and downwind VMG [m/s] and
  their true wind angles [deg], refined on a 1 deg grid within 4 deg of the 5 deg grid's best; NaN where
  no angle has an equilibrium.
- ``vpp_reference_resistance.csv``: upright (heel 0, leeway 0) resistance of hull + keel fin + bulb +
  rudder, speed_mps, friction_n (viscous: ORC friction lines with form factors), residuary_n (hull
  residuary from the ORC surfaces plus the fin's and the bulb's), total_n, and total_n_package_axes (the
  total as the unpatched package reads the surfaces, see below), for 0.25-2.2 m/s in 0.05 m/s steps.
- ``benchmarks/figures/vpp_reference_real_boat.png``: one boat-speed polar per case and the resistance
  curve, with the data sheet's figures marked.
It then prints the best VMGs and the upright resistance beside the data sheet's table for the real boat
(``SHEET_UPWIND_VMG``, ``SHEET_DOWNWIND_VMG``, ``SHEET_RESISTANCE``).

Units: SI throughout (m, m/s, N, kg, deg); the package itself works in knots for wind speed input and
stored boat speed, converted here with its own factor (0.5144 m/s per knot) both ways.

Inputs of a case (json key: what this script makes of it): ``hull`` (Lwl, Loa, Bwl, Boa, Tc, Vol, WSA,
Amax, Tmax, Ff, Fa: the canoe body's particulars at 158.4 kg in sea water, measured on the CAD mesh) and
``mass`` go to the package's ``Yacht``; ``keel`` (Cu, Cl, Span, Tc_ratio, vol) to its ``Keel``, with the
fin's measured volume for the fin's residuary resistance; ``bulb`` (Chord, area = wetted area, vol, CG,
Tc_ratio) to its ``Bulb`` (wetted area, volume and form factor; no side force); ``rudder`` (Cu, Cl, Span,
Tc_ratio, vol) to its ``Rudder``; ``main`` (P, E, Roach, BAD) to its ``Main``, checked against the case's
``area`` and ``ce_above_wl`` (the package's centre of effort P/3 (1 + Roach) + BAD above the base of the
mast, plus ``HBI`` above the waterline; the full main's 2.056 m is its centroid less the boom's lift under
the sail); ``dummy_jib`` (I, J, LPG) and ``HBI`` to a ``Jib`` of 0.002 m2 (the package's aero model needs
a headsail; it adds nothing); ``GZ`` (heel [deg], gz_m [m]: the real hull, keel and rudder with the URDF's
centre of gravity 0.096 m above the waterline, free trim) to the righting moment. ``crew`` must be 0.

Assumptions (each a command-line option): the main alone; no crew righting moment (a robot); the sail
flattening factor allowed down to 0.25 (``--flat-min``; a stand-in for easing the sheet, the package's
floor is 0.53); each case's main carried whole (``--reef-min 1``: the package would otherwise reef it
to as little as a quarter of its area, its reduction factor RED down to 0.5, where that is faster or the
only equilibrium; the reefs are the cases R1 and R2); heel capped at 35 deg (``--phi-max``); a uniform
true wind (the true wind speed applies at the sail; ``--wind-profile`` takes the package's log profile
referred to 10 m, which cuts the wind at this 2 m centre of effort by a fifth). With these the script
gives the data sheet's table within 1 %. The reef floor is the one that matters: with ``--reef-min
0.5`` the full main finds an upwind equilibrium at 10 m/s (VMG 0.84 m/s at 47 deg, reefed by the
package to about 0.3 of its area) where the sheet, carrying it whole, finds none; at 3-7 m/s the
package never reefs.

The old reference, a stiffer parametric boat of our own estimate (``shared/eboat/vpp_inputs.json``:
an ``inputs`` block, no cases; centre of gravity 0.16 m below the waterline), still runs with
``--inputs <that json>``: it writes ``vpp_reference_polar.csv``, ``vpp_reference_vmg.csv`` and
``vpp_reference_resistance.csv`` without a case suffix to ``benchmarks/data/`` and the figure
``benchmarks/figures/vpp_reference.png``, and prints the sheet's "Independent anchors" beside its
results (``STIFF_BOAT_*``). It is retired as the project's reference; its numbers remain in
benchmarks/RESULTS.md ("An independent VPP of the same hull"), with the runs on the twin's procedural
hull (``--hull-form``, ``benchmarks/data/mesh_hull/``, ``mesh_hull_twin_stability/``).

The bug corrected here: python-vpp 1.0.0's ``HydroMod.__load_data`` reads ``dat/ORCi_Drag_Surfaces.csv``,
whose blocks are labelled "RRmult(lvr_i,btr_j)": rows (first column, 3 ... 9) are the length/volume
ratio LVR, columns (2.5 ... 9) the beam/draft ratio BTR. The package takes the row labels as BTR and the
column labels as LVR, builds ``RegularGridInterpolator((fn, btr, lvr), ...)`` on that and evaluates it at
``(fn, self.btr, self.lvr)``, so it looks the surface up at LVR := the boat's BTR and BTR := its LVR.
For the real E-Boat (LVR 4.72, BTR 6.76) that reads the residuary resistance of a boat far lighter for
its length. We do not edit the installed package: ``AxisFixedHydroMod`` (a subclass) reads the same csv
with our own parser and replaces ``_interp_Rr`` by an interpolator whose axes are (Fn, BTR, LVR) in
truth, so the package's own call ``_interp_Rr((fn, btr, lvr))`` gets the right value. As the package
does, a zero-resistance layer is added at Fn = 0. The package-axes reading is kept for comparison
(``total_n_package_axes``, and with ``--package-axes-polar`` a second polar in the summary).

The package's VPP builds its models by name inside ``python_vpp.VPPMod``; to make it use the subclasses
(fixed surfaces, uniform wind), the lower flat floor and the reef floor (its point solver called with the
lower bound of RED raised to ``--reef-min``), those module names are swapped for the time of a run and
restored afterwards (``_patched_vpp``). Nothing of the package is copied: this is our code
calling its classes ``Yacht``, ``Keel``, ``Bulb``, ``Rudder``, ``Main``, ``Jib``, ``VPP`` and its model
classes.

Other inputs: ``--hull-form FILE`` takes a JSON with waterline_length, waterline_beam, canoe_draft,
displaced_volume, wetted_area, max_section_area (e.g. ``dataclasses.asdict`` of
``ocean_warp.hull_form.HullForm``; other keys are ignored) in place of the case's hull particulars.
``--righting-arm FILE`` replaces the case's GZ curve by the one the simulator measures on its own boat
(a csv with columns series, heel_deg, gz_m, as ``benchmarks/studies/righting_arm.py`` writes
``benchmarks/data/righting_arm.csv``; the rows of ``--righting-arm-series``, default ``mesh``), so the
VPP sails a boat exactly as stiff as the twin. The package derives LVR and BTR from the particulars and
does not use Cp or Cm (printed for information).

Run (CPU, one core: about 1.5 min per case on a loaded 2-core machine, for the 5 deg angle grid and 1 deg
refinements near the best upwind and downwind VMG; ``--package-axes-polar`` adds the polar of the package's
own reading for comparison, about 3 min more per case):
    pip install -e ".[vpp]" && python -m benchmarks.references.vpp_reference --case R R1 R2
Options: --case, --inputs FILE, --hull-form FILE, --righting-arm FILE, --out DIR, --figure FILE,
--flat-min, --reef-min, --phi-max, --wind-profile, --package-axes-polar; the inputs' format and reader:
``benchmarks/references/vpp_inputs.py``; see --help.
"""

from __future__ import annotations

import argparse
import contextlib
import csv
import dataclasses
import math
import time
import warnings
from pathlib import Path

import numpy as np

from ocean_warp.atomic_files import atomic_output, save_figure
from benchmarks import DATA, FIGURES
from benchmarks.references.vpp_inputs import DEFAULT_INPUTS, VppBoat, input_cases, load_boat, read_righting_arm

REAL_BOAT_DATA = DATA / "real_boat"
"""Where the real boat's reference tables go [csv]."""
REAL_BOAT_FIGURE = FIGURES / "vpp_reference_real_boat.png"
TRUE_WIND_SPEEDS = (3.0, 5.0, 7.0, 10.0)  # m/s
TRUE_WIND_ANGLES = np.arange(30.0, 180.0 + 1e-9, 5.0)  # deg
RESISTANCE_SPEEDS = np.round(np.arange(0.25, 2.2 + 1e-9, 0.05), 2)  # m/s
REFINE_HALF_WIDTH = 4.0  # deg either side of the 5 deg grid's best VMG, in 1 deg steps

# The data sheet's table for the real boat (shared/eboat/README.md, "An independent VPP of the real boat"):
# independent numbers for the summary and the tests. Upwind: (VMG [m/s], true wind angle [deg]), None where
# the sheet finds no equilibrium at any angle.
SHEET_UPWIND_VMG = {
    "R": {3.0: (0.97, 40), 5.0: (1.06, 39), 7.0: (1.00, 41), 10.0: None},
    "R1": {3.0: (0.77, 44), 5.0: (1.05, 40), 7.0: (1.01, 41), 10.0: (0.76, 48)},
    "R2": {3.0: (0.49, 49), 5.0: (0.82, 44), 7.0: (0.99, 43), 10.0: (0.80, 49)},
}
SHEET_DOWNWIND_VMG = {"R": {3.0: 1.16, 5.0: 1.74, 7.0: 2.00, 10.0: 2.35}}  # [m/s], full main
SHEET_RESISTANCE = {1.0: 6.7, 1.5: 18.1, 1.7: 26.9, 2.0: 69.0}  # upright, hull + fin + bulb + rudder [N]

# The sheet's "Independent anchors" of the stiffer parametric boat (shared/eboat/vpp_inputs.json), retired.
STIFF_BOAT_UPWIND_VMG = {3.0: (1.09, 37), 5.0: (1.43, 33), 7.0: (1.49, 29), 10.0: (1.50, 31)}
STIFF_BOAT_BEAM = {3.0: 1.66, 5.0: 1.92, 7.0: 2.11, 10.0: 2.28}
STIFF_BOAT_BROAD = {3.0: 1.51, 5.0: 1.88, 7.0: 2.09, 10.0: 2.37}
STIFF_BOAT_RESISTANCE = {1.0: 5.9, 1.28: 10.5, 1.5: 16.0, 1.71: 25.0, 1.9: 52.0, 2.1: 98.0}


# ----------------------------------------------------------------------------------------------------
# The ORC residuary resistance surfaces, read with the axes the file labels.

def read_resistance_surfaces(path: Path):
    """Parse ORCi_Drag_Surfaces.csv: blocks '"RRmult(lvr_i,btr_j)",Fn=,<fn>', a row of BTR values,
    then one row per LVR (its value first). Returns fn (nf,), lvr (nl,), btr (nb,), rr (nf, nl, nb)."""
    with open(path, newline="") as f:
        rows = [r for r in csv.reader(f)]
    fns, blocks, lvr, btr = [], [], None, None
    i = 0
    while i < len(rows):
        row = rows[i]
        if row and row[0].startswith("RRmult"):
            if row[0] != "RRmult(lvr_i,btr_j)":
                raise ValueError(f"unexpected block label {row[0]!r} in {path}")
            fns.append(float(row[2]))
            btr_here = np.array([float(v) for v in rows[i + 1][1:] if v.strip()])
            block, lvr_here, j = [], [], i + 2
            while j < len(rows) and rows[j] and rows[j][0].strip() and not rows[j][0].startswith("RRmult"):
                lvr_here.append(float(rows[j][0]))
                block.append([float(v) for v in rows[j][1:1 + len(btr_here)]])
                j += 1
            if lvr is None:
                lvr, btr = np.array(lvr_here), btr_here
            elif not (np.array_equal(lvr, lvr_here) and np.array_equal(btr, btr_here)):
                raise ValueError(f"blocks of {path} differ in their LVR/BTR grids")
            blocks.append(block)
            i = j
        else:
            i += 1
    return np.array(fns), lvr, btr, np.array(blocks)


def fixed_rr_interpolator(path: Path):
    """Interpolator taking points (fn, btr, lvr), the package's calling order, with the file's axes
    put right; a zero layer at Fn = 0 and linear extrapolation outside the grid, as the package does."""
    from scipy.interpolate import RegularGridInterpolator

    fn, lvr, btr, rr = read_resistance_surfaces(path)
    fn = np.concatenate([[0.0], fn])
    rr = np.concatenate([np.zeros((1,) + rr.shape[1:]), rr])
    return RegularGridInterpolator((fn, btr, lvr), rr.transpose(0, 2, 1), method="linear",
                                   bounds_error=False, fill_value=None)


# ----------------------------------------------------------------------------------------------------
# Subclasses of the package's classes.

def _make_classes():
    """Our subclasses, built on import of python_vpp (kept inside a function so --help works without
    the optional dependency)."""
    from python_vpp import Yacht
    from python_vpp.AeroMod import Z_REF, AeroMod, wind_triangle
    from python_vpp.HydroMod import HydroMod
    from python_vpp.UtilsMod import DATA_DIR

    surfaces = DATA_DIR / "ORCi_Drag_Surfaces.csv"
    fixed = fixed_rr_interpolator(surfaces)

    class AxisFixedHydroMod(HydroMod):
        """HydroMod whose residuary surfaces are read with LVR and BTR on their labelled axes."""

        def __init__(self, *args, **kwargs):
            super().__init__(*args, **kwargs)
            self.package_axes_interp_Rr = self._interp_Rr
            self._interp_Rr = fixed

    class UniformWindAeroMod(AeroMod):
        """AeroMod with the true wind speed the same at every height (no log wind profile)."""

        def _update_windTriangle(self):
            self.awa, self.aws = wind_triangle(self.tws, self.twa, self.vb, self.phi, Z_REF)
            _, self.aws_hull = wind_triangle(self.tws, self.twa, self.vb, self.phi, Z_REF)

    class RobotYacht(Yacht):
        """A Yacht without crew on the rail: no crew righting moment."""

        def _get_RmC(self, phi):
            return 0.0 * np.asarray(phi, dtype=float)

    return AxisFixedHydroMod, UniformWindAeroMod, RobotYacht, HydroMod, AeroMod, surfaces


@contextlib.contextmanager
def _patched_vpp(hydro_cls, aero_cls, flat_min, reef_min):
    """Let python_vpp.VPPMod build its models from the given classes, with the given flat floor, and keep
    its reduction factor RED at or above ``reef_min`` (RED <= 1 reefs the main to RED^2 of its area)."""
    from python_vpp import VPPMod

    saved = VPPMod.HydroMod, VPPMod.AeroMod, VPPMod.FLAT_MIN, VPPMod._solve_point
    solve_point = VPPMod._solve_point

    def solve_point_reef_floor(aero, hydro, tws, twa, phi_max, guesses, fallbacks=(), red_bounds=(0.5, 2.0)):
        low = max(red_bounds[0], reef_min) if aero.up else red_bounds[0]
        return solve_point(aero, hydro, tws, twa, phi_max, guesses, fallbacks, (low, red_bounds[1]))

    VPPMod.HydroMod, VPPMod.AeroMod, VPPMod.FLAT_MIN = hydro_cls, aero_cls, flat_min
    VPPMod._solve_point = solve_point_reef_floor
    try:
        yield
    finally:
        VPPMod.HydroMod, VPPMod.AeroMod, VPPMod.FLAT_MIN, VPPMod._solve_point = saved


# ----------------------------------------------------------------------------------------------------
# The boat (its inputs: benchmarks/references/vpp_inputs.py).

def build_yacht(boat: VppBoat, yacht_cls, righting_arm: dict | None = None):
    """The package's Yacht of ``boat`` (class ``yacht_cls``), with ``righting_arm`` for its GZ if given."""
    from python_vpp import Bulb, Jib, Keel, Main, Rudder

    k, r, m, j = boat.keel, boat.rudder, boat.main, boat.dummy_jib
    keel = Keel(Cu=k["Cu"], Cl=k["Cl"], Span=k["Span"], Tc_ratio=k["Tc_ratio"])
    keel.vol = k["vol"]  # the physical fin (and, in the old format, ballast) volume, not the package's estimate
    appendages = [keel]
    if boat.bulb is not None:
        b = boat.bulb
        appendages.append(Bulb(Chord=b["Chord"], area=b["area"], vol=b["vol"], CG=b["CG"], Tc_ratio=b["Tc_ratio"]))
    appendages.append(Rudder(Cu=r["Cu"], Cl=r["Cl"], Span=r["Span"], Tc_ratio=r["Tc_ratio"]))
    main = Main("Main", P=m["P"], E=m["E"], Roach=m["Roach"], BAD=m["BAD"])
    jib = Jib("none", I=j["I"], J=j["J"], LPG=j["LPG"], HBI=boat.hbi)
    h = boat.hull
    return yacht_cls(Name="E-Boat", Lwl=h["Lwl"], Vol=h["Vol"], Bwl=h["Bwl"], Tc=h["Tc"], WSA=h["WSA"],
                     Tmax=h["Tmax"], Amax=h["Amax"], Mass=boat.mass, Loa=h["Loa"], Boa=h["Boa"], Ff=h["Ff"],
                     Fa=h["Fa"], App=appendages, Sails=[main, jib],
                     GZ=righting_arm if righting_arm is not None else boat.gz, crew_weight=0.0)


# ----------------------------------------------------------------------------------------------------
# Runs.

def upright_resistance(hydro, speeds, interp):
    """(friction, residuary, total) [N] upright, leeway 0, with the given residuary interpolator."""
    saved = hydro._interp_Rr
    hydro._interp_Rr = interp
    out = np.zeros((len(speeds), 3))
    try:
        for k, v in enumerate(speeds):
            total = float(hydro.update(float(v), 0.0, 0.0)[0])  # no side force: no induced drag
            residuary = float(hydro._get_Rr())  # hull + fin + bulb, at the state update() just set
            out[k] = total - residuary, residuary, total
    finally:
        hydro._interp_Rr = saved
    return out


@dataclasses.dataclass
class Polar:
    """A VPP polar on a (true wind speed, true wind angle) grid; NaN where no equilibrium."""

    tws: np.ndarray
    """(S,) true wind speeds [m/s]."""
    twa: np.ndarray
    """(A,) true wind angles [deg]."""
    speed: np.ndarray
    """(S, A) boat speed [m/s]."""
    heel: np.ndarray
    """(S, A) heel [deg]."""
    leeway: np.ndarray
    """(S, A) leeway [deg]."""
    flat: np.ndarray
    """(S, A) the package's sail flattening factor (1 = full power)."""
    reef: np.ndarray
    """(S, A) the main's reef factor (1 = whole main; area x reef^2)."""


def run_polar(yacht, hydro_cls, aero_cls, flat_min, reef_min, phi_max, tws_mps, twa_deg) -> Polar:
    """Solve the VPP on the grid (one sail set: main + dummy jib)."""
    from python_vpp import VPP
    from python_vpp.UtilsMod import KNOTS_TO_MPS

    tws_mps, twa_deg = np.asarray(tws_mps, dtype=float), np.asarray(twa_deg, dtype=float)
    with _patched_vpp(hydro_cls, aero_cls, flat_min, reef_min):
        vpp = VPP(yacht)
        vpp.set_analysis(tws_mps / KNOTS_TO_MPS, twa_deg, phi_max=phi_max)
        vpp.run(method="sequential")
    store = vpp.store[:, :, 0, :]  # rows vb [kn], heel, leeway, flat, RED; all 0 where not solved
    solved = store[..., 0] > 0

    def where_solved(values):
        return np.where(solved, values, np.nan)

    # RED above 1 shortens the jib's foot (nothing, for the dummy jib); at or below 1 it reefs the main.
    return Polar(tws_mps, twa_deg, where_solved(store[..., 0] * KNOTS_TO_MPS), where_solved(store[..., 1]),
                 where_solved(store[..., 2]), where_solved(store[..., 3]),
                 where_solved(np.minimum(store[..., 4], 1.0)))


def best_vmg(polar: Polar, refine=None) -> dict[float, dict[str, float]]:
    """Per wind speed: the best upwind VMG (toward the wind, true wind angles below 90 deg) and downwind VMG
    (away from it, above 90 deg) [m/s] and their true wind angles [deg], NaN where no such angle has an
    equilibrium. ``refine(tws, angles)``, if
    given, solves a finer angle grid (a Polar of one wind speed); it is asked for 1 deg steps within
    REFINE_HALF_WIDTH of the grid's best, and a better VMG there wins."""
    out = {}
    for i, tws in enumerate(polar.tws):
        row = {}
        for side, sign in (("upwind", 1.0), ("downwind", -1.0)):
            vmg = sign * polar.speed[i] * np.cos(np.radians(polar.twa))
            vmg[sign * (90.0 - polar.twa) <= 0.0] = np.nan  # upwind: angles below 90 deg; downwind: above
            if np.all(np.isnan(vmg)):
                row[f"{side}_vmg_mps"], row[f"{side}_twa_deg"] = math.nan, math.nan
                continue
            j = int(np.nanargmax(vmg))
            best, angle = float(vmg[j]), float(polar.twa[j])
            if refine is not None:
                low, high = (20.0, 89.0) if sign > 0 else (91.0, 180.0)
                twa = np.arange(max(angle - REFINE_HALF_WIDTH, low), min(angle + REFINE_HALF_WIDTH, high) + 1e-9, 1.0)
                fine = refine(float(tws), twa)
                fine_vmg = sign * fine.speed[0] * np.cos(np.radians(twa))
                if not np.all(np.isnan(fine_vmg)) and np.nanmax(fine_vmg) > best:
                    k = int(np.nanargmax(fine_vmg))
                    best, angle = float(fine_vmg[k]), float(twa[k])
            row[f"{side}_vmg_mps"], row[f"{side}_twa_deg"] = best, angle
        out[float(tws)] = row
    return out


# ----------------------------------------------------------------------------------------------------
# Output.

def _atomic_write_csv(path: Path, header, rows):
    with atomic_output(path) as temporary, open(temporary, "w", newline="") as handle:
        writer = csv.writer(handle)
        writer.writerow(header)
        for row in rows:
            writer.writerow(["nan" if isinstance(v, float) and math.isnan(v) else
                             (f"{v:.6g}" if isinstance(v, float) else v) for v in row])


def write_polar_csv(path: Path, polar: Polar):
    rows = []
    for i, tws in enumerate(polar.tws):
        for j, twa in enumerate(polar.twa):
            vb = float(polar.speed[i, j])
            rows.append([float(tws), float(twa), vb, float(polar.heel[i, j]), float(polar.leeway[i, j]),
                         float(polar.flat[i, j]), float(polar.reef[i, j]),
                         round(vb * math.cos(math.radians(twa)), 12)])  # exactly 0 at 90 deg
    _atomic_write_csv(path, ["true_wind_speed_mps", "true_wind_angle_deg", "boat_speed_mps", "heel_deg",
                             "leeway_deg", "flat", "reef", "vmg_mps"], rows)


def write_figure(path: Path, results, resistance, package_resistance, anchors):
    """One polar panel per case (the sheet's best VMGs marked x) and the resistance curves, two panels a row."""
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    panels = len(results) + 1
    columns = min(panels, 2)
    rows = math.ceil(panels / columns)
    fig = plt.figure(figsize=(5.6 * columns, 4.9 * rows))
    top = max(float(np.nanmax(polar.speed)) for _, polar, _, _ in results if np.isfinite(polar.speed).any())
    for n, (boat, polar, _, _) in enumerate(results):
        ax = fig.add_subplot(rows, columns, n + 1, projection="polar")
        ax.set_theta_zero_location("N")
        ax.set_theta_direction(-1)
        ax.set_thetamin(0)
        ax.set_thetamax(180)
        for i, tws in enumerate(polar.tws):
            line, = ax.plot(np.radians(polar.twa), polar.speed[i], "-o", ms=2.5, label=f"TWS {tws:g} m/s")
            sheet = []  # (angle [deg], boat speed [m/s]) of the sheet's best VMGs
            if boat.case in SHEET_UPWIND_VMG and SHEET_UPWIND_VMG[boat.case].get(tws):
                vmg, angle = SHEET_UPWIND_VMG[boat.case][tws]
                sheet.append((angle, vmg / math.cos(math.radians(angle))))
            if boat.case in SHEET_DOWNWIND_VMG and tws in SHEET_DOWNWIND_VMG[boat.case]:
                sheet.append((180.0, SHEET_DOWNWIND_VMG[boat.case][tws]))
            ax.plot([math.radians(a) for a, _ in sheet], [v for _, v in sheet], "x", color=line.get_color(), ms=8)
        ax.set_rmax(0.5 * math.ceil(2.0 * top))  # the same scale in every panel
        where = f"case {boat.case}: " if boat.case else ""
        ax.set_title(f"{where}main {boat.main_area:.2f} m2, boat speed [m/s]", fontsize=10)
        if n == 0:
            ax.legend(loc="lower left", bbox_to_anchor=(-0.25, 0.0), fontsize=8)
    ax2 = fig.add_subplot(rows, columns, len(results) + 1)
    ax2.plot(RESISTANCE_SPEEDS, resistance[:, 2], "-", label="total, surfaces read as labelled (fixed)")
    ax2.plot(RESISTANCE_SPEEDS, package_resistance[:, 2], "--", label="total, package's swapped axes")
    ax2.plot(RESISTANCE_SPEEDS, resistance[:, 0], ":", label="friction (viscous)")
    ax2.plot(list(anchors), list(anchors.values()), "kx", label="data sheet")
    ax2.set_xlabel("boat speed [m/s]")
    ax2.set_ylabel("upright resistance [N]")
    ax2.set_title("Upright resistance (heel 0, leeway 0)", fontsize=10)
    ax2.grid(alpha=0.3)
    ax2.legend(fontsize=8)
    fig.suptitle("E-Boat VPP (python-vpp, ORC models, residuary axes fixed), flat water; x: the data sheet's figures",
                 fontsize=11)
    fig.tight_layout()
    save_figure(fig, path, dpi=100)


def _percent(ours, sheet):
    return "" if math.isnan(ours) else f"{100.0 * (ours / sheet - 1.0):+5.1f} %"


def print_sheet_summary(results, resistance_at):
    """The real boat: best VMGs and upright resistance beside the data sheet's table."""
    f = lambda v: "  -  " if math.isnan(v) else f"{v:5.2f}"  # noqa: E731
    a = lambda v: "   " if math.isnan(v) else f"{v:3.0f}"  # noqa: E731
    print("\nBest VMG [m/s] (true wind angle [deg]): this run (fixed axes; pkg = package's swapped axes, with "
          "--package-axes-polar) and the data sheet; -: no equilibrium, or not run")
    print(f"{'case':>4} {'TWS':>4} | {'upwind':^13} {'pkg':^13} {'sheet':^13} {'diff':>8} | "
          f"{'downwind':^13} {'sheet':>5} {'diff':>8}")
    for boat, _, vmg, package in results:
        for tws, row in vmg.items():
            sheet_up = SHEET_UPWIND_VMG.get(boat.case, {}).get(tws)
            sheet_down = SHEET_DOWNWIND_VMG.get(boat.case, {}).get(tws)
            up, up_angle = row["upwind_vmg_mps"], row["upwind_twa_deg"]
            pkg = package["vmg"][tws] if package else {"upwind_vmg_mps": math.nan, "upwind_twa_deg": math.nan}
            sheet_text = (f"{sheet_up[0]:5.2f} ({sheet_up[1]:3d})  " if sheet_up else
                          (" none        " if boat.case in SHEET_UPWIND_VMG else "             "))
            print(f"{boat.label:>4} {tws:4g} | {f(up)} ({a(up_angle)})  {f(pkg['upwind_vmg_mps'])} "
                  f"({a(pkg['upwind_twa_deg'])})  {sheet_text}{_percent(up, sheet_up[0]) if sheet_up else '':>8} | "
                  f"{f(row['downwind_vmg_mps'])} ({a(row['downwind_twa_deg'])})  "
                  f"{f(sheet_down) if sheet_down else '     '} "
                  f"{_percent(row['downwind_vmg_mps'], sheet_down) if sheet_down else '':>8}")
    print("\nUpright resistance [N]: speed m/s | fixed | package axes | sheet | diff")
    for v, (fixed, pkg) in resistance_at.items():
        print(f"  {v:5.2f} | {fixed:6.1f} | {pkg:6.1f} | {SHEET_RESISTANCE[v]:6.1f} | "
              f"{_percent(fixed, SHEET_RESISTANCE[v])}")


def _at(polar: Polar, i, twa):
    return float(polar.speed[i, int(np.argmin(np.abs(polar.twa - twa)))])


def print_stiff_boat_summary(polar, vmg, package, resistance_at):
    """The old stiff boat: against the sheet's "Independent anchors"."""
    f = lambda v: "  nan" if math.isnan(v) else f"{v:5.2f}"  # noqa: E731
    print("\nSummary: fixed = surfaces read as labelled; pkg = package's swapped axes; sheet = the stiff boat's "
          "anchors")
    print(f"{'TWS m/s':>7} | {'best upwind VMG m/s (TWA)':^38} | {'beam reach 90 m/s':^21} |"
          f" {'broad reach 120 m/s':^21}")
    print(f"{'':>7} | {'fixed':^12} {'pkg':^12} {'sheet':^12} | {'fixed':>5} {'pkg':>5} {'sheet':>6}"
          f"    | {'fixed':>5} {'pkg':>5} {'sheet':>6}")
    for i, tws in enumerate(polar.tws):
        tws = float(tws)
        v, a = vmg[tws]["upwind_vmg_mps"], vmg[tws]["upwind_twa_deg"]
        pv, pa = ((package["vmg"][tws]["upwind_vmg_mps"], package["vmg"][tws]["upwind_twa_deg"]) if package
                  else (math.nan, math.nan))
        ps = package["polar"] if package else dataclasses.replace(polar, speed=np.full_like(polar.speed, np.nan))
        rv, ra = STIFF_BOAT_UPWIND_VMG[tws]
        print(f"{tws:7g} | {f(v)} ({a:3.0f})  {f(pv)} ({pa:3.0f})  {rv:5.2f} ({ra:3d})  |"
              f" {f(_at(polar, i, 90))} {f(_at(ps, i, 90))} {STIFF_BOAT_BEAM[tws]:6.2f}    |"
              f" {f(_at(polar, i, 120))} {f(_at(ps, i, 120))} {STIFF_BOAT_BROAD[tws]:6.2f}")
    print("\nUpright resistance [N]: speed m/s | fixed | package axes | sheet")
    for v, (fixed, pkg) in resistance_at.items():
        print(f"  {v:5.2f} | {fixed:7.1f} | {pkg:7.1f} | {STIFF_BOAT_RESISTANCE[v]:6.1f}")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    parser.add_argument("--inputs", type=Path, default=DEFAULT_INPUTS,
                        help="the VPP inputs json: the real boat's cases, or the old stiff boat's 'inputs'")
    parser.add_argument("--case", nargs="+", default=None,
                        help="case(s) of a json with cases (R: full main, R1, R2: reefed); default R")
    parser.add_argument("--hull-form", type=Path, default=None,
                        help="JSON of hull particulars replacing the inputs' (waterline_length, ...)")
    parser.add_argument("--righting-arm", type=Path, default=None,
                        help="csv of the righting arm replacing the inputs' GZ (series, heel_deg, gz_m), e.g. the "
                             "simulator's benchmarks/data/righting_arm.csv")
    parser.add_argument("--righting-arm-series", default="mesh", help="the rows of --righting-arm to use")
    parser.add_argument("--out", type=Path, default=None,
                        help="folder of the csvs (default benchmarks/data/real_boat, or benchmarks/data for the "
                             "old format)")
    parser.add_argument("--figure", type=Path, default=None,
                        help="the figure (default benchmarks/figures/vpp_reference_real_boat.png, or "
                             "vpp_reference.png for the old format)")
    parser.add_argument("--flat-min", type=float, default=0.25, help="lowest sail flattening factor")
    parser.add_argument("--reef-min", type=float, default=None,
                        help="lowest reef factor the VPP may give the main (area x reef^2): default 1 for a json "
                             "with cases (each case's main carried whole: the reefs are the cases), 0.5 (the "
                             "package's own floor) for the old format")
    parser.add_argument("--phi-max", type=float, default=35.0, help="heel cap [deg]")
    parser.add_argument("--wind-profile", action="store_true",
                        help="use the package's log wind profile (true wind at 10 m) instead of uniform wind")
    parser.add_argument("--no-refine", action="store_true", help="best VMGs from the 5 deg grid only")
    parser.add_argument("--package-axes-polar", action="store_true",
                        help="also solve the polar with the package's swapped axes (for the summary's comparison; "
                             "doubles the run time or more)")
    args = parser.parse_args(argv)
    if not (0.0 < args.flat_min <= 1.0):
        parser.error(f"--flat-min must be in (0, 1], got {args.flat_min}")
    if args.reef_min is not None and not (0.5 <= args.reef_min <= 1.0):
        parser.error(f"--reef-min must be in [0.5, 1], got {args.reef_min}")
    if not (0.0 < args.phi_max <= 90.0):
        parser.error(f"--phi-max must be in (0, 90] deg, got {args.phi_max}")

    try:
        cases = input_cases(args.inputs)
        if cases is None:
            boats = [load_boat(args.inputs, None if args.case is None else args.case[0], args.hull_form)]
        else:
            boats = [load_boat(args.inputs, c, args.hull_form) for c in (args.case or ["R"])]
        righting_arm = (read_righting_arm(args.righting_arm, args.righting_arm_series)
                        if args.righting_arm is not None else None)
    except (ValueError, OSError, KeyError, TypeError) as error:
        parser.error(str(error))
    real_format = cases is not None
    if args.reef_min is None:
        args.reef_min = 1.0 if real_format else 0.5
    out = args.out if args.out is not None else (REAL_BOAT_DATA if real_format else DATA)
    figure = args.figure if args.figure is not None else (
        REAL_BOAT_FIGURE if real_format else FIGURES / "vpp_reference.png")

    try:
        import python_vpp
    except ImportError:
        raise SystemExit('python-vpp is not installed: pip install -e ".[vpp]"') from None
    fixed_hydro, uniform_aero, robot_yacht, package_hydro, package_aero, surfaces = _make_classes()
    aero_cls = package_aero if args.wind_profile else uniform_aero
    t0 = time.perf_counter()
    print(f"python-vpp {python_vpp.__version__}; inputs {args.inputs}"
          + (f"; hull form {args.hull_form}" if args.hull_form else "")
          + (f"; righting arm {args.righting_arm} ({args.righting_arm_series})" if args.righting_arm else ""))
    print(f"residuary surfaces: {surfaces} (read as labelled: rows LVR, columns BTR)")
    print(f"flat >= {args.flat_min}, heel <= {args.phi_max} deg, "
          f"main reef factor >= {args.reef_min}, "
          f"{'log wind profile (10 m)' if args.wind_profile else 'uniform wind'}, no crew righting moment")

    results, tables = [], {}
    for boat in boats:
        yacht = build_yacht(boat, robot_yacht, righting_arm)
        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            hydro = fixed_hydro(yacht)
        for w in caught:
            print(f"warning (HydroMod): {w.message}")
        h = boat.hull
        cp, cm = h["Vol"] / (h["Amax"] * h["Lwl"]), h["Amax"] / (h["Bwl"] * h["Tc"])
        gz = np.interp(np.arange(0.0, 60.1, 5.0), yacht._gz_data["Heel"], yacht._gz_data["GZ"])
        print(f"\ncase {boat.label}: Lwl {h['Lwl']:.3f} m, Bwl {h['Bwl']:.3f} m, Tc {h['Tc']:.3f} m, "
              f"Vol {h['Vol']:.4f} m3, WSA {h['WSA']:.3f} m2, Amax {h['Amax']:.4f} m2, mass {boat.mass:.1f} kg; "
              f"LVR {yacht.lvr:.3f}, BTR {yacht.btr:.3f}, Cp {cp:.3f}, Cm {cm:.3f}; main {boat.main_area:.3f} m2, "
              f"its centre of effort {boat.ce_above_waterline:.3f} m above the waterline; "
              f"largest GZ to 60 deg {gz.max():.3f} m ({gz.max() * boat.mass * 9.81:.0f} N m)")
        volume = h["Vol"] + boat.keel["vol"] + (boat.bulb["vol"] if boat.bulb else 0.0) + boat.rudder.get("vol", 0.0)
        if abs(hydro.rho * volume / boat.mass - 1) > 0.05:
            print(f"note: canoe body + appendage volumes float {hydro.rho * volume:.1f} kg, not the mass "
                  f"{boat.mass:.1f} kg (the package takes resistance per unit of the mass and does not check)")

        resistance = upright_resistance(hydro, RESISTANCE_SPEEDS, hydro._interp_Rr)
        package_resistance = upright_resistance(hydro, RESISTANCE_SPEEDS, hydro.package_axes_interp_Rr)
        anchors = SHEET_RESISTANCE if real_format else STIFF_BOAT_RESISTANCE
        speeds = np.array(list(anchors))
        at_fixed = upright_resistance(hydro, speeds, hydro._interp_Rr)[:, 2]
        at_pkg = upright_resistance(hydro, speeds, hydro.package_axes_interp_Rr)[:, 2]
        tables[boat.label] = (resistance, package_resistance,
                              {float(v): (a, b) for v, a, b in zip(speeds, at_fixed, at_pkg)})

        def solver(hydro_cls):
            """The VPP on (wind speeds, angles) with this run's options and the given residuary reading."""
            return lambda tws, twa: run_polar(yacht, hydro_cls, aero_cls, args.flat_min, args.reef_min,
                                              args.phi_max, np.atleast_1d(tws), twa)

        with warnings.catch_warnings(record=True) as caught:
            warnings.simplefilter("always")
            t1 = time.perf_counter()
            polar = solver(fixed_hydro)(TRUE_WIND_SPEEDS, TRUE_WIND_ANGLES)
            vmg = best_vmg(polar, None if args.no_refine else solver(fixed_hydro))
            print(f"case {boat.label}: polar (fixed axes) {time.perf_counter() - t1:.1f} s")
            package = None
            if args.package_axes_polar:
                t1 = time.perf_counter()
                p_polar = solver(package_hydro)(TRUE_WIND_SPEEDS, TRUE_WIND_ANGLES)
                package = {"polar": p_polar,
                           "vmg": best_vmg(p_polar, None if args.no_refine else solver(package_hydro))}
                print(f"case {boat.label}: polar (package axes) {time.perf_counter() - t1:.1f} s")
        messages = {}
        for w in caught:
            key = f"{w.category.__name__}: {str(w.message).splitlines()[0][:100]}"
            messages[key] = messages.get(key, 0) + 1
        for key, n in messages.items():
            print(f"warning x{n}: {key}")
        unsolved = [(float(tws), float(polar.twa[j])) for i, tws in enumerate(polar.tws)
                    for j in range(len(polar.twa)) if math.isnan(polar.speed[i, j])]
        print(f"case {boat.label}: no equilibrium (NaN) at {len(unsolved)} of {polar.speed.size} points"
              + (f": {unsolved}" if unsolved else ""))
        write_polar_csv(out / f"vpp_reference_polar{'_' + boat.case if boat.case else ''}.csv", polar)
        results.append((boat, polar, vmg, package))

    first = tables[boats[0].label]
    if any(not np.allclose(t[0], first[0]) for t in tables.values()):
        raise SystemExit("the cases differ in their upright resistance (hull or appendages): run them one at a time")
    _atomic_write_csv(out / "vpp_reference_resistance.csv",
                      ["speed_mps", "friction_n", "residuary_n", "total_n", "total_n_package_axes"],
                      [[float(v), *map(float, r), float(p)] for v, r, p in
                       zip(RESISTANCE_SPEEDS, first[0], first[1][:, 2])])
    _atomic_write_csv(out / "vpp_reference_vmg.csv",
                      ["case", "main_area_m2", "true_wind_speed_mps", "upwind_vmg_mps", "upwind_twa_deg",
                       "downwind_vmg_mps", "downwind_twa_deg"],
                      [[boat.label, round(boat.main_area, 4), tws, row["upwind_vmg_mps"], row["upwind_twa_deg"],
                        row["downwind_vmg_mps"], row["downwind_twa_deg"]]
                       for boat, _, vmg, _ in results for tws, row in vmg.items()])
    write_figure(figure, results, first[0], first[1], SHEET_RESISTANCE if real_format else STIFF_BOAT_RESISTANCE)

    if real_format:
        print_sheet_summary(results, first[2])
    else:
        boat, polar, vmg, package = results[0]
        print_stiff_boat_summary(polar, vmg, package, first[2])
    print(f"\nwrote {out}/vpp_reference_*.csv, {figure}; {time.perf_counter() - t0:.1f} s in all")


if __name__ == "__main__":
    main()
