"""The E-Boat's speed polar: steady speed over true wind angles and speeds, the sheet trimmed for speed.

Every (true wind speed, true wind angle, sheet setting) is one boat of a single fleet, so the whole
polar is one batched simulation. Each boat starts at 1 m/s on its heading with its sheet already set
(sheeted hard in on a reach in strong wind it would capsize before easing), and a PID autopilot holds
the heading; after a settling time, its speed is averaged over the last window. For each wind speed
and angle the sheet setting with the best speed wins (a grid search), counting only boats that held
their heading (mean error under ``heading_tolerance``), stayed upright and made way: where none did,
the angle is in the no-go zone and its speed is NaN.
"""

from __future__ import annotations

import dataclasses
import math
import sys

import numpy as np
import warp as wp
from tqdm import tqdm

from ocean_warp.kernels.heading_hold import accumulate_course_keeping
from ..replay import ReplayedLaunches
from ..wind import WindConfig
from .heading_autopilot import HeadingAutopilot
from .eboat import EBoatConfig
from .eboat_simulator import EBoatSimulator
from .simulator_config import EBoatSimulatorConfig

__all__ = ["PolarResult", "speed_polar"]


@dataclasses.dataclass(frozen=True)
class PolarResult:
    wind_speeds: np.ndarray
    """(S,) true wind speeds [m/s]."""
    wind_angles: np.ndarray
    """(A,) true wind angles [rad]: 0 head to wind, pi dead downwind."""
    speed: np.ndarray
    """(S, A) best steady speed through the water [m/s]; NaN where the boat could not hold the angle."""
    sheet: np.ndarray
    """(S, A) sheet setting of the best speed [rad]."""
    heel: np.ndarray
    """(S, A) mean heel at the best speed [rad] (positive: to starboard)."""
    held: np.ndarray
    """(S, A, K) whether each sheet setting held its heading, upright and making way."""
    all_speeds: np.ndarray
    """(S, A, K) steady speed of every sheet setting [m/s]."""
    sheets: np.ndarray
    """(K,) the sheet settings tried [rad]."""


def speed_polar(*, wind_speeds=(4.0, 7.0, 10.0), wind_angles_deg=np.arange(0.0, 181.0, 15.0),
                sheets_deg=np.arange(0.0, 91.0, 15.0), settle_time: float = 60.0, average_time: float = 20.0,
                heading_tolerance_deg: float = 5.0, boat: EBoatConfig | None = None, dt: float = 0.05,
                device=None, progress: bool | None = False) -> PolarResult:
    """Sail the grid and return the polar (see the module docstring). ``progress``: a progress bar of the
    time steps on stderr (None: only where stderr is a terminal)."""
    speeds = np.asarray(wind_speeds, dtype=np.float64)
    angles = np.radians(np.asarray(wind_angles_deg, dtype=np.float64))
    sheets = np.radians(np.asarray(sheets_deg, dtype=np.float64))
    grid_speed, grid_angle, grid_sheet = (g.ravel() for g in np.meshgrid(speeds, angles, sheets, indexing="ij"))
    count = grid_speed.size
    # The wind comes from +x (blows towards -x); a boat with true wind angle a heads at yaw a.
    config = EBoatSimulatorConfig(boat=boat if boat is not None else EBoatConfig(),
                                  wind=WindConfig(speed=float(speeds[0]), direction=math.pi), dt=dt)
    sim = EBoatSimulator(config, count, device=device)
    sim.reset(position=np.column_stack([np.arange(count) * 30.0, np.zeros(count), np.zeros(count)]),
              heading=grid_angle, velocity=[1.0, 0, 0, 0, 0, 0], wind_speed=grid_speed, wind_direction=math.pi,
              sheet=grid_sheet)
    autopilot = HeadingAutopilot(sim)
    autopilot.set_target(grid_angle)
    steps = int(round((settle_time + average_time) / dt))
    averaging = int(round(average_time / dt))
    sums = wp.zeros(count, dtype=wp.vec3, device=sim.device)
    # Each a captured graph: uncaptured, a step's launches took ten times the GPU's time for the step.
    settle_step = ReplayedLaunches(lambda: _sail_step(sim, autopilot), sim.device)
    averaging_step = ReplayedLaunches(lambda: _sail_step(sim, autopilot, sums), sim.device)
    for step in tqdm(range(steps), desc="polar", unit="step", file=sys.stderr, dynamic_ncols=True,
                     disable=None if progress is None else not progress):
        (averaging_step if step >= steps - averaging else settle_step)()
    mean_speed, heading_error, heel = (sums.numpy().astype(np.float64) / averaging).T
    held = ((np.abs(heading_error) < math.radians(heading_tolerance_deg))
            & (sim.fleet.numpy()["status"] == 0) & (mean_speed > 0.05))
    shape = (len(speeds), len(angles), len(sheets))
    mean_speed, held, heel = mean_speed.reshape(shape), held.reshape(shape), heel.reshape(shape)
    candidate = np.where(held, mean_speed, -np.inf)
    best = np.argmax(candidate, axis=2)
    pick = lambda a: np.take_along_axis(a, best[..., None], axis=2)[..., 0]  # noqa: E731
    any_held = held.any(axis=2)
    return PolarResult(speeds, angles, np.where(any_held, pick(mean_speed), np.nan), np.where(any_held, sheets[best], np.nan),
                       np.where(any_held, pick(heel), np.nan), held, mean_speed, sheets)


def _sail_step(sim: EBoatSimulator, autopilot: HeadingAutopilot, sums: wp.array | None = None) -> None:
    """Launches of one step: steer, advance, and add the boats' course keeping to ``sums`` if given."""
    autopilot.steer()
    sim.launch_step()
    if sums is not None:
        wp.launch(accumulate_course_keeping, dim=sim.count, device=sim.device,
                  inputs=[autopilot.target, sim.state.orientation, sim.state.velocity], outputs=[sums])
