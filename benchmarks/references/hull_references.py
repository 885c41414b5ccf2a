"""The per-triangle hull model and the rigid-body step as a user would write them in torch: vectorised
over (boats, triangles), all cases of the waterline clipping computed and selected with masks, no
host synchronisation (so a CUDA graph can capture it). One hull type, as in the benchmark."""

from __future__ import annotations

import torch

from benchmarks.references.ocean_references import TorchOceanReference


def rotate(q, v):
    """Rotate vectors v (..., 3) by quaternions q (..., 4) x y z w."""
    u, w = q[..., :3], q[..., 3:]
    t = 2.0 * torch.cross(u, v, dim=-1)
    return v + w * t + torch.cross(u, t, dim=-1)


def rotate_inverse(q, v):
    return rotate(torch.cat([-q[..., :3], q[..., 3:]], dim=-1), v)


class TorchHullReference:
    """Mirrors ``Simulator``: sampling at vertices, hull wrenches, Fossen integration, in torch."""

    def __init__(self, simulator, *, ocean_fields=None):
        fleet, hydro = simulator.fleet, simulator.config.hydrodynamics
        if len(fleet.model.boat_types) != 1:
            raise ValueError("the torch reference handles one hull type")
        boat = fleet.model.boat_types[0]
        device = torch.device("cuda" if fleet.device.is_cuda else "cpu")
        self.device, self.hydro, self.config = device, hydro, simulator.config
        self.water = water = simulator.ocean.config.water
        as_tensor = lambda a, dtype=torch.float32: torch.as_tensor(a, dtype=dtype, device=device)  # noqa: E731
        self.vertices = as_tensor(boat.hull.vertices)
        self.triangles = as_tensor(boat.hull.triangles, torch.int64)
        self.length = float(boat.hull.length)
        self.mass = boat.mass
        self.center_of_mass = as_tensor(boat.center_of_mass)
        self.inertia_origin = as_tensor(boat.inertia_about_origin)
        self.added_mass = as_tensor(boat.added_mass)
        self.inverse_mass_matrix = as_tensor(boat.mass_matrix).inverse()
        self.linear_damping = as_tensor(boat.linear_damping)
        self.quadratic_damping = as_tensor(boat.quadratic_damping)
        self.weight = as_tensor([0.0, 0.0, -boat.mass * water.gravity])

        ocean = simulator.ocean
        self.cell = ocean.config.cell_size
        self.n = ocean.config.resolution
        self.choppiness = ocean.config.choppiness
        self.iterations = ocean.config.inversion_iterations if self.choppiness > 0 else 0
        # (4, n, n, 2) field pairs: Warp's own fields (hull-only benchmark) or the torch ocean's.
        self.fields = ocean_fields
        self.ocean = None
        if ocean_fields is None:
            import warp as wp

            self.fields = wp.to_torch(ocean.fields)
        tensors = fleet.tensors
        self.position = tensors.position.clone()
        self.orientation = tensors.orientation.clone()
        self.velocity = tensors.velocity.clone()
        self.wrench = torch.zeros_like(self.velocity)

    def with_torch_ocean(self, cells, time: float) -> "TorchHullReference":
        """Evaluate the ocean with the torch.fft reference too (for the full-step benchmark)."""
        self.ocean = TorchOceanReference(cells, str(self.device))
        self.ocean.time.fill_(time)
        return self

    # --- ocean sampling ---------------------------------------------------------------------------
    def _bilinear(self, field, xy):
        g = xy / self.cell
        g0 = torch.floor(g)
        t = g - g0
        ix0 = torch.remainder(g0[..., 0].long(), self.n)
        iy0 = torch.remainder(g0[..., 1].long(), self.n)
        ix1, iy1 = (ix0 + 1) % self.n, (iy0 + 1) % self.n
        tx, ty = t[..., 0:1], t[..., 1:2]
        lower = (1 - tx) * field[iy0, ix0] + tx * field[iy0, ix1]
        upper = (1 - tx) * field[iy1, ix0] + tx * field[iy1, ix1]
        return (1 - ty) * lower + ty * upper

    def _surface(self, xy):
        """(height, water velocity (..., 3)) above world points xy (..., 2)."""
        q = xy
        for _ in range(self.iterations):
            q = xy - self.choppiness * self._bilinear(self.fields[1], q)
        height_rate = self._bilinear(self.fields[0], q)
        horizontal = self._bilinear(self.fields[3], q)
        return height_rate[..., 0], torch.cat([horizontal, height_rate[..., 1:2]], dim=-1)

    # --- water forces -------------------------------------------------------------------------------
    def hull_wrenches(self):
        """(boats, 6) body-frame wrenches about the origin; updates self.wrench."""
        q = self.orientation[:, None, :].expand(-1, len(self.vertices), -1)
        world = self.position[:, None, :] + rotate(q, self.vertices[None])
        height, flow_world = self._surface(world[..., :2])
        depth = height - world[..., 2]
        flow = rotate_inverse(q, flow_world)
        _, origin_flow = self._surface(self.position[:, :2])
        origin_flow = rotate_inverse(self.orientation, origin_flow)

        linear, angular = self.velocity[:, None, :3], self.velocity[:, None, 3:]
        reynolds = torch.clamp(torch.linalg.norm(self.velocity[:, :3] - origin_flow, dim=-1) * self.length
                               / self.water.kinematic_viscosity, min=1e5)
        friction = (0.075 / (torch.log10(reynolds) - 2.0) ** 2)[:, None]

        r = self.vertices[self.triangles][None].expand(len(depth), -1, -1, -1)  # (B, T, 3, 3)
        d = depth[:, self.triangles]  # (B, T, 3)
        u = flow[:, self.triangles]  # (B, T, 3, 3)
        wet = d > 0
        count = wet.sum(-1)
        odd = torch.where(count == 1, torch.argmax(wet.int(), -1), torch.argmax((~wet).int(), -1))
        order = (odd[..., None] + torch.arange(3, device=self.device)) % 3
        ra, rb, rc = (torch.gather(r, 2, order[..., k, None, None].expand(-1, -1, 1, 3))[..., 0, :] for k in range(3))
        da, db, dc = (torch.gather(d, 2, order[..., k, None])[..., 0] for k in range(3))
        ua, ub, uc = (torch.gather(u, 2, order[..., k, None, None].expand(-1, -1, 1, 3))[..., 0, :] for k in range(3))

        def cut(x0, d0, x1, d1):
            fraction = (d0 / (d0 - d1))[..., None]
            return x0 + fraction * (x1 - x0)

        zero = torch.zeros_like(da)
        one_in = count == 1
        # piece 1: full triangle, the single submerged corner's triangle, or the first half of the quad
        p1 = [torch.where(count[..., None] == 3, r[..., 0, :], torch.where(one_in[..., None], ra, cut(rb, db, ra, da))),
              torch.where(count[..., None] == 3, r[..., 1, :], torch.where(one_in[..., None], cut(ra, da, rb, db), rb)),
              torch.where(count[..., None] == 3, r[..., 2, :], torch.where(one_in[..., None], cut(ra, da, rc, dc), rc))]
        d1 = [torch.where(count == 3, d[..., 0], torch.where(one_in, da, zero)),
              torch.where(count == 3, d[..., 1], torch.where(one_in, zero, db)),
              torch.where(count == 3, d[..., 2], torch.where(one_in, zero, dc))]
        u1 = [torch.where(count[..., None] == 3, u[..., 0, :], torch.where(one_in[..., None], ua, cut(ub, db, ua, da))),
              torch.where(count[..., None] == 3, u[..., 1, :], torch.where(one_in[..., None], cut(ua, da, ub, db), ub)),
              torch.where(count[..., None] == 3, u[..., 2, :], torch.where(one_in[..., None], cut(ua, da, uc, dc), uc))]
        # piece 2: the second half of the quad (two corners submerged)
        p2 = [cut(rb, db, ra, da), rc, cut(rc, dc, ra, da)]
        d2 = [zero, dc, zero]
        u2 = [cut(ub, db, ua, da), uc, cut(uc, dc, ua, da)]
        total = self._pieces(p1, d1, u1, linear, angular, friction, count > 0)
        total = total + self._pieces(p2, d2, u2, linear, angular, friction, count == 2)
        self.wrench = total.sum(dim=1)
        return self.wrench

    def _pieces(self, r, d, u, linear, angular, friction, use):
        h = self.hydro
        area_vector = 0.5 * torch.cross(r[1] - r[0], r[2] - r[0], dim=-1)
        area = torch.linalg.norm(area_vector, dim=-1, keepdim=True)
        valid = use & (area[..., 0] > 1e-12)
        normal = area_vector / torch.clamp(area, min=1e-30)
        rho_g = self.water.density * self.water.gravity
        p = [rho_g * x for x in d]
        pressure_sum = (p[0] + p[1] + p[2])[..., None]
        force = -(pressure_sum / 3.0) * area_vector
        first_moment = (area / 12.0) * (p[0][..., None] * r[0] + p[1][..., None] * r[1] + p[2][..., None] * r[2]
                                        + pressure_sum * (r[0] + r[1] + r[2]))
        moment = torch.cross(normal, first_moment, dim=-1)
        centroid = (r[0] + r[1] + r[2]) / 3.0
        relative = linear + torch.cross(angular.expand_as(centroid), centroid, dim=-1) - (u[0] + u[1] + u[2]) / 3.0
        speed = torch.linalg.norm(relative, dim=-1, keepdim=True)
        moving = speed > 1e-6
        cos_t = (normal * relative).sum(-1, keepdim=True) / torch.clamp(speed, min=1e-30)
        s = speed / h.reference_speed
        drag_pressure = (h.pressure_drag_linear + h.pressure_drag_quadratic * s) * s * torch.clamp(cos_t, min=0.0) \
            ** h.pressure_drag_falloff
        suction = (h.suction_linear + h.suction_quadratic * s) * s * torch.clamp(-cos_t, min=0.0) ** h.suction_falloff
        drag = torch.where(cos_t > 0, -drag_pressure, suction) * area * normal
        if h.skin_friction:
            tangential = relative - (relative * normal).sum(-1, keepdim=True) * normal
            drag = drag - 0.5 * self.water.density * friction[..., None] * area * torch.linalg.norm(
                tangential, dim=-1, keepdim=True) * tangential
        drag = torch.where(moving, drag, torch.zeros_like(drag))
        wrench = torch.cat([force + drag, moment + torch.cross(centroid, drag, dim=-1)], dim=-1)
        return torch.where(valid[..., None], wrench, torch.zeros_like(wrench))

    # --- rigid bodies -------------------------------------------------------------------------------
    def integrate(self, dt: float):
        nu, q = self.velocity, self.orientation
        v, w = nu[:, :3], nu[:, 3:]
        r_g = self.center_of_mass.expand_as(v)
        gravity = rotate_inverse(q, self.weight.expand_as(v))
        tau = self.wrench + torch.cat([gravity, torch.cross(r_g, gravity, dim=-1)], dim=-1)
        _, origin_flow = self._surface(self.position[:, :2])
        current = torch.cat([rotate_inverse(q, origin_flow), torch.zeros_like(v)], dim=-1)
        nu_r = nu - current
        w_cross_v = torch.cross(w, v, dim=-1)
        c_rb = torch.cat([self.mass * (w_cross_v + torch.cross(w, torch.cross(w, r_g, dim=-1), dim=-1)),
                          torch.cross(w, w @ self.inertia_origin.T, dim=-1)
                          + self.mass * torch.cross(r_g, w_cross_v, dim=-1)], dim=-1)
        a = nu_r @ self.added_mass.T
        c_a = torch.cat([torch.cross(nu_r[:, 3:], a[:, :3], dim=-1),
                         torch.cross(nu_r[:, :3], a[:, :3], dim=-1) + torch.cross(nu_r[:, 3:], a[:, 3:], dim=-1)], dim=-1)
        damping = self.linear_damping * nu_r + self.quadratic_damping * nu_r.abs() * nu_r
        self.velocity = nu + dt * ((tau - c_rb - c_a - damping) @ self.inverse_mass_matrix.T)
        v, w = self.velocity[:, :3], self.velocity[:, 3:]
        self.position = self.position + dt * rotate(q, v)
        rate = torch.linalg.norm(w, dim=-1, keepdim=True)
        half = 0.5 * rate * dt
        axis = w / torch.clamp(rate, min=1e-30)
        step = torch.cat([axis * torch.sin(half), torch.cos(half)], dim=-1)
        x1, y1, z1, w1 = q.unbind(-1)
        x2, y2, z2, w2 = step.unbind(-1)
        turned = torch.stack([w1 * x2 + x1 * w2 + y1 * z2 - z1 * y2, w1 * y2 - x1 * z2 + y1 * w2 + z1 * x2,
                              w1 * z2 + x1 * y2 - y1 * x2 + z1 * w2, w1 * w2 - x1 * x2 - y1 * y2 - z1 * z2], dim=-1)
        self.orientation = turned / torch.linalg.norm(turned, dim=-1, keepdim=True)

    def substep(self, dt: float):
        """Ocean (torch.fft), water forces, integration: the full substep."""
        self.ocean.update()
        fields = self.ocean.fields
        self.fields = torch.stack([fields.real, fields.imag], dim=-1)
        self.hull_wrenches()
        self.integrate(dt)
        self.ocean.time += dt

