"""A small 3-DOF WAM-V for the classical controllers' tests, independent of the simulator: numpy, a batch of
boats in calm water, and a fake env around it that exposes what a ``Controller`` reads.

Body frame FLU (x bow, y port), yaw counter-clockwise. Fossen's manoeuvring model
M nu' + C(nu) nu + D(nu) nu = tau + tau_disturbance, M = diag(180 + 20, 180 + 100, 446 + 200) (VRX's rigid body
and an added mass of ours), VRX's linear damping (100, 100, 800) and quadratic (150, 100, 800)
(``wamv_gazebo_dynamics_plugin.xacro``). Two thrusters at x = -2.37 m, y = +-1.03 m; a thrust action a
gives 250 a N forward (a > 0) or 100 a N astern (a < 0); an angle action turns the thrust by a x the azimuth
limit toward port."""

from types import SimpleNamespace

import numpy as np
import torch

MASS = np.array([200.0, 280.0, 646.0])
LINEAR_DAMPING = np.array([100.0, 100.0, 800.0])
QUADRATIC_DAMPING = np.array([150.0, 100.0, 800.0])
THRUSTER_X, THRUSTER_Y = -2.37, 1.03
FORWARD, REVERSE = 250.0, 100.0


class Plant:
    """N boats' pose (x, y, yaw) and body velocity (u, v, r); ``disturbance`` (N, 2) a world-frame force [N]."""

    def __init__(self, pose, azimuth_limit=np.pi / 2, disturbance=None):
        self.eta = np.array(pose, dtype=float).reshape(-1, 3)
        self.nu = np.zeros_like(self.eta)
        self.azimuth_limit = azimuth_limit
        self.disturbance = np.zeros((len(self.eta), 2)) if disturbance is None else np.asarray(disturbance, float)

    def forces(self, actions):
        """Body force and moment (N, 3) of the thrusters for (N, 2) or (N, 4) actions."""
        a = np.clip(np.asarray(actions, float), -1.0, 1.0)
        thrust = np.where(a[:, :2] >= 0.0, a[:, :2] * FORWARD, a[:, :2] * REVERSE)
        angle = a[:, 2:4] * self.azimuth_limit if a.shape[1] == 4 else np.zeros_like(thrust)
        fx, fy = thrust * np.cos(angle), thrust * np.sin(angle)
        y = np.array([THRUSTER_Y, -THRUSTER_Y])
        moment = (THRUSTER_X * fy - y * fx).sum(axis=1)
        return np.column_stack([fx.sum(axis=1), fy.sum(axis=1), moment])

    def step(self, actions, dt):
        u, v, r = self.nu.T
        psi = self.eta[:, 2]
        c, s = np.cos(psi), np.sin(psi)
        dist_body = np.column_stack([c * self.disturbance[:, 0] + s * self.disturbance[:, 1],
                                     -s * self.disturbance[:, 0] + c * self.disturbance[:, 1], np.zeros(len(psi))])
        coriolis = np.column_stack([-MASS[1] * v * r, MASS[0] * u * r, (MASS[1] - MASS[0]) * u * v])
        damping = (LINEAR_DAMPING + QUADRATIC_DAMPING * np.abs(self.nu)) * self.nu
        self.nu = self.nu + dt * (self.forces(actions) + dist_body - coriolis - damping) / MASS
        u, v, r = self.nu.T
        self.eta = self.eta + dt * np.column_stack([c * u - s * v, s * u + c * v, r])
        self.eta[:, 2] = np.remainder(self.eta[:, 2] + np.pi, 2 * np.pi) - np.pi


def fake_env(plant, num_actions, targets, route=None, decision_period=0.2, obstacles=None, gate_width=20.0):
    """A stand-in for a ``BatchedEnv`` around ``plant``: buffers of torch tensors (CPU), the sizes; ``obstacles``
    (N, K, 4) buoys x, y from the origin, radius, kind (default none); a task of gates ``gate_width`` [m] wide."""
    n = len(plant.eta)
    route = np.zeros((n, 1, 3)) if route is None else route
    obstacles = np.zeros((n, 0, 4)) if obstacles is None else obstacles
    buffers = SimpleNamespace(
        actions=torch.zeros(n, num_actions), position=torch.zeros(n, 3), orientation=torch.zeros(n, 4),
        velocity=torch.zeros(n, 6), target=torch.tensor(np.asarray(targets), dtype=torch.float32),
        origin=torch.zeros(n, 3), route=torch.tensor(route, dtype=torch.float32),
        waypoint_index=torch.zeros(n, dtype=torch.int32), done=torch.zeros(n, dtype=torch.bool),
        obstacles=torch.tensor(np.asarray(obstacles), dtype=torch.float32))
    env = SimpleNamespace(buffers=buffers, num_envs=n, num_actions=num_actions, torch_device=torch.device("cpu"),
                          decision_period=decision_period, task=SimpleNamespace(gate_width=gate_width))
    sync(env, plant)
    return env


def sync(env, plant):
    """The plant's state into the env's buffers."""
    b = env.buffers
    b.position[:, :2] = torch.tensor(plant.eta[:, :2], dtype=torch.float32)
    half = plant.eta[:, 2] / 2
    b.orientation.copy_(torch.tensor(np.column_stack([0 * half, 0 * half, np.sin(half), np.cos(half)]),
                                     dtype=torch.float32))
    b.velocity[:, [0, 1, 5]] = torch.tensor(plant.nu, dtype=torch.float32)


def run(env, plant, controller, seconds, substeps=10, on_decision=None):
    """``controller`` sails ``plant`` for ``seconds``; ``on_decision(env, plant)`` after each decision."""
    dt = env.decision_period / substeps
    for _ in range(int(round(seconds / env.decision_period))):
        controller.act(env)
        actions = env.buffers.actions.numpy().copy()
        for _ in range(substeps):
            plant.step(actions, dt)
        sync(env, plant)
        if on_decision is not None:
            on_decision(env, plant)
