"""What the WAM-V tests share: VRX's thrust curve written out independently, and small simulators."""

import numpy as np

from ocean_warp.sensors import SensorConfig
from ocean_warp.wamv import WamvConfig, WamvSimulator, WamvSimulatorConfig


def vrx_thrust(command):
    """VRX's usv_gazebo_thrust_plugin mapping (mappingType 1): a generalised logistic curve either side of 0.01,
    capped at 250 N ahead and 100 N astern; here 0 within +-0.01 (our dead band)."""
    c = np.clip(np.asarray(command, dtype=np.float64), -1.0, 1.0)

    def logistic(x, a, k, b, nu, shift, m):
        return a + (k - a) / (shift + np.exp(-b * (x - m))) ** (1.0 / nu)

    ahead = np.minimum(logistic(c, 0.01, 59.82, 5.0, 0.38, 0.56, 0.28), 250.0)
    astern = np.maximum(logistic(c, -199.13, -0.09, 8.84, 5.34, 0.99, -0.57), -100.0)
    return np.where(c > 0.01, ahead, np.where(c < -0.01, astern, 0.0))


def simulator(count, device, **boat):
    """``count`` WAM-Vs (the vrx profile unless ``boat`` says otherwise) in still water, exact sensors."""
    boat.setdefault("profile", "vrx")
    config = WamvSimulatorConfig(boat=WamvConfig(**boat), sensors=SensorConfig.noise_free())
    return WamvSimulator(config, count, device=device)


def run(sim, seconds):
    for _ in range(int(round(seconds / sim.config.dt))):
        sim.step()
    return sim.fleet.numpy()
