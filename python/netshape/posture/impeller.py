"""Parametric impeller: the test part for 5-axis tool posture planning.

Geometry (all in the workpiece frame, z = the impeller axis, units mm and degrees in the TOML keys):

- hub: the plane z = 0 (a hub of revolution with a flat profile) between ``hub_inner_radius_mm`` and
  ``hub_outer_radius_mm``;
- camber line of blade 0 on the hub: the circular arc from (r_in, 0) to r_out·(cos ω, sin ω) leaving the inlet
  at ``inlet_angle_deg`` from the tangential direction (ω = ``wrap_deg``), an exact rational quadratic NURBS;
- shroud curve: the same arc turned by ``twist_deg`` about z and lifted to z = ``blade_height_mm``; the blade is
  the ruled NURBS surface (degree 2 × 1) between the hub curve and the shroud curve, so it leans over the
  passage more at larger radii (its circumferential lean is r·twist over the height);
- thickness: the two faces of a blade are its camber surface turned by ±δ about z, δ = thickness_mm / (2 r_mean),
  r_mean = (r_in + r_out)/2 (circumferential thickness 2δ·r);
- ``blades`` blades, blade k turned by 2πk/N.

Because every face is a rotation of one surface about z, the blade-to-blade gap is exact: the suction face of
blade k turned by 2π/N − 2δ is the pressure face of blade k + 1, so at radius r the circumferential gap (arc
length at constant r and z) is r·(2π/N − 2δ) at every height (:meth:`Impeller.passage_gap`).

The machined surface is the passage floor between blades 0 and 1 (the ruled surface between the two faces' hub
curves, normal +z), the CC path its iso-curve v = 1/2, and the obstacles the two blades (faces, tip, leading
and trailing edges). With the default keys the passage is narrow and deep: the normal posture (tool along +z)
collides with the leaning blade on the inner part of the path.
"""

from __future__ import annotations

import math
import os
from dataclasses import dataclass, field, fields

import numpy as np

from ..geometry import NurbsSurface, TriangleMesh


@dataclass
class ImpellerParams:
    """Impeller keys (TOML names, units in the names)."""

    blades: int = 12
    hub_inner_radius_mm: float = 40.0
    hub_outer_radius_mm: float = 80.0
    blade_height_mm: float = 30.0
    inlet_angle_deg: float = 35.0
    wrap_deg: float = 35.0
    twist_deg: float = 10.0
    thickness_mm: float = 3.0
    mesh_count_u: int = 24
    mesh_count_v: int = 8

    def validate(self) -> None:
        """Raise ValueError naming the key and the value."""
        for f in fields(self):
            v = getattr(self, f.name)
            if isinstance(v, bool) or not isinstance(v, (int, float)) or not math.isfinite(v):
                raise ValueError(f"{f.name} = {v!r}: must be a finite number")
        if not isinstance(self.blades, int) or not 3 <= self.blades <= 64:
            raise ValueError(f"blades = {self.blades!r}: must be an integer in [3, 64]")
        for key in ("mesh_count_u", "mesh_count_v"):
            v = getattr(self, key)
            if not isinstance(v, int) or not 2 <= v <= 1000:
                raise ValueError(f"{key} = {v!r}: must be an integer in [2, 1000]")
        if self.hub_inner_radius_mm <= 0:
            raise ValueError(f"hub_inner_radius_mm = {self.hub_inner_radius_mm!r}: must be positive [mm]")
        if self.hub_outer_radius_mm <= self.hub_inner_radius_mm:
            raise ValueError(f"hub_outer_radius_mm = {self.hub_outer_radius_mm!r}: must exceed "
                             f"hub_inner_radius_mm = {self.hub_inner_radius_mm!r} [mm]")
        if self.blade_height_mm <= 0:
            raise ValueError(f"blade_height_mm = {self.blade_height_mm!r}: must be positive [mm]")
        if not 0 < self.inlet_angle_deg < 90:
            raise ValueError(f"inlet_angle_deg = {self.inlet_angle_deg!r}: must be in (0, 90) [deg]")
        if not 0 <= self.wrap_deg < 120:
            raise ValueError(f"wrap_deg = {self.wrap_deg!r}: must be in [0, 120) [deg]")
        if not -60 < self.twist_deg < 60:
            raise ValueError(f"twist_deg = {self.twist_deg!r}: must be in (-60, 60) [deg]")
        pitch = 360.0 / self.blades
        thick_deg = math.degrees(self.thickness_mm / (0.5 * (self.hub_inner_radius_mm + self.hub_outer_radius_mm)))
        if not 0 < thick_deg < 0.8 * pitch:
            raise ValueError(f"thickness_mm = {self.thickness_mm!r}: must be positive and leave a passage "
                             f"(blade angle {thick_deg:.3g} deg vs pitch {pitch:.3g} deg)")


def _rot(angle: float) -> np.ndarray:
    c, s = math.cos(angle), math.sin(angle)
    return np.array([[c, -s, 0.0], [s, c, 0.0], [0.0, 0.0, 1.0]])


def _camber_arc(p: ImpellerParams) -> tuple[np.ndarray, np.ndarray]:
    """Control points (3, 3) and weights (3,) of the hub camber arc of blade 0 (rational quadratic)."""
    r1, r2 = p.hub_inner_radius_mm, p.hub_outer_radius_mm
    w = math.radians(p.wrap_deg)
    b = math.radians(p.inlet_angle_deg)
    p1 = np.array([r1, 0.0])
    p2 = np.array([r2 * math.cos(w), r2 * math.sin(w)])
    t1 = np.array([math.sin(b), math.cos(b)])  # β from the tangential direction (0, 1) towards radial (1, 0)
    m = np.array([t1[1], -t1[0]])
    chord = p2 - p1
    denom = 2.0 * float(m @ chord)
    if abs(denom) < 1e-12 * float(chord @ chord):  # straight blade
        mid = 0.5 * (p1 + p2)
        weight = 1.0
    else:
        rho = float(chord @ chord) / denom
        c = p1 + rho * m
        a1, a2 = p1 - c, p2 - c
        half = 0.5 * math.acos(max(-1.0, min(1.0, float(a1 @ a2) / (np.linalg.norm(a1) * np.linalg.norm(a2)))))
        if half >= 0.5 * math.pi - 1e-6:
            raise ValueError(f"inlet_angle_deg = {p.inlet_angle_deg!r}: the camber arc would span 180 deg or more")
        bis = (a1 + a2) / np.linalg.norm(a1 + a2)
        mid = c + bis * abs(rho) / math.cos(half)
        weight = math.cos(half)
    pts = np.zeros((3, 3))
    pts[0, :2], pts[1, :2], pts[2, :2] = p1, mid, p2
    return pts, np.array([1.0, weight, 1.0])


_KNOTS_U = np.array([0.0, 0.0, 0.0, 1.0, 1.0, 1.0])
_KNOTS_V = np.array([0.0, 0.0, 1.0, 1.0])


def _ruled(a: np.ndarray, b: np.ndarray, weights: np.ndarray) -> NurbsSurface:
    """Ruled NURBS (degree 2 in u, 1 in v) between two rational quadratic curves with equal weights."""
    cps = np.empty((6, 3))
    cps[0::2], cps[1::2] = a, b
    return NurbsSurface(2, 1, _KNOTS_U, _KNOTS_V, cps, np.repeat(weights, 2))


@dataclass
class Impeller:
    """The generated impeller (see the module docstring)."""

    params: ImpellerParams
    blade_faces: list[tuple[NurbsSurface, NurbsSurface]] = field(default_factory=list)  # (pressure −δ, suction +δ)
    floor: NurbsSurface | None = None
    delta: float = 0.0  # half thickness angle δ [rad]

    @property
    def pitch(self) -> float:
        """Blade pitch 2π/N [rad]."""
        return 2.0 * math.pi / self.params.blades

    def passage_gap(self, r) -> np.ndarray:
        """Circumferential blade-to-blade gap r·(2π/N − 2δ) at radius r [mm] (exact, any height)."""
        return np.asarray(r, float) * (self.pitch - 2.0 * self.delta)

    def blade_mesh(self, k: int) -> tuple[np.ndarray, np.ndarray]:
        """Closed triangle mesh of blade k: (vertices (v, 3), faces (m, 3)) — both faces, tip, edges."""
        p = self.params
        nu, nv = p.mesh_count_u, p.mesh_count_v
        us, vs = np.linspace(0, 1, nu), np.linspace(0, 1, nv)
        lo, hi = self.blade_faces[k]
        a = lo.evaluate_grid(us, vs, normals=False).reshape(nu, nv, 3)
        b = hi.evaluate_grid(us, vs, normals=False).reshape(nu, nv, 3)
        verts = np.concatenate([a.reshape(-1, 3), b.reshape(-1, 3)])
        off = nu * nv
        idx = lambda i, j: i * nv + j  # noqa: E731
        tris = []
        for i in range(nu - 1):
            for j in range(nv - 1):
                q = (idx(i, j), idx(i + 1, j), idx(i + 1, j + 1), idx(i, j + 1))
                tris += [(q[0], q[1], q[2]), (q[0], q[2], q[3])]
                tris += [(off + q[0], off + q[2], off + q[1]), (off + q[0], off + q[3], off + q[2])]
        for i in range(nu - 1):  # tip (v = 1) and hub edge (v = 0) strips
            for j in (0, nv - 1):
                tris += [(idx(i, j), idx(i + 1, j), off + idx(i + 1, j)), (idx(i, j), off + idx(i + 1, j), off + idx(i, j))]
        for j in range(nv - 1):  # leading (u = 0) and trailing (u = 1) edges
            for i in (0, nu - 1):
                tris += [(idx(i, j), idx(i, j + 1), off + idx(i, j + 1)), (idx(i, j), off + idx(i, j + 1), off + idx(i, j))]
        return verts, np.asarray(tris, np.int64)

    def obstacles(self) -> tuple[np.ndarray, np.ndarray]:
        """Blades 0 and 1 (the walls of the machined passage) as one mesh (vertices, faces)."""
        v0, f0 = self.blade_mesh(0)
        v1, f1 = self.blade_mesh(1)
        return np.concatenate([v0, v1]), np.concatenate([f0, f1 + len(v0)])

    def obstacle_mesh(self) -> TriangleMesh:
        v, f = self.obstacles()
        return TriangleMesh(v, f)

    def cc_path(self, points: int) -> tuple[np.ndarray, np.ndarray]:
        """CC points (n, 3) along the middle of the passage floor (iso-curve v = 1/2, u ∈ [0, 1]) and normals."""
        if not isinstance(points, int) or points < 4:
            raise ValueError(f"points = {points!r}: must be an integer ≥ 4")
        uv = np.column_stack([np.linspace(0.0, 1.0, points), np.full(points, 0.5)])
        pts, nrm = self.floor.evaluate_with_normals(uv)
        return np.asarray(pts), np.asarray(nrm)

    def blade_path(self, points: int, height: float = 0.75) -> tuple[np.ndarray, np.ndarray, np.ndarray,
                                                                       np.ndarray]:
        """A second 5-axis path: point milling of blade 1's pressure face (the passage side) along its iso-curve
        at `height` (fraction of the blade height, v) from the leading to the trailing edge, u ∈ [0, 1].

        Returns CC points (n, 3), unit normals (n, 3) pointing into the passage (towards blade 0), and the
        obstacles (vertices, faces): blade 0 (the opposite wall) and the passage floor. The normal posture lies
        nearly horizontal across the passage, so the tool must tilt up out of it; the face leans and turns
        along the path, so even the normal posture turns the rotary axes. The machined face itself, like the
        floor of :meth:`cc_path`, is not an obstacle."""
        if not isinstance(points, int) or points < 4:
            raise ValueError(f"points = {points!r}: must be an integer ≥ 4")
        if not 0 < height < 1:
            raise ValueError(f"height = {height!r}: must be in (0, 1)")
        face = self.blade_faces[1][0]
        uv = np.column_stack([np.linspace(0.0, 1.0, points), np.full(points, float(height))])
        pts, nrm = (np.asarray(x) for x in face.evaluate_with_normals(uv))
        towards = (self.blade_faces[0][1].evaluate_with_normals(uv)[0] - pts)  # across the passage
        nrm = nrm * np.sign(np.sum(nrm * towards, axis=1))[:, None]
        v0, f0 = self.blade_mesh(0)
        nu, nv = self.params.mesh_count_u, self.params.mesh_count_v
        grid = self.floor.evaluate_grid(np.linspace(0, 1, nu), np.linspace(0, 1, nv), normals=False)
        fv = np.asarray(grid).reshape(-1, 3)
        ff = [(i * nv + j, (i + 1) * nv + j, (i + 1) * nv + j + 1) for i in range(nu - 1) for j in range(nv - 1)]
        ff += [(i * nv + j, (i + 1) * nv + j + 1, i * nv + j + 1) for i in range(nu - 1) for j in range(nv - 1)]
        return pts, nrm, np.concatenate([v0, fv]), np.concatenate([f0, np.asarray(ff, np.int64) + len(v0)])


def make_impeller(params: ImpellerParams | None = None) -> Impeller:
    """Build the impeller's NURBS surfaces from validated parameters (defaults: :class:`ImpellerParams`)."""
    p = params or ImpellerParams()
    p.validate()
    arc, weights = _camber_arc(p)
    tw = math.radians(p.twist_deg)
    shroud = arc @ _rot(tw).T + np.array([0.0, 0.0, p.blade_height_mm])
    delta = p.thickness_mm / (p.hub_inner_radius_mm + p.hub_outer_radius_mm)
    imp = Impeller(params=p, delta=delta)
    pitch = 2.0 * math.pi / p.blades
    for k in range(p.blades):
        faces = []
        for sign in (-1.0, 1.0):
            r = _rot(k * pitch + sign * delta).T
            faces.append(_ruled(arc @ r, shroud @ r, weights))
        imp.blade_faces.append((faces[0], faces[1]))
    # passage floor between blade 0's suction face and blade 1's pressure face, on the hub z = 0
    a = arc @ _rot(delta).T
    b = arc @ _rot(pitch - delta).T
    imp.floor = _ruled(a, b, weights)
    return imp


def impeller_params_from_dict(d: dict, *, source: str = "impeller") -> ImpellerParams:
    """ImpellerParams from TOML keys; unknown keys and bad values raise ValueError naming them."""
    if not isinstance(d, dict):
        raise ValueError(f"{source}: must be a table of keys")
    known = {f.name: f for f in fields(ImpellerParams)}
    p = ImpellerParams()
    for key, value in d.items():
        if key not in known:
            raise ValueError(f"{source}: {key} = {value!r}: unknown key (known: {', '.join(known)})")
        if key in ("blades", "mesh_count_u", "mesh_count_v"):
            if isinstance(value, bool) or not isinstance(value, int):
                raise ValueError(f"{source}: {key} = {value!r}: must be an integer")
        elif isinstance(value, bool) or not isinstance(value, (int, float)):
            raise ValueError(f"{source}: {key} = {value!r}: must be a number")
        setattr(p, key, value if key in ("blades", "mesh_count_u", "mesh_count_v") else float(value))
    try:
        p.validate()
    except ValueError as exc:
        raise ValueError(f"{source}: {exc}") from None
    return p


def load_impeller(path: str | os.PathLike | None = None) -> Impeller:
    """The impeller of a TOML file of :class:`ImpellerParams` keys (None: the defaults)."""
    if path is None:
        return make_impeller()
    from netshape._config import load_toml

    data = load_toml(path)
    return make_impeller(impeller_params_from_dict(data, source=os.fspath(path)))


__all__ = ["Impeller", "ImpellerParams", "impeller_params_from_dict", "load_impeller", "make_impeller"]
