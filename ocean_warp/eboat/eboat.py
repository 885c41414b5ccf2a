"""The E-Boat preset: hull, mass properties, rig, foil tables and hydrodynamics from the data sheet."""

from __future__ import annotations

import dataclasses
import enum
import importlib.resources

import numpy as np
import warp as wp

from ..boat_type import BoatType
from ..hull import Hull
from ..hydrodynamics_config import HydrodynamicsConfig
from ..seakeeping.database import HydroDatabase
from ..seakeeping.eboat_database import eboat_hydro_database
from ..kernels.appendage_buoyancy import AppendageBuoyancy
from ..kernels.foils import FoilTables
from ..kernels.point_buoyancy import PointBuoyancy
from ..kernels.sailing_rig import RigParameters
from ..hull_form import HullForm, Topsides, floating_waterline, measure_hull_form, measure_topsides
from ..resistance import DEFAULT_FORM_FACTOR, ResiduaryResistance
from ..sail import Mainsail
from ..stability import Appendages
from ..validation import require_choice
from ..water_config import WaterConfig
from .geometry import PROCEDURAL_MAST_LENGTH, Ballast, EBoatGeometry, HullKind, eboat_geometry, eboat_lifting_surfaces
from .hull_shape import MIN_TRIANGLE_BUDGET, HullShape, eboat_hull, resolution_for_budget
from .mass_properties import MassProperties, eboat_mass_properties
from .offsets_hull import DEFAULT_SECTION_POINTS, DEFAULT_STATIONS, offsets_hull
from .sheet import ACTUATORS, BOOM_HEIGHT, ENVIRONMENT, FOILS, VRX, Version

__all__ = ["Profile", "Hydrostatics", "HullKind", "Ballast", "EBoatConfig", "EBoat", "load_foil_table",
           "eboat_hydrodynamics", "eboat_hull_mesh", "eboat_lifting_surfaces"]

MAST_LENGTH = PROCEDURAL_MAST_LENGTH
"""Sheet, mast row [m]: the procedural boat's mast (the real one's: ``EBoat.geometry.mast_length``)."""
SEA_WATER_DENSITY = 1025.0
"""[kg/m^3]: the water of the hull's form at rest (``EBoat.hull_form``)."""
APPENDAGE_FADE_HEIGHT = 0.5
"""The appendages' buoyancy fades in as their centroid sinks through this band about the surface [m]
(assumed; about the keel's and rudder's depth, so that a capsized or airborne boat loses it)."""
WINDAGE_AREA = 0.5
"""Seed profile: drag area C_D A of the mast, rigging and topsides [m^2], any wind direction (assumed, not
on the sheet): the 3.55 x 0.1 m mast as a cylinder (C_D about 1.2, 0.43 m^2) and a little of the hull
above water. The original twin had none; without it the seed's sail table points closer than 20 degrees
to the wind."""
WINDAGE_HEIGHT = 1.2
"""Seed profile: height of the windage's centre in the base frame [m] (assumed)."""
HULL_WINDAGE_DRAG = 0.816
"""Physics profile: C_D of the hull's topsides on their projected area (the ORC VPP's hull windage). The
mast's drag is in the ORC main's parasitic drag (``ocean_warp.sail``), so it is not added again."""


class Profile(str, enum.Enum):
    """Which models make the boat's forces (the design card's "named profiles")."""

    PHYSICS = "physics"
    """Per-triangle hydrostatics and Froude-Krylov pressure with cross-flow drag; forward resistance as
    ITTC-1957 friction with a form factor plus Delft-series residuary resistance
    (``ocean_warp.resistance``); keel and rudder as lifting surfaces (``ocean_warp.lifting_surface``); the
    sheet's sail coefficients; windage."""
    SEED = "seed"
    """The seed's Gazebo twin: four-point buoyancy with VRX damping and the sheet's foil tables for keel
    and rudder alike, to compare with the paper."""


class Hydrostatics(str, enum.Enum):
    """How the water holds the boat up."""

    MESH = "mesh"
    """Per-triangle pressure on the hull mesh, with drag and friction (ocean_warp's model)."""
    POINTS = "points"
    """The original twin's four-point buoyancy with VRX-style damping (to compare with Gazebo)."""


@dataclasses.dataclass(frozen=True)
class EBoatConfig:
    """Which E-Boat to build."""

    version: Version | str = Version.C
    """"V-A", "V-B" or "V-C" (default): the sheet's snapshots of the original model, where they differ."""
    profile: Profile | str = Profile.PHYSICS
    """"physics" (default) or "seed": the force models (see :class:`Profile`)."""
    hydrostatics: Hydrostatics | str | None = None
    """"mesh" or "points" (the original four-point buoyancy and VRX damping); None (default): the
    profile's, mesh for "physics" and points for "seed". Points with the physics profile keep its foils
    (a cheap hull for tests and quick training)."""
    original_tuning: bool = False
    """Apply V-C's tuning hacks (sheet: sail lift held above 100 deg, foil lift zero above 90 deg,
    rudder force x 0.3, keel minus 0.6 of the sail's side force, sail force x 0.1 outside 5-160 deg).
    They are not physics: off by default."""
    hull: HullKind | str = HullKind.REAL
    """"real" (default): the F-Boat as its CAD has it (hull lofted from the offsets table, links where the
    URDF's joint chain puts them, the real keel fin and bulb, rudder and sail; origin on the real waterline
    at rest); "procedural": the canoe body with the sheet's link table at assumed heights, the boat the
    shipped policies were trained on (see ``ocean_warp.eboat.geometry``)."""
    ballast: Ballast | str = Ballast.CAD
    """The real boat's keel: "cad" (default: the URDF's 40.04 kg spread through fin and bulb) or "lead_bulb"
    (an assumption, not a fact: a 44 kg lead bulb on a solid GRP fin, 10.8 kg heavier, its centre of gravity
    0.03-0.05 m below the waterline as the sheet estimates). Only with ``hull`` "real"."""
    seakeeping: bool = False
    """Seakeeping from potential flow for the real hull in the physics profile's mesh model: the shipped
    hydrodynamic database's infinite-frequency added mass, radiation memory and diffraction load
    (``ocean_warp.seakeeping``, ``ocean_warp.kernels.radiation``), with the drag terms that stood in for them
    removed, all of it in a frame that follows the heading but not the heel and trim
    (``kernels.seakeeping_frame``). Off by default for its cost (the step about 35 % more than without it
    before issue 33, against 15-22 % without it); against capytaine its RAOs hold within 17 % (heave, pitch) and
    20 % (roll) from 0.9 s, and under sail it passes the same polar and tacking checks (``benchmarks/RESULTS.md``,
    issue 33)."""
    hull_shape: HullShape = dataclasses.field(default_factory=HullShape)
    """Dimensions of the procedural canoe body (``hull`` "procedural" only)."""
    hull_triangles: int | None = None
    """Triangle budget of the physics hull (at least 40), for either hull: the same shape meshed with fewer or
    more stations and section points (``hull_shape.resolution_for_budget``: at most the budget, the stations
    about 44 / 12 of the section points), for speed over detail; None (default): 44 stations of 12 points,
    2 024 triangles (the procedural hull: ``hull_shape`` as it is). With a budget, ``hull_shape`` must keep
    the default resolution, which the budget replaces. ``benchmarks/studies/hull_fidelity.py`` measures what a
    budget costs."""
    reef_areas: tuple[float, ...] = (2.0, 1.15)
    """Sail areas of the reef levels after the full sail [m^2], each positive, below the full sail's (the sheet's
    3.188 m^2) and below the one before: level k > 0 sails the full sail scaled by s_k = sqrt(area_k / 3.188)
    about its tack (``kernels.sailing_rig``). The default, about 2.0 and 1.15 m^2 (63 % and 36 % of the area,
    s = 0.79 and 0.60), are the model-yacht style change-downs of the sheet's VPP (issue 34); () gives the full
    sail alone."""

    def __post_init__(self):
        object.__setattr__(self, "version", require_choice("EBoatConfig", "version", self.version, Version))
        object.__setattr__(self, "profile", require_choice("EBoatConfig", "profile", self.profile, Profile))
        if self.hydrostatics is None:
            default = Hydrostatics.MESH if self.profile is Profile.PHYSICS else Hydrostatics.POINTS
            object.__setattr__(self, "hydrostatics", default)
        object.__setattr__(self, "hydrostatics", require_choice("EBoatConfig", "hydrostatics", self.hydrostatics,
                                                                Hydrostatics))
        if not isinstance(self.seakeeping, bool):
            raise ValueError(f"EBoatConfig.seakeeping must be True or False, got {self.seakeeping!r}")
        if not isinstance(self.original_tuning, bool):
            raise ValueError(f"EBoatConfig.original_tuning must be True or False, got {self.original_tuning!r}")
        object.__setattr__(self, "hull", require_choice("EBoatConfig", "hull", self.hull, HullKind))
        object.__setattr__(self, "ballast", require_choice("EBoatConfig", "ballast", self.ballast, Ballast))
        if not isinstance(self.hull_shape, HullShape):
            raise ValueError(f"EBoatConfig.hull_shape must be a HullShape, got {self.hull_shape!r}")
        if self.hull is HullKind.REAL:
            if self.hull_shape != HullShape():
                raise ValueError("EBoatConfig.hull_shape shapes the procedural hull; with hull 'real' leave it at "
                                 "its default (or choose hull='procedural')")
        elif self.ballast is not Ballast.CAD:
            raise ValueError(f"EBoatConfig.ballast {self.ballast.value!r} changes the real boat's keel; the "
                             "procedural hull has only the sheet's link table ('cad')")
        if self.seakeeping and (self.hull is not HullKind.REAL or self.profile is not Profile.PHYSICS
                                or self.hydrostatics is not Hydrostatics.MESH):
            raise ValueError("EBoatConfig.seakeeping needs the real hull in the physics profile's mesh model (its "
                             "hydrodynamic database is the real hull's)")
        self._check_hull_triangles()
        self._check_reef_areas()

    def _check_reef_areas(self) -> None:
        areas = self.reef_areas
        try:
            values = tuple(float(a) for a in areas)
        except (TypeError, ValueError):
            raise ValueError(f"EBoatConfig.reef_areas must be a sequence of areas [m^2], got {areas!r}") from None
        full = FOILS[self.version].sail_area
        if not all(np.isfinite(values)) or any(a <= 0.0 for a in values) or any(a >= full for a in values):
            raise ValueError(f"EBoatConfig.reef_areas must be finite areas in (0, {full}) m^2, below the full sail's "
                             f"{full} m^2, got {areas!r}")
        if any(b >= a for a, b in zip(values, values[1:])):
            raise ValueError(f"EBoatConfig.reef_areas must decrease from level to level, got {areas!r}")
        object.__setattr__(self, "reef_areas", values)

    @property
    def sail_areas(self) -> tuple[float, ...]:
        """Sail area of every reef level [m^2]: the full sail's (level 0), then ``reef_areas``."""
        return (FOILS[self.version].sail_area,) + self.reef_areas

    @property
    def reef_levels(self) -> int:
        """Number of reef levels, the full sail included."""
        return 1 + len(self.reef_areas)

    @property
    def reef_scales(self) -> tuple[float, ...]:
        """Linear factor s of every reef level on the full sail's dimensions: 1, then sqrt(area / full area)."""
        full = FOILS[self.version].sail_area
        return (1.0,) + tuple(float(np.sqrt(area / full)) for area in self.reef_areas)

    def _check_hull_triangles(self) -> None:
        budget = self.hull_triangles
        if budget is None:
            return
        if isinstance(budget, bool) or not isinstance(budget, (int, np.integer)) or budget < MIN_TRIANGLE_BUDGET:
            raise ValueError(f"EBoatConfig.hull_triangles must be None or an integer >= {MIN_TRIANGLE_BUDGET}, "
                             f"got {budget!r}")
        default = HullShape()
        if (self.hull_shape.stations, self.hull_shape.section_points) != (default.stations, default.section_points):
            raise ValueError(f"EBoatConfig.hull_triangles ({budget}) chooses the hull's stations and section_points; "
                             f"leave hull_shape's at {default.stations} and {default.section_points} (got "
                             f"{self.hull_shape.stations} and {self.hull_shape.section_points}) or hull_triangles None")

    @property
    def meshed_hull_shape(self) -> HullShape:
        """``hull_shape`` at the resolution the procedural hull is built with (``hull_triangles``'s, if set)."""
        if self.hull_triangles is None:
            return self.hull_shape
        return self.hull_shape.with_triangle_budget(int(self.hull_triangles))

    @property
    def uses_hydro_database(self) -> bool:
        """Whether this boat's hull sails with its hydrodynamic database: ``seakeeping`` on, for the real hull,
        meshed, in the physics profile."""
        return (self.seakeeping and self.hull is HullKind.REAL and self.profile is Profile.PHYSICS
                and self.hydrostatics is Hydrostatics.MESH)

    @property
    def hull_resolution(self) -> tuple[int, int]:
        """(stations, section_points) of the physics hull: ``hull_triangles``'s, else the default (44, 12; the
        procedural hull: ``hull_shape``'s); its triangles number stations x (4 section_points - 2)."""
        if self.hull is HullKind.PROCEDURAL:
            shape = self.meshed_hull_shape
            return shape.stations, shape.section_points
        if self.hull_triangles is None:
            return DEFAULT_STATIONS, DEFAULT_SECTION_POINTS
        return resolution_for_budget(int(self.hull_triangles))


def eboat_hull_mesh(config: EBoatConfig, detail: int = 1) -> Hull:
    """The hull mesh of ``config`` in its body frame, lofted with ``detail`` times as many stations and section
    points as the physics hull (1: the physics hull itself)."""
    stations, section_points = config.hull_resolution
    if config.hull is HullKind.PROCEDURAL:
        return eboat_hull(dataclasses.replace(config.meshed_hull_shape, stations=stations * detail,
                                              section_points=section_points * detail))
    return offsets_hull(stations * detail, section_points * detail)


def load_foil_table() -> np.ndarray:
    """(181, 5) the sheet's foil_coefficients.csv: alpha [deg], sail C_L, sail C_D, foil C_L, foil C_D."""
    with importlib.resources.files("ocean_warp.eboat").joinpath("foil_coefficients.csv").open() as handle:
        table = np.loadtxt(handle, delimiter=",", skiprows=1)
    if table.shape != (181, 5) or not np.array_equal(table[:, 0], np.arange(181)):
        raise ValueError(f"foil_coefficients.csv must hold 181 rows of 0..180 deg and 4 coefficients, got {table.shape}")
    return table


def eboat_hydrodynamics(profile: Profile | str = Profile.PHYSICS, *, radiation: bool = False,
                        **overrides) -> HydrodynamicsConfig:
    """The per-triangle water model of the E-Boat's hull under ``profile`` (see below), with ``overrides``;
    ``radiation``: the hull has a hydrodynamic database, whose radiation damps it (the drag keeps what viscosity
    does only: :data:`VISCOUS_CROSS_FLOW`)."""
    profile = require_choice("eboat_hydrodynamics", "profile", profile, Profile)
    model = dict(EBOAT_HYDRODYNAMICS[profile])
    if radiation:
        model.update(VISCOUS_CROSS_FLOW)
    return HydrodynamicsConfig(**{**model, **overrides})


# Kerner's drag coefficients as the seed profile's mesh hull had them, fitted at one point: with the
# sheet's full thrust, 120.1 N, the boat reached 1.71 m/s, about its hull speed (2026-11-21). Applied to
# the whole flow they made a bluff body's ram pressure ahead, 5-8x a displacement hull's resistance
# below hull speed. The physics profile keeps them for the cross flow only (sway, heave, roll, pitch,
# yaw: the heave-period and RAO tests hold with them) and resists motion ahead with friction times
# (1 + k) and the Delft residuary resistance.
_KERNER_CROSS_FLOW = dict(pressure_drag_linear=80.0, pressure_drag_quadratic=400.0, suction_linear=40.0,
                          suction_quadratic=200.0)
# With radiation damping from potential flow the linear terms above, which stood in for it, go: what is left
# is the viscous cross-flow drag, quadratic in the cross-flow speed. 400 N/m^2 at 1 m/s on the faces the flow
# meets and 200 on those it leaves amount to C_D = (400 + 200) / (0.5 rho 1 m^2/s^2) = 1.17 on a section's
# projected area, a flat plate's normal drag (Hoerner, "Fluid-Dynamic Drag", 1965, ch. 3: 1.17 for a square
# plate) and within the range of ship sections' cross-flow drag coefficients (0.5-1.3 by bilge radius;
# Faltinsen, "Sea Loads on Ships and Offshore Structures", 1990, ch. 7): a flat-bottomed, hard-chined hull
# such as this one sits at the plate's end of that range.
VISCOUS_CROSS_FLOW = dict(pressure_drag_linear=0.0, suction_linear=0.0)
"""The changes to the physics profile's drag for a hull with a hydrodynamic database."""
EBOAT_HYDRODYNAMICS = {
    Profile.PHYSICS: dict(_KERNER_CROSS_FLOW, cross_flow_only=True, form_factor=DEFAULT_FORM_FACTOR),
    Profile.SEED: dict(_KERNER_CROSS_FLOW),
}


class EBoat:
    """Everything about the E-Boat that does not change while it sails: its :class:`BoatType` (hull
    mesh, composite mass properties, added mass, damping), its rig (sail, keel, rudder, propeller,
    actuators) and foil tables, and the water model it sails in."""

    def __init__(self, config: EBoatConfig | None = None):
        self.config = config if config is not None else EBoatConfig()
        version = self.config.version
        self.geometry: EBoatGeometry = eboat_geometry(self.config.hull, version, self.config.ballast)
        """Where the parts are (links, rig, keel and rudder, propeller, appendages), body frame."""
        self.mass_properties: MassProperties = eboat_mass_properties(version, self.geometry.links)
        self.hull = eboat_hull_mesh(self.config)
        vrx = VRX[version]
        self.seakeeping: HydroDatabase | None = self._hydro_database()
        """The hull's hydrodynamic database (radiation, infinite-frequency added mass), or None: the real hull
        in the physics profile has one (shipped: ``ocean_warp.seakeeping.eboat_hydro_database``), the procedural
        hull and the seed profile keep the constant VRX added mass and their drag terms."""
        if self.config.hydrostatics is Hydrostatics.POINTS:
            damping = dict(linear_damping=vrx.linear_damping, quadratic_damping=vrx.quadratic_damping,
                           astern_surge_factor=vrx.astern_surge_factor)
        else:
            # The mesh model damps surge, sway and heave itself; the sheet's roll and pitch terms stand in for
            # the appendages' and rig's damping that the mesh does not see. Yaw: the physics profile's keel,
            # rudder (lifting surfaces) and hull (cross flow) damp it, so the sheet's N_r is not added again.
            rotational = tuple(vrx.linear_damping[3:])
            if self.config.profile is Profile.PHYSICS:
                rotational = rotational[:2] + (0.0,)
            if self.seakeeping is not None:
                # Radiation damps roll and pitch now, and the keel's and rudder's cross flow and the hull's
                # viscous drag the rest: the sheet's linear terms, which stood in for them, go too.
                rotational = (0.0, 0.0, 0.0)
            damping = dict(linear_damping=(0.0, 0.0, 0.0) + rotational)
        mp = self.mass_properties
        waterline = floating_waterline(self.hull, self.hull_load(SEA_WATER_DENSITY))
        self.hull_form: HullForm = measure_hull_form(self.hull, waterline)
        """The canoe body's form below its waterline at rest, upright, in sea water (1025 kg/m^3)."""
        physics = self.config.profile is Profile.PHYSICS
        residuary = ResiduaryResistance.delft(self.hull_form) if physics else None
        added_mass = vrx.added_mass if self.seakeeping is None else None
        self.boat_type = BoatType(hull=self.hull, mass=mp.mass, center_of_mass=tuple(mp.center_of_mass),
                                  inertia=mp.inertia, added_mass=added_mass, seakeeping=self.seakeeping,
                                  name=f"eboat {version.value}", residuary=residuary, **damping)
        self.hydrodynamics = eboat_hydrodynamics(self.config.profile, radiation=self.seakeeping is not None)
        """The water model of this profile, in sea water (the simulator's config sets the density)."""
        self.foil_table = load_foil_table()
        self.masthead = self.geometry.masthead
        """Top of the mast in the body frame [m]: vane and anemometer."""
        self.rig_figures = FOILS[version]
        self.vrx = vrx
        self.keel, self.rudder = self.geometry.keel, self.geometry.rudder
        """The physics profile's keel and rudder (:class:`LiftingSurface`)."""
        deck = float(self.hull.vertices[:, 2].max())
        geometry = self.geometry
        self.mainsail = Mainsail(area=self.rig_figures.sail_area,
                                 luff=geometry.sail_head_height - geometry.sail_foot_height,
                                 boom_above_deck=geometry.sail_foot_height - deck)
        """The physics profile's main (:class:`Mainsail`): luff from its foot to its head, its foot above the
        deck's highest point."""
        self.topsides: Topsides = measure_topsides(self.hull, waterline)
        """The hull above its waterline at rest, as the wind sees it (the physics profile's windage)."""

    def _hydro_database(self) -> HydroDatabase | None:
        """The shipped database for the real hull in the physics profile's mesh model, else None. It was computed
        on the default mesh (and is checked against it); a triangle budget meshes the same lines coarser or finer,
        so it takes the same database."""
        config = self.config
        if not config.uses_hydro_database:
            return None
        return eboat_hydro_database(self.hull if config.hull_triangles is None else None)

    def hull_load(self, density: float) -> float:
        """Mass [kg] the hull mesh carries at rest in water of ``density`` [kg/m^3]: the boat's, less what
        the appendages outside the mesh (keel fin, bulb, rudder) displace."""
        return self.mass_properties.mass - density * self.geometry.appendage_volume

    @property
    def appendages(self) -> Appendages | None:
        """The keel fin, bulb and rudder outside the hull mesh as ``ocean_warp.stability`` floats them, as the
        mesh hydrostatics' ``kernels.appendage_buoyancy`` does (None: the procedural boat, which counts none)."""
        geometry = self.geometry
        if geometry.appendage_volume <= 0.0:
            return None
        return Appendages(geometry.appendage_volume, geometry.appendage_center, APPENDAGE_FADE_HEIGHT)

    @property
    def boom_inertia(self) -> float:
        """Boom and full sail about the mast [kg m^2]: the boom as a 1.8 m rod from the mast (sheet), the sail
        as a triangle on it (:attr:`sail_inertia`)."""
        boom = next(link for link in self.geometry.links if link.name == "boom").mass
        return boom * 1.8**2 / 3 + self.sail_inertia

    @property
    def sail_inertia(self) -> float:
        """The full sail's share of :attr:`boom_inertia` [kg m^2]: a triangle on the boom (foot 1.8 m, centroid
        0.6 m aft; assumed). A reef of linear factor s scales it by s^4 (mass s^2, arm s)."""
        sail = next(link for link in self.geometry.links if link.name == "sail").mass
        return sail * (0.6**2 + 1.8**2 / 18)

    @property
    def sail_foot_height(self) -> float:
        """Height of the sail's foot in the body frame [m], about which a reef scales the sail: the physics
        profile's is the real (or procedural) sail's foot; the seed profile's the sheet's assumed boom height
        (0.45 m above the base frame, which puts the sheet's 1.5 m centre of effort a third of the way up a
        triangle to the masthead)."""
        if self.config.profile is Profile.PHYSICS:
            return self.geometry.sail_foot_height
        return BOOM_HEIGHT + self.geometry.base_z

    @property
    def sail_center_height(self) -> float:
        """Height of the full sail's centre of effort in the body frame [m] (``RigParameters.sail_height``)."""
        if self.config.profile is Profile.PHYSICS:
            return self.geometry.sail_center_height
        return self.rig_figures.sail_center_height + self.geometry.base_z

    def rig_parameters(self, water_density: float, device="cpu") -> RigParameters:
        """The rig's device struct for water of ``water_density`` [kg/m^3] (keel and rudder), its table of reef
        scales on ``device``. The physics profile's foils act where the boat has them (the real boat's lift at
        each foil's quarter chord); the seed profile's where the sheet puts them (base frame)."""
        figures, act, geometry = self.rig_figures, ACTUATORS, self.geometry
        rig = RigParameters()
        # The sail swings with the boom about the gooseneck's vertical axis (the real boat's 0.049 m aft of the
        # mast's; the procedural boat's on it).
        rig.mast_step = wp.vec3(geometry.boom_pivot[0], geometry.boom_pivot[1], geometry.mast_step[2])
        rig.sail_arm = figures.sail_arm
        physics = self.config.profile is Profile.PHYSICS
        rig.sail_height = self.sail_center_height
        rig.sail_area = figures.sail_area
        rig.sail_foot_height = self.sail_foot_height
        rig.reef_scale = wp.array(np.array(self.config.reef_scales, dtype=np.float32), dtype=float, device=device)
        rig.sail_inertia = self.sail_inertia
        rig.keel_center = wp.vec3(*(geometry.keel_center if physics else geometry.from_base(figures.keel_center)))
        rig.keel_area = self.keel.area if physics else figures.keel_area
        rig.rudder_center = wp.vec3(*(geometry.rudder_center if physics
                                      else geometry.from_base(figures.rudder_center)))
        rig.rudder_area = self.rudder.area if physics else figures.rudder_area
        rig.propeller_position = wp.vec3(*geometry.propeller_position)
        rig.thrust_per_level = act["thrust_per_level"]
        rig.reverse_factor = act["reverse_factor"]
        rig.max_level = act["propeller_levels"]
        rig.rudder_limit = np.radians(act["rudder_limit_deg"])
        rig.rudder_rate = act["rudder_rate"]
        rig.sheet_limit_max = np.radians(act["sheet_limit_deg"])
        rig.sheet_rate = act["sheet_rate"]
        rig.boom_inertia = self.boom_inertia
        rig.boom_damping = figures.boom_damping
        rig.air_density = ENVIRONMENT["air_density"]
        rig.water_density = water_density
        if physics:
            rig.windage_area_ahead = HULL_WINDAGE_DRAG * self.topsides.area_ahead
            rig.windage_area_abeam = HULL_WINDAGE_DRAG * self.topsides.area_abeam
            rig.windage_center = wp.vec3(*self.topsides.center_abeam)
        else:
            rig.windage_area_ahead = rig.windage_area_abeam = WINDAGE_AREA
            rig.windage_center = wp.vec3(*geometry.from_base((geometry.mast_step[0], 0.0, WINDAGE_HEIGHT)))
        tuned = self.config.original_tuning
        rig.sail_lift_limit = np.radians(100.0 if tuned else 180.0)
        rig.foil_lift_limit = np.radians(90.0 if tuned else 180.0)
        rig.original_tuning = int(tuned)
        return rig

    def coefficient_tables(self) -> dict[str, np.ndarray]:
        """C_L and C_D at 0..180 deg, (181,) each, of the sail, keel and rudder under this profile: the sheet's
        tables (seed), or the ORC main and the fins as lifting surfaces (physics)."""
        table = self.foil_table
        tables = {"sail_lift": table[:, 1], "sail_drag": table[:, 2]}
        if self.config.profile is Profile.PHYSICS:
            tables["sail_lift"], tables["sail_drag"] = self.mainsail.tables()
            for name, surface in (("keel", self.keel), ("rudder", self.rudder)):
                tables[f"{name}_lift"], tables[f"{name}_drag"] = surface.tables()
        else:
            for name in ("keel", "rudder"):
                tables[f"{name}_lift"], tables[f"{name}_drag"] = table[:, 3], table[:, 4]
        return tables

    def foil_tables(self, device) -> FoilTables:
        tables = FoilTables()
        for name, values in self.coefficient_tables().items():
            setattr(tables, name, wp.array(np.asarray(values, dtype=np.float32), dtype=float, device=device))
        return tables

    def point_buoyancy(self, device, water: WaterConfig) -> PointBuoyancy:
        """The original twin's four buoyancy points (sheet: x = +-0.6, y = +-0.45 m, R 0.4 m, L 2.4 m; at the
        base frame's height, which the real boat's body frame puts 0.094 m below its origin)."""
        model = PointBuoyancy()
        points = np.array([self.geometry.from_base(point) for point in self.vrx.points], dtype=np.float32)
        model.points = wp.array(points, dtype=wp.vec3, device=device)
        model.radius = self.vrx.hull_radius
        model.slice_length = self.vrx.hull_length / 2.0
        model.density = water.density
        model.gravity = water.gravity
        return model

    def appendage_buoyancy(self, water: WaterConfig) -> AppendageBuoyancy | None:
        """The buoyancy of the appendages outside the hull mesh (keel fin, bulb, rudder) in ``water``, for the
        mesh hydrostatics (``kernels.appendage_buoyancy``); None where the geometry counts none (the procedural
        hull)."""
        appendages = self.appendages
        if appendages is None:
            return None
        model = AppendageBuoyancy()
        model.volume = appendages.volume
        model.center = wp.vec3(*appendages.center)
        model.fade_height = appendages.fade_height
        model.density = water.density
        model.gravity = water.gravity
        return model

    def rest_height(self, device="cpu", water: WaterConfig | None = None) -> float:
        """Height [m] of the body origin above still ``water`` (default sea water) when the boat floats
        upright at rest on its mesh (found by bisection on the vertical force of the hull pass, without drag,
        with the appendages' buoyancy)."""
        from ..fleet import Fleet
        from ..ocean import Ocean
        from ..ocean_config import OceanConfig
        from ..simulator import Simulator, SimulatorConfig

        fleet = Fleet(self.boat_type, 1, device=device)
        water = water if water is not None else WaterConfig()
        still = Ocean(OceanConfig(tile_size=64.0, resolution=16, significant_wave_height=0.0, water=water),
                      device=device)
        simulator = Simulator(still, fleet, SimulatorConfig(hydrodynamics=self.hydrodynamics.without_drag()))
        low, high = -0.5, 0.5
        weight = self.hull_load(water.density) * water.gravity
        for _ in range(40):
            middle = 0.5 * (low + high)
            fleet.reset(position=[0.0, 0.0, middle])
            simulator.compute_hull_wrenches()
            if fleet.forces.hydro_wrench.numpy()[0, 2] < weight:
                high = middle
            else:
                low = middle
        return 0.5 * (low + high)

    def waterline_length(self, waterline_z: float = 0.0) -> float:
        """Length [m] of the hull where the plane z = ``waterline_z`` (body frame) cuts it."""
        vertices = self.hull.vertices
        edges = self.hull.to_trimesh().edges_unique
        z0, z1 = vertices[edges[:, 0], 2] - waterline_z, vertices[edges[:, 1], 2] - waterline_z
        crossing = z0 * z1 < 0
        t = z0[crossing] / (z0[crossing] - z1[crossing])
        x = vertices[edges[crossing, 0], 0] + t * (vertices[edges[crossing, 1], 0] - vertices[edges[crossing, 0], 0])
        return float(np.ptp(x))

