"""An independent velocity prediction (VPP) of the E-Boat, to check the simulator's sailing against.

The E-Boat is a 2.5 m sailing robot with a main sail alone (no jib). This script runs the ORC-model VPP
of the PyPI package ``python-vpp`` (1.0.0, import name ``python_vpp``; MIT-licensed, used only by this
benchmark and never by the ``ocean_warp`` core) on the inputs of ``shared/eboat/vpp_inputs.json`` (see
``shared/eboat/README.md``, "Independent anchors"), in flat water, and writes:

- ``<out>/vpp_reference_polar.csv``: true_wind_speed_mps, true_wind_angle_deg, boat_speed_mps, heel_deg,
  leeway_deg, vmg_mps for true wind speeds 3, 5, 7, 10 m/s and true wind angles 30-180 deg in 5 deg
  steps; NaN where the VPP finds no equilibrium. vmg_mps = boat speed x cos(true wind angle), positive
  toward the wind.
- ``<out>/vpp_reference_resistance.csv``: upright (heel 0, leeway 0) resistance of hull + keel + rudder,
  speed_mps, friction_n (viscous: ITTC/ORC friction lines with form factors), residuary_n (hull
  residuary from the ORC surfaces plus the keel's), total_n, and total_n_package_axes (the total as the
  unpatched package reads the surfaces, see below), for 0.25-2.2 m/s in 0.05 m/s steps.
- ``benchmarks/figures/vpp_reference.png``: the boat-speed polar and the resistance curve.
It then prints a summary beside the figures of the README.

Units: SI throughout (m, m/s, N, kg, deg); the package itself works in knots for wind speed input and
stored boat speed, converted here with its own factor (0.5144 m/s per knot) both ways.

Assumptions of the inputs (they follow the json's "_about"): the main alone, with a negligible dummy jib
(0.0017 m2) because the package's aero model needs a headsail; no crew righting moment (a robot); keel
fin + ballast volume set to the physical 0.0078 m3; the sail flattening factor allowed down to 0.25 (a
stand-in for easing the sheet; the package's floor is 0.53); heel capped at 35 deg; a uniform true wind
(the true wind speed applies at the sail; the package's log wind profile referred to 10 m would cut the
wind at this 1.4 m rig by a quarter). Each is a command-line option.

The bug corrected here: python-vpp 1.0.0's ``HydroMod.__load_data`` reads ``dat/ORCi_Drag_Surfaces.csv``,
whose blocks are labelled "RRmult(lvr_i,btr_j)": rows (first column, 3 ... 9) are the length/volume
ratio LVR, columns (2.5 ... 9) the beam/draft ratio BTR. The package takes the row labels as BTR and the
column labels as LVR, builds ``RegularGridInterpolator((fn, btr, lvr), ...)`` on that and evaluates it at
``(fn, self.btr, self.lvr)``, so it looks the surface up at LVR := the boat's BTR and BTR := its LVR.
For the E-Boat (LVR 4.56, BTR 3.2) that reads the residuary resistance of a boat far heavier for its
length. We do not edit the installed package: ``AxisFixedHydroMod`` (a subclass) reads the same csv
with our own parser and replaces ``_interp_Rr`` by an interpolator whose axes are (Fn, BTR, LVR) in
truth, so the package's own call ``_interp_Rr((fn, btr, lvr))`` gets the right value. As the package
does, a zero-resistance layer is added at Fn = 0. The package-axes reading is kept for comparison
(``total_n_package_axes``, and the summary's second polar).

The package's VPP builds its models by name inside ``python_vpp.VPPMod``; to make it use the subclasses
(fixed surfaces, uniform wind) and the lower flat floor, those module names are swapped for the time of
a run and restored afterwards (``_patched_vpp``). Nothing of the package is copied: this is our code
calling its classes ``Yacht``, ``Keel``, ``Rudder``, ``Main``, ``Jib``, ``VPP`` and its model classes.

Hull particulars: by default the json's (a parametric estimate: Lwl 2.4 m ...). ``--hull-form FILE``
takes a JSON with waterline_length, waterline_beam, canoe_draft, displaced_volume, wetted_area,
max_section_area (e.g. ``dataclasses.asdict`` of ``ocean_warp.hull_form.HullForm``; other keys are
ignored) for the simulator's own procedural hull. ``--righting-arm FILE`` replaces the json's GZ curve
(from a parametric hull with the centre of gravity 0.16 m below the waterline and a 6 kg rig) by the
simulator's own (``benchmarks/data/righting_arm.csv``, the sheet's link table: centre of gravity 0.16 m
above the waterline, a 12.5 kg mast), so the VPP sails a boat as stiff as the twin. The mass, freeboards
and appendages stay the json's; the package derives LVR and BTR from the particulars and does not use Cp or Cm (printed
for information).

Run (CPU, about 30 s: 5 deg angle grid, a 1 deg refinement near the best upwind VMG, and the
package-axes polar for comparison):
    pip install -e ".[vpp]" && python -m benchmarks.references.vpp_reference
Options: --inputs FILE, --hull-form FILE, --out DIR, --figure FILE, --no-package-axes-polar (skip the
second, unpatched polar that the summary compares), see --help.
"""

from __future__ import annotations

import argparse
import contextlib
import csv
import json
import math
import time
import warnings
from pathlib import Path

import numpy as np

from ocean_warp.atomic_files import atomic_output, save_figure
from benchmarks import REPO, DATA, FIGURES

DEFAULT_INPUTS = REPO.parent / "shared/eboat/vpp_inputs.json"
TRUE_WIND_SPEEDS = (3.0, 5.0, 7.0, 10.0)  # m/s
TRUE_WIND_ANGLES = np.arange(30.0, 180.0 + 1e-9, 5.0)  # deg
RESISTANCE_SPEEDS = np.round(np.arange(0.25, 2.2 + 1e-9, 0.05), 2)  # m/s

# The README's figures ("Independent anchors"), for the summary.
README_VMG = {3.0: (1.09, 37), 5.0: (1.43, 33), 7.0: (1.49, 29), 10.0: (1.50, 31)}
README_BEAM = {3.0: 1.66, 5.0: 1.92, 7.0: 2.11, 10.0: 2.28}
README_BROAD = {3.0: 1.51, 5.0: 1.88, 7.0: 2.09, 10.0: 2.37}
README_RESISTANCE = {1.0: 5.9, 1.28: 10.5, 1.5: 16.0, 1.71: 25.0, 1.9: 52.0, 2.1: 98.0}

HULL_FORM_KEYS = {  # --hull-form key -> Yacht argument
    "waterline_length": "Lwl", "waterline_beam": "Bwl", "canoe_draft": "Tc",
    "displaced_volume": "Vol", "wetted_area": "WSA", "max_section_area": "Amax",
}


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
def _patched_vpp(hydro_cls, aero_cls, flat_min):
    """Let python_vpp.VPPMod build its models from the given classes, with the given flat floor."""
    from python_vpp import VPPMod

    saved = VPPMod.HydroMod, VPPMod.AeroMod, VPPMod.FLAT_MIN
    VPPMod.HydroMod, VPPMod.AeroMod, VPPMod.FLAT_MIN = hydro_cls, aero_cls, flat_min
    try:
        yield
    finally:
        VPPMod.HydroMod, VPPMod.AeroMod, VPPMod.FLAT_MIN = saved


# ----------------------------------------------------------------------------------------------------
# Building the boat.

def load_inputs(path: Path, hull_form: Path | None):
    data = json.loads(Path(path).read_text())
    inputs = dict(data["inputs"])
    if hull_form is not None:
        form = json.loads(Path(hull_form).read_text())
        missing = [k for k in HULL_FORM_KEYS if k not in form]
        if missing:
            raise SystemExit(f"--hull-form {hull_form}: missing keys {missing}")
        for key, name in HULL_FORM_KEYS.items():
            value = float(form[key])
            if not (math.isfinite(value) and value > 0):
                raise SystemExit(f"--hull-form {hull_form}: {key} must be positive, got {value}")
            inputs[name] = value
    return data, inputs


def read_righting_arm(path: Path, series: str = "mesh") -> dict[str, list[float]]:
    """The righting-arm curve of ``path`` (a csv with columns series, heel_deg, gz_m, as
    ``benchmarks/studies/righting_arm.py`` writes it: the rows of ``series``) in the package's GZ form, 0-60 deg."""
    heel, gz = [], []
    with open(path, newline="") as table:
        for row in csv.DictReader(table):
            if row.get("series", series) == series and float(row["heel_deg"]) <= 60.0:
                heel.append(float(row["heel_deg"]))
                gz.append(float(row["gz_m"]))
    if len(heel) < 3 or heel[0] != 0.0 or any(b <= a for a, b in zip(heel, heel[1:])):
        raise SystemExit(f"--righting-arm {path}: need rows of series {series!r} with heel_deg rising from 0")
    if not all(math.isfinite(g) for g in gz):
        raise SystemExit(f"--righting-arm {path}: gz_m must be finite")
    return {"Heel": heel, "GZ": gz}


def build_yacht(data, inputs, yacht_cls, righting_arm: dict | None = None):
    from python_vpp import Jib, Keel, Main, Rudder

    keel = Keel(Cu=inputs["keel"]["Cu"], Cl=inputs["keel"]["Cl"], Span=inputs["keel"]["Span"],
                Tc_ratio=inputs["keel"]["Tc_ratio"])
    keel.vol = inputs["keel"]["vol"]  # the physical fin + ballast volume, not the package's estimate
    rudder = Rudder(Cu=inputs["rudder"]["Cu"], Cl=inputs["rudder"]["Cl"], Span=inputs["rudder"]["Span"],
                    Tc_ratio=inputs["rudder"]["Tc_ratio"])
    main = Main("Main", P=inputs["main"]["P"], E=inputs["main"]["E"], Roach=inputs["main"]["Roach"],
                BAD=inputs["main"]["BAD"])
    jib = Jib("none", I=inputs["dummy_jib"]["I"], J=inputs["dummy_jib"]["J"], LPG=inputs["dummy_jib"]["LPG"],
              HBI=inputs["HBI"])
    gz = righting_arm if righting_arm is not None else {"Heel": list(data["GZ"]["heel"]),
                                                         "GZ": list(data["GZ"]["gz_m"])}
    return yacht_cls(Name="E-Boat", Lwl=inputs["Lwl"], Vol=inputs["Vol"], Bwl=inputs["Bwl"], Tc=inputs["Tc"],
                     WSA=inputs["WSA"], Tmax=inputs["Tmax"], Amax=inputs["Amax"], Mass=inputs["Mass"],
                     Loa=inputs["Loa"], Boa=inputs["Boa"], Ff=inputs["Ff"], Fa=inputs["Fa"],
                     App=[keel, rudder], Sails=[main, jib], GZ=gz, crew_weight=0.0)


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
            residuary = float(hydro._get_Rr())  # hull + keel, at the state update() just set
            out[k] = total - residuary, residuary, total
    finally:
        hydro._interp_Rr = saved
    return out


def run_polar(yacht, hydro_cls, aero_cls, flat_min, phi_max, tws_mps, twa_deg):
    """Boat speed [m/s], heel, leeway [deg], shape (len(tws), len(twa)); NaN where not converged."""
    from python_vpp import VPP
    from python_vpp.UtilsMod import KNOTS_TO_MPS

    with _patched_vpp(hydro_cls, aero_cls, flat_min):
        vpp = VPP(yacht)
        vpp.set_analysis(np.asarray(tws_mps, dtype=float) / KNOTS_TO_MPS, np.asarray(twa_deg, dtype=float),
                         phi_max=phi_max)
        vpp.run(method="sequential")
    store = vpp.store[:, :, 0, :]  # one sail set: main + dummy jib
    solved = store[..., 0] > 0
    speed = np.where(solved, store[..., 0] * KNOTS_TO_MPS, np.nan)
    heel = np.where(solved, store[..., 1], np.nan)
    leeway = np.where(solved, store[..., 2], np.nan)
    return speed, heel, leeway


def best_upwind(yacht, hydro_cls, aero_cls, flat_min, phi_max, speed, refine):
    """Best upwind VMG [m/s] and its angle per wind speed: from the 5 deg grid, then (refine) a 1 deg
    grid within 4 deg of the grid's best."""
    out = {}
    for i, tws in enumerate(TRUE_WIND_SPEEDS):
        vmg = speed[i] * np.cos(np.radians(TRUE_WIND_ANGLES))
        if np.all(np.isnan(vmg)):
            out[tws] = (math.nan, math.nan)
            continue
        j = int(np.nanargmax(vmg))
        best = (float(vmg[j]), float(TRUE_WIND_ANGLES[j]))
        if refine:
            twa = np.arange(max(TRUE_WIND_ANGLES[j] - 4, 20.0), TRUE_WIND_ANGLES[j] + 4 + 1e-9, 1.0)
            fine, _, _ = run_polar(yacht, hydro_cls, aero_cls, flat_min, phi_max, [tws], twa)
            fine_vmg = fine[0] * np.cos(np.radians(twa))
            if not np.all(np.isnan(fine_vmg)) and np.nanmax(fine_vmg) > best[0]:
                k = int(np.nanargmax(fine_vmg))
                best = (float(fine_vmg[k]), float(twa[k]))
        out[tws] = best
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


def write_figure(path: Path, speed, resistance, package_resistance):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig = plt.figure(figsize=(12, 5.5))
    ax = fig.add_subplot(1, 2, 1, projection="polar")
    ax.set_theta_zero_location("N")
    ax.set_theta_direction(-1)
    ax.set_thetamin(0)
    ax.set_thetamax(180)
    for i, tws in enumerate(TRUE_WIND_SPEEDS):
        ax.plot(np.radians(TRUE_WIND_ANGLES), speed[i], "-o", ms=3, label=f"TWS {tws:g} m/s")
    ax.set_title("E-Boat VPP (python-vpp, axes fixed): boat speed [m/s]", fontsize=10)
    ax.set_xlabel("true wind angle [deg]")
    ax.legend(loc="center right", bbox_to_anchor=(0.0, 0.5), fontsize=8)  # left of the half disc
    ax2 = fig.add_subplot(1, 2, 2)
    ax2.plot(RESISTANCE_SPEEDS, resistance[:, 2], "-", label="total, surfaces read as labelled (fixed)")
    ax2.plot(RESISTANCE_SPEEDS, package_resistance[:, 2], "--", label="total, package's swapped axes")
    ax2.plot(RESISTANCE_SPEEDS, resistance[:, 0], ":", label="friction (viscous)")
    ax2.plot(list(README_RESISTANCE), list(README_RESISTANCE.values()), "kx", label="README anchors")
    ax2.set_xlabel("boat speed [m/s]")
    ax2.set_ylabel("upright resistance, hull + keel + rudder [N]")
    ax2.set_title("Upright resistance (heel 0, leeway 0)", fontsize=10)
    ax2.grid(alpha=0.3)
    ax2.legend(fontsize=8)
    fig.tight_layout()
    save_figure(fig, path, dpi=120)


def _at(speed, i, twa):
    return float(speed[i, int(np.argmin(np.abs(TRUE_WIND_ANGLES - twa)))])


def print_summary(speed, vmg, package, resistance_at):
    f = lambda v: "  nan" if math.isnan(v) else f"{v:5.2f}"  # noqa: E731
    print("\nSummary: fixed = surfaces read as labelled; pkg = package's swapped axes; README = anchors")
    print(f"{'TWS m/s':>7} | {'best upwind VMG m/s (TWA)':^38} | {'beam reach 90 m/s':^21} |"
          f" {'broad reach 120 m/s':^21}")
    print(f"{'':>7} | {'fixed':^12} {'pkg':^12} {'README':^12} | {'fixed':>5} {'pkg':>5} {'README':>6}"
          f"    | {'fixed':>5} {'pkg':>5} {'README':>6}")
    for i, tws in enumerate(TRUE_WIND_SPEEDS):
        v, a = vmg[tws]
        pv, pa = package["vmg"][tws] if package else (math.nan, math.nan)
        ps = package["speed"] if package else np.full_like(speed, np.nan)
        rv, ra = README_VMG[tws]
        print(f"{tws:7g} | {f(v)} ({a:3.0f})  {f(pv)} ({pa:3.0f})  {rv:5.2f} ({ra:3d})  |"
              f" {f(_at(speed, i, 90))} {f(_at(ps, i, 90))} {README_BEAM[tws]:6.2f}    |"
              f" {f(_at(speed, i, 120))} {f(_at(ps, i, 120))} {README_BROAD[tws]:6.2f}")
    print("\nUpright resistance [N]: speed m/s | fixed | package axes | README")
    for v, (fixed, pkg) in resistance_at.items():
        print(f"  {v:5.2f} | {fixed:7.1f} | {pkg:7.1f} | {README_RESISTANCE[v]:6.1f}")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                     formatter_class=argparse.ArgumentDefaultsHelpFormatter)
    parser.add_argument("--inputs", type=Path, default=DEFAULT_INPUTS, help="the VPP inputs json")
    parser.add_argument("--hull-form", type=Path, default=None,
                        help="JSON of hull particulars replacing the inputs' (waterline_length, ...)")
    parser.add_argument("--righting-arm", type=Path, default=None,
                        help="csv of the righting arm replacing the inputs' GZ (series, heel_deg, gz_m: the "
                             "'mesh' rows of benchmarks/data/righting_arm.csv are the simulator's own boat)")
    parser.add_argument("--out", type=Path, default=DATA, help="folder of the csvs")
    parser.add_argument("--figure", type=Path, default=FIGURES / "vpp_reference.png")
    parser.add_argument("--flat-min", type=float, default=0.25, help="lowest sail flattening factor")
    parser.add_argument("--phi-max", type=float, default=35.0, help="heel cap [deg]")
    parser.add_argument("--wind-profile", action="store_true",
                        help="use the package's log wind profile (true wind at 10 m) instead of uniform wind")
    parser.add_argument("--no-refine", action="store_true", help="best VMG from the 5 deg grid only")
    parser.add_argument("--no-package-axes-polar", action="store_true",
                        help="skip the polar with the package's swapped axes (summary comparison only)")
    args = parser.parse_args(argv)

    try:
        import python_vpp
    except ImportError:
        raise SystemExit('python-vpp is not installed: pip install -e ".[vpp]"') from None
    fixed_hydro, uniform_aero, robot_yacht, package_hydro, package_aero, surfaces = _make_classes()
    aero_cls = package_aero if args.wind_profile else uniform_aero
    t0 = time.perf_counter()

    data, inputs = load_inputs(args.inputs, args.hull_form)
    righting_arm = read_righting_arm(args.righting_arm) if args.righting_arm is not None else None
    yacht = build_yacht(data, inputs, robot_yacht, righting_arm)
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        hydro = fixed_hydro(yacht)
    for w in caught:
        print(f"warning (HydroMod): {w.message}")
    cp = inputs["Vol"] / (inputs["Amax"] * inputs["Lwl"])
    cm = inputs["Amax"] / (inputs["Bwl"] * inputs["Tc"])
    print(f"python-vpp {python_vpp.__version__}; inputs {args.inputs}"
          + (f"; hull form {args.hull_form}" if args.hull_form else "")
          + (f"; righting arm {args.righting_arm}" if args.righting_arm else ""))
    print(f"Lwl {inputs['Lwl']:.3f} m, Bwl {inputs['Bwl']:.3f} m, Tc {inputs['Tc']:.3f} m, "
          f"Vol {inputs['Vol']:.4f} m3, WSA {inputs['WSA']:.3f} m2, Amax {inputs['Amax']:.4f} m2, "
          f"mass {inputs['Mass']:.1f} kg; LVR {yacht.lvr:.3f}, BTR {yacht.btr:.3f}, Cp {cp:.3f}, Cm {cm:.3f}")
    afloat = hydro.rho * (inputs["Vol"] + inputs["keel"]["vol"])  # the package's rudder "vol" is no volume
    if abs(afloat / inputs["Mass"] - 1) > 0.05:
        print(f"note: canoe body + keel volumes float {afloat:.1f} kg, not the mass {inputs['Mass']:.1f} kg "
              "(the package takes resistance per unit of the mass and does not check)")
    print(f"residuary surfaces: {surfaces} (read as labelled: rows LVR, columns BTR)")
    print(f"flat >= {args.flat_min}, heel <= {args.phi_max} deg, "
          f"{'log wind profile (10 m)' if args.wind_profile else 'uniform wind'}, no crew righting moment")

    # Resistance, both readings of the surfaces.
    resistance = upright_resistance(hydro, RESISTANCE_SPEEDS, hydro._interp_Rr)
    package_resistance = upright_resistance(hydro, RESISTANCE_SPEEDS, hydro.package_axes_interp_Rr)
    anchors = np.array(list(README_RESISTANCE))
    at_fixed = upright_resistance(hydro, anchors, hydro._interp_Rr)[:, 2]
    at_pkg = upright_resistance(hydro, anchors, hydro.package_axes_interp_Rr)[:, 2]
    resistance_at = {float(v): (a, b) for v, a, b in zip(anchors, at_fixed, at_pkg)}
    _atomic_write_csv(
        args.out / "vpp_reference_resistance.csv",
        ["speed_mps", "friction_n", "residuary_n", "total_n", "total_n_package_axes"],
        [[float(v), *map(float, r), float(p)] for v, r, p in
         zip(RESISTANCE_SPEEDS, resistance, package_resistance[:, 2])])

    # Polar with the fixed surfaces.
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        t1 = time.perf_counter()
        speed, heel, leeway = run_polar(yacht, fixed_hydro, aero_cls, args.flat_min, args.phi_max,
                                        TRUE_WIND_SPEEDS, TRUE_WIND_ANGLES)
        vmg = best_upwind(yacht, fixed_hydro, aero_cls, args.flat_min, args.phi_max, speed,
                          not args.no_refine)
        print(f"polar (fixed axes): {time.perf_counter() - t1:.1f} s")
        package = None
        if not args.no_package_axes_polar:
            t1 = time.perf_counter()
            p_speed, _, _ = run_polar(yacht, package_hydro, aero_cls, args.flat_min, args.phi_max,
                                      TRUE_WIND_SPEEDS, TRUE_WIND_ANGLES)
            p_vmg = best_upwind(yacht, package_hydro, aero_cls, args.flat_min, args.phi_max, p_speed,
                                not args.no_refine)
            package = {"speed": p_speed, "vmg": p_vmg}
            print(f"polar (package axes): {time.perf_counter() - t1:.1f} s")
    messages = {}
    for w in caught:
        key = f"{w.category.__name__}: {str(w.message).splitlines()[0][:100]}"
        messages[key] = messages.get(key, 0) + 1
    for key, n in messages.items():
        print(f"warning x{n}: {key}")

    rows = []
    for i, tws in enumerate(TRUE_WIND_SPEEDS):
        for j, twa in enumerate(TRUE_WIND_ANGLES):
            vb = float(speed[i, j])
            rows.append([float(tws), float(twa), vb, float(heel[i, j]), float(leeway[i, j]),
                         round(vb * math.cos(math.radians(twa)), 12)])  # exactly 0 at 90 deg
    _atomic_write_csv(args.out / "vpp_reference_polar.csv",
                      ["true_wind_speed_mps", "true_wind_angle_deg", "boat_speed_mps", "heel_deg",
                       "leeway_deg", "vmg_mps"], rows)
    write_figure(args.figure, speed, resistance, package_resistance)

    unsolved = [(tws, float(TRUE_WIND_ANGLES[j])) for i, tws in enumerate(TRUE_WIND_SPEEDS)
                for j in range(len(TRUE_WIND_ANGLES)) if math.isnan(speed[i, j])]
    print(f"no equilibrium (NaN) at {len(unsolved)} of {speed.size} points"
          + (f": {unsolved}" if unsolved else ""))
    print_summary(speed, vmg, package, resistance_at)
    print(f"\nwrote {args.out / 'vpp_reference_polar.csv'}, {args.out / 'vpp_reference_resistance.csv'}, "
          f"{args.figure}; {time.perf_counter() - t0:.1f} s in all")


if __name__ == "__main__":
    main()
