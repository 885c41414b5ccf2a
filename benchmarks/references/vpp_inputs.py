"""The inputs of the E-Boat's VPP (``vpp_reference``): one boat and sail plan, read from either json format.

- The real boat's (``shared/eboat/vpp_inputs_real.json``): ``cases`` (R, R1, R2: the full and reefed mains),
  each with its hull particulars, mass, keel fin, bulb, rudder, main, HBI, dummy jib and GZ curve.
- The old stiffer parametric boat's (``shared/eboat/vpp_inputs.json``): one ``inputs`` block and a top-level
  GZ curve, no bulb.

``load_boat`` checks every number is finite, that the case's main area and centre of effort agree with the
package's formulas of P, E, Roach, BAD and HBI, and that the robot carries no crew, raising a one-line
ValueError naming the key otherwise. ``read_righting_arm`` reads a GZ curve the simulator measured
(``benchmarks/studies/righting_arm.py``'s csv). Lengths [m], areas [m2], volumes [m3], mass [kg], heel [deg].
No python-vpp needed here.
"""

from __future__ import annotations

import csv
import dataclasses
import json
import math
from pathlib import Path

from benchmarks import REPO

DEFAULT_INPUTS = REPO.parent / "shared/eboat/vpp_inputs_real.json"
"""The real boat's VPP inputs, one case per sail plan."""
HULL_KEYS = ("Lwl", "Loa", "Bwl", "Boa", "Tc", "Vol", "WSA", "Amax", "Tmax", "Ff", "Fa")
HULL_FORM_KEYS = {  # --hull-form key -> Yacht argument
    "waterline_length": "Lwl", "waterline_beam": "Bwl", "canoe_draft": "Tc",
    "displaced_volume": "Vol", "wetted_area": "WSA", "max_section_area": "Amax",
}
CASE_CE_TOLERANCE = 0.01  # m, the json's ce_above_wl against the package's centre of effort of P, Roach, BAD
CASE_AREA_TOLERANCE = 0.01  # relative, the json's main area against 0.5 P E (1 + Roach)


@dataclasses.dataclass(frozen=True)
class VppBoat:
    """One boat and sail plan as the VPP takes it (lengths [m], areas [m2], volumes [m3], mass [kg])."""

    case: str | None
    """The case's name in a json with cases (R, R1, R2); None for the old single-boat format."""
    hull: dict
    """Yacht particulars: HULL_KEYS."""
    mass: float
    """Displacement, hull and appendages [kg]."""
    keel: dict
    """Fin: Cu, Cl (root and tip chord), Span, Tc_ratio, vol (its own volume, for its residuary)."""
    bulb: dict | None
    """Chord, area (wetted), vol, CG (depth, negative below the waterline), Tc_ratio; None: no bulb."""
    rudder: dict
    """Cu, Cl, Span, Tc_ratio (vol, where given, is information: the package gives a rudder no residuary)."""
    main: dict
    """P (luff), E (foot), Roach, BAD (boom above the mast's base)."""
    hbi: float
    """Height of the mast's base (the package's base of I) above the waterline [m]."""
    dummy_jib: dict
    """I, J, LPG of the negligible jib the package's aero model needs."""
    gz: dict
    """Righting arm, {"Heel": [deg], "GZ": [m]}."""

    @property
    def main_area(self) -> float:
        """The package's main area 0.5 P E (1 + Roach) [m2]."""
        return 0.5 * self.main["P"] * self.main["E"] * (1.0 + self.main["Roach"])

    @property
    def ce_above_waterline(self) -> float:
        """The package's geometric centre of effort of the main above the waterline [m]."""
        return self.main["P"] / 3.0 * (1.0 + self.main["Roach"]) + self.main["BAD"] + self.hbi

    @property
    def label(self) -> str:
        return self.case if self.case is not None else "inputs"


def _numbers(block: dict, keys, where: str) -> dict:
    """The keys of ``block`` as finite floats; ValueError naming ``where`` and the key otherwise."""
    missing = [k for k in keys if k not in block]
    if missing:
        raise ValueError(f"{where}: missing keys {missing}")
    out = {}
    for key in keys:
        value = block[key]
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
            raise ValueError(f"{where}.{key}: must be a finite number, got {value!r}")
        out[key] = float(value)
    return out


def _gz(heel, gz_m, where: str) -> dict:
    heel, gz_m = [float(v) for v in heel], [float(v) for v in gz_m]
    if len(heel) != len(gz_m) or len(heel) < 3 or heel[0] != 0.0 or any(b <= a for a, b in zip(heel, heel[1:])):
        raise ValueError(f"{where}: need at least 3 (heel, GZ) pairs with heel rising from 0 deg")
    if not all(math.isfinite(g) for g in gz_m):
        raise ValueError(f"{where}: GZ must be finite")
    return {"Heel": heel, "GZ": gz_m}


def input_cases(path: Path) -> list[str] | None:
    """The case names of a VPP inputs json, None for the old single-boat format."""
    data = json.loads(Path(path).read_text())
    return list(data["cases"]) if "cases" in data else None


def load_boat(path: Path, case: str | None = None, hull_form: Path | None = None) -> VppBoat:
    """The boat of ``case`` in the json at ``path`` (a ``cases`` json, default case R), or of its
    ``inputs`` block (the old format; ``case`` must be None), with ``hull_form``'s particulars if given."""
    data = json.loads(Path(path).read_text())
    if "cases" in data:
        case = "R" if case is None else case
        if case not in data["cases"]:
            raise ValueError(f"case {case!r} is not in {path}; it has {list(data['cases'])}")
        c, where = data["cases"][case], f"{path}: cases.{case}"
        crew = float(c.get("crew", 0.0))
        if crew != 0.0:
            raise ValueError(f"{where}.crew: the robot carries no crew, got {crew}")
        main = _numbers(c["main"], ("P", "E", "Roach", "BAD", "area", "ce_above_wl"), f"{where}.main")
        boat = VppBoat(
            case=case, hull=_numbers(c["hull"], HULL_KEYS, f"{where}.hull"),
            mass=_numbers(c, ("mass",), where)["mass"],
            keel=_numbers(c["keel"], ("Cu", "Cl", "Span", "Tc_ratio", "vol"), f"{where}.keel"),
            bulb=(_numbers(c["bulb"], ("Chord", "area", "vol", "CG", "Tc_ratio"), f"{where}.bulb")
                  if c.get("bulb") is not None else None),
            rudder=_numbers(c["rudder"], ("Cu", "Cl", "Span", "Tc_ratio"), f"{where}.rudder"),
            main={k: main[k] for k in ("P", "E", "Roach", "BAD")},
            hbi=_numbers(c, ("HBI",), where)["HBI"],
            dummy_jib=_numbers(c["dummy_jib"], ("I", "J", "LPG"), f"{where}.dummy_jib"),
            gz=_gz(c["GZ"]["heel"], c["GZ"]["gz_m"], f"{where}.GZ"))
        if abs(boat.main_area / main["area"] - 1.0) > CASE_AREA_TOLERANCE:
            raise ValueError(f"{where}.main: area {main['area']:.4g} m2 is not 0.5 P E (1 + Roach) = "
                             f"{boat.main_area:.4g} m2")
        if abs(boat.ce_above_waterline - main["ce_above_wl"]) > CASE_CE_TOLERANCE:
            raise ValueError(f"{where}.main: ce_above_wl {main['ce_above_wl']:.4g} m is not P/3 (1 + Roach) + BAD"
                             f" + HBI = {boat.ce_above_waterline:.4g} m")
    elif "inputs" in data:
        if case is not None:
            raise ValueError(f"{path} has no cases (the old single-boat format): leave --case out")
        i, where = data["inputs"], f"{path}: inputs"
        boat = VppBoat(
            case=None, hull=_numbers(i, HULL_KEYS, where), mass=_numbers(i, ("Mass",), where)["Mass"],
            keel=_numbers(i["keel"], ("Cu", "Cl", "Span", "Tc_ratio", "vol"), f"{where}.keel"), bulb=None,
            rudder=_numbers(i["rudder"], ("Cu", "Cl", "Span", "Tc_ratio"), f"{where}.rudder"),
            main=_numbers(i["main"], ("P", "E", "Roach", "BAD"), f"{where}.main"),
            hbi=_numbers(i, ("HBI",), where)["HBI"],
            dummy_jib=_numbers(i["dummy_jib"], ("I", "J", "LPG"), f"{where}.dummy_jib"),
            gz=_gz(data["GZ"]["heel"], data["GZ"]["gz_m"], f"{path}: GZ"))
    else:
        raise ValueError(f"{path}: neither 'cases' (the real boat's format) nor 'inputs' (the old one)")
    if hull_form is not None:
        form = json.loads(Path(hull_form).read_text())
        values = _numbers(form, HULL_FORM_KEYS, f"--hull-form {hull_form}")
        bad = [k for k, v in values.items() if v <= 0]
        if bad:
            raise ValueError(f"--hull-form {hull_form}: {bad[0]} must be positive, got {values[bad[0]]}")
        boat = dataclasses.replace(boat, hull={**boat.hull, **{HULL_FORM_KEYS[k]: v for k, v in values.items()}})
    return boat


def read_righting_arm(path: Path, series: str = "mesh") -> dict[str, list[float]]:
    """The righting-arm curve of ``path`` (a csv with columns series, heel_deg, gz_m, as
    ``benchmarks/studies/righting_arm.py`` writes it: the rows of ``series``; a csv without a series
    column is one curve) in the package's GZ form {"Heel": [deg], "GZ": [m]}."""
    heel, gz = [], []
    with open(path, newline="") as table:
        for row in csv.DictReader(table):
            if row.get("series", series) == series:
                heel.append(float(row["heel_deg"]))
                gz.append(float(row["gz_m"]))
    return _gz(heel, gz, f"--righting-arm {path} (series {series!r})")
