"""The WAM-V's two stern thrusters as a force model (``kernels.thrusters``: mapping, azimuth, out-of-water cut)."""

from __future__ import annotations

import warp as wp

from ..kernels.thrusters import ThrusterParameters, reset_thrusters, thruster_actions, thrusters
from .config import ThrusterLayout, WamvConfig

__all__ = ["Thrusters"]


class Thrusters:
    """Every boat's left and right thruster (columns 0 and 1): what is commanded (``thrust_command`` in [-1, 1],
    ``angle_command`` [rad]) and what they do (``thrust`` [N], ``thruster_angle`` [rad], positive turning the boat
    to port), (N, 2) float32 arrays each, and the force model that adds their wrench every substep."""

    def __init__(self, config: WamvConfig, count: int, *, device):
        self.device = wp.get_device(device)
        self.count = int(count)
        parameters = ThrusterParameters()
        parameters.pivot_left = wp.vec3(*config.engine_pivots[0])
        parameters.pivot_right = wp.vec3(*config.engine_pivots[1])
        parameters.propeller_offset = wp.vec3(*config.propeller_offset)
        parameters.max_forward = config.max_forward_thrust
        parameters.max_reverse = config.max_reverse_thrust
        azimuth = config.thrusters is ThrusterLayout.AZIMUTH
        parameters.angle_limit = config.max_thruster_angle if azimuth else 0.0
        self.parameters = parameters
        zeros = lambda: wp.zeros((self.count, 2), dtype=float, device=self.device)  # noqa: E731
        self.thrust_command, self.angle_command = zeros(), zeros()
        self.thrust, self.thruster_angle = zeros(), zeros()
        self._every_boat = wp.ones(self.count, dtype=wp.int32, device=self.device)
        self._every_column = wp.ones(4, dtype=wp.int32, device=self.device)

    def substep(self, simulator) -> None:
        fleet = simulator.fleet
        wp.launch(thrusters, dim=self.count, device=self.device,
                  inputs=[self.parameters, simulator.ocean.surface, fleet.state.position, fleet.state.orientation,
                          self.thrust_command, self.angle_command],
                  outputs=[self.thrust, self.thruster_angle, fleet.forces.model_wrench, fleet.state.status])

    def reset_masked(self, mask: wp.array) -> None:
        """Boats whose ``mask`` is non-zero: commands, thrust and angles to zero (launches only, graph-safe)."""
        wp.launch(reset_thrusters, dim=self.count, device=self.device, inputs=[mask],
                  outputs=[self.thrust_command, self.angle_command, self.thrust, self.thruster_angle])

    def launch_actions(self, actions: wp.array, enabled: wp.array | None = None) -> None:
        """Actions (N, A) float32 in [-1, 1] -> commands: columns 0, 1 the thrust commands; with azimuth thrusters
        columns 2, 3 times the angle limit; ``enabled`` (A,) int32: a zero switches its column off (commands 0;
        None: all on)."""
        wp.launch(thruster_actions, dim=self.count, device=self.device,
                  inputs=[actions, self._every_column if enabled is None else enabled, self.parameters.angle_limit],
                  outputs=[self.thrust_command, self.angle_command])
