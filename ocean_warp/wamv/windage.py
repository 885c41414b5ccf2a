"""The wind on the WAM-V as a force model: VRX's three lumped coefficients (``kernels.lumped_windage``)."""

from __future__ import annotations

import warp as wp

from ..kernels.lumped_windage import lumped_windage

__all__ = ["Windage"]


class Windage:
    """Adds, every substep, the wind's surge and sway force and yaw moment on each boat from ``coefficients``
    (c_x, c_y, c_z) and the wind model's velocity at each boat (gusts included)."""

    def __init__(self, coefficients, wind, count: int, *, device):
        self.coefficients = wp.vec3(*(float(c) for c in coefficients))
        self.wind = wind
        self.count = int(count)
        self.device = wp.get_device(device)

    def substep(self, simulator) -> None:
        fleet = simulator.fleet
        wp.launch(lumped_windage, dim=self.count, device=self.device,
                  inputs=[self.coefficients, self.wind.state.velocity, fleet.state.orientation, fleet.state.velocity],
                  outputs=[fleet.forces.model_wrench])
