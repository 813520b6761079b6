"""netshape.deflection — tool deflection, the wall error it leaves and its path compensation.

The end mill is a uniform cantilever (length = stick-out, E from the cutter, I from an inscribed
square D⁴/48 or an equivalent diameter 0.8·D) loaded by the instantaneous cutting force of the
flat end mill model (netshape.force); the wall at height z is generated when a flute's element at z
passes the wall angle (0 for the left wall / up milling, π for the right wall / down milling), and
the wall error there is the deflection at z along the wall normal, + when material is left
(J.-H. Cho, S.-H. Suh, "Path compensation toward direct shape control: dealing with tool deflection
problem in 2D contour machining", 1993). Along a program the engagement comes from a Z-map swept move
by move; the compensation schemes (1-D, integrated, sectional, accelerated) live in C++
(netshape._core.compensation) and are driven from here. See docs/deflection.md.

    import netshape as ns
    m = ns.deflection.make_model(diameter=25, flutes=4, helix_deg=60, stick_out=250,
                                 youngs_modulus=210e3, feed_per_tooth=0.0127, ap=2.5, ae=2, mode="down",
                                 coefficients="cho_suh_example")
    ns.deflection.steady_wall(m, "down")["wall_error_mm"]
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np

from .._core import compensation as _comp
from .._core import deflection as _d
from .._core import force as _f

InertiaModel = _d.InertiaModel
LoadModel = _d.LoadModel
WallSide = _d.WallSide
Cantilever = _d.Cantilever
DeflectionModel = _d.DeflectionModel
DeflectionWorkspace = _d.DeflectionWorkspace
WallErrors = _d.WallErrors
second_moment = _d.second_moment
disk_forces = _d.disk_forces
deflection_at = _d.deflection_at
generation_angle = _d.generation_angle
wall_errors = _d.wall_errors
cut_levels = _d.cut_levels
max_force = _d.max_force
ReferenceLevel = _comp.ReferenceLevel
DeflectionScheme = _comp.DeflectionScheme
PathOptions = _comp.PathOptions
PathWallErrors = _comp.PathWallErrors
DeflectionCompensationOptions = _comp.DeflectionCompensationOptions
DeflectionCompensationResult = _comp.DeflectionCompensationResult
path_wall_errors = _comp.path_wall_errors
one_d_compensation = _comp.one_d_compensation
compensate_deflection = _comp.compensate_deflection
wall_normals = _comp.wall_normals

#: Kline–DeVor constant coefficient sets (K_T [N/mm²], K_R [-]) shipped for the examples.
#: "cho_suh_example": K_T = 1000 N/mm², K_R = 0.4 — assumed constants of the order of Kline's
#: empirical values for the §5 simulation set-up of Cho & Suh 1993 (Kline's regression in A, W, f is
#: not reproduced); replace with a calibrated set for real predictions.
KLINE_DEVOR_SETS: dict[str, tuple[float, float]] = {"cho_suh_example": (1000.0, 0.4)}

_LEVELS = ("bottom", "middle", "top")


def parse_coefficients(text: str):
    """``NAME`` (a linear edge set of netshape.force or a Kline–DeVor set of :data:`KLINE_DEVOR_SETS`),
    ``Ktc=…,Krc=…,Kac=…,Kte=…,Kre=…,Kae=…`` (linear edge) or ``KT=…,KR=…`` (Kline–DeVor, paper eq. 1)
    → LinearEdgeCoefficients or KlineDevorCoefficients; a path ending in ``.toml``: a coefficient file
    with the chip-size effect (:func:`netshape.deflection.chip.load_coefficients`) →
    SizeEffectCoefficients. ValueError names the bad item."""
    from netshape.force.simulate import parse_coefficients as parse_linear
    from netshape.force.simulate import parse_named_values

    if not isinstance(text, str) or not text.strip():
        raise ValueError(f"coefficients = {text!r}: expected a set name, Ktc=…,… or KT=…,KR=…")
    t = text.strip()
    if t.lower().endswith(".toml") and "=" not in t:
        from .chip import load_coefficients

        return load_coefficients(t)
    if "=" not in t:
        if t in KLINE_DEVOR_SETS:
            kt, kr = KLINE_DEVOR_SETS[t]
            return _f.KlineDevorCoefficients(kt=kt, kr=kr)
        names = list(_f.linear_edge_coefficient_set_names())
        if t in names:
            return _f.linear_edge_coefficient_set(t).coefficients
        raise ValueError(f"coefficients = {t!r}: unknown set (known: {', '.join(names + list(KLINE_DEVOR_SETS))})")
    keys = {item.split("=", 1)[0].strip().lower() for item in t.split(",") if "=" in item}
    if keys and keys <= {"kt", "kr"}:
        vals = parse_named_values(t, ("KT", "KR"))
        if "kt" not in vals or vals["kt"] <= 0:
            raise ValueError(f"coefficients KT = {vals.get('kt')!r}: required and positive [N/mm^2]")
        return _f.KlineDevorCoefficients(kt=vals["kt"], kr=vals.get("kr", 0.0))
    return parse_linear(t)


def _check_positive(name: str, value: float) -> float:
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value) or value <= 0:
        raise ValueError(f"{name} = {value!r}: must be a positive finite number")
    return float(value)


def make_model(*, diameter: float, flutes: int, helix_deg: float, stick_out: float, youngs_modulus: float,
               feed_per_tooth: float, ap: float, ae: float | None = None, mode: str = "down",
               coefficients="cho_suh_example", inertia: str = "square", load: str = "distributed",
               disk_height: float = 0.05, smooth_edges: bool = True,
               holder_compliance: float = 0.0, chip=None) -> DeflectionModel:
    """A validated :class:`DeflectionModel` for a steady cut (mm, MPa, degrees for the helix).
    ``coefficients``: text for :func:`parse_coefficients` or a coefficient object;
    ``holder_compliance`` [mm/N] the clamp/holder spring in series with the cantilever; ``chip`` a
    netshape.force.RunoutSizeEffect (runout and chip-size effect of the element chips) or None;
    coefficients with a size effect (:class:`chip.SizeEffectCoefficients`) add theirs to it."""
    d = _check_positive("diameter", diameter)
    _check_positive("stick_out", stick_out)
    if not isinstance(youngs_modulus, (int, float)) or not math.isfinite(youngs_modulus) or youngs_modulus <= 0:
        raise ValueError(f"youngs_modulus = {youngs_modulus!r}: must be a positive finite number [MPa]")
    _check_positive("ap", ap)
    if float(stick_out) < float(ap):
        raise ValueError(f"stick_out = {stick_out!r}: shorter than the axial depth of cut ap = {ap!r} [mm]")
    if mode not in ("up", "down", "slot"):
        raise ValueError(f"mode = {mode!r}: must be up, down or slot")
    if mode != "slot":
        if ae is None:
            raise ValueError(f"ae: required for mode {mode}")
        _check_positive("ae", ae)
        if ae > d:
            raise ValueError(f"ae = {ae!r}: must not exceed the diameter {d!r} [mm]")
    from .chip import chip_of

    k = parse_coefficients(coefficients) if isinstance(coefficients, str) else coefficients
    k, chip = chip_of(k, chip)
    m = DeflectionModel()
    fm = m.force
    fm.radius = 0.5 * d
    fm.flutes = int(flutes)
    fm.helix = math.radians(helix_deg)
    fm.axial_depth = float(ap)
    fm.feed_per_tooth = _check_positive("feed_per_tooth", feed_per_tooth)
    fm.disk_height = _check_positive("disk_height", disk_height)
    if isinstance(k, _f.KlineDevorCoefficients):
        fm.coefficient_model = _f.FlatCoefficientModel.kline_devor
        fm.kline_devor = k
    else:
        fm.coefficient_model = _f.FlatCoefficientModel.linear_edge
        fm.linear_edge = k
    fm.engagement = _f.AngularEngagement.from_mode(_f.milling_mode_from_string(mode), 0.5 * d,
                                                   float(ae) if mode != "slot" else d)
    m.force = fm
    m.beam = Cantilever.tool(d, float(stick_out), float(youngs_modulus), _d.inertia_model_from_string(inertia))
    m.load = _d.load_model_from_string(load)
    m.smooth_edges = bool(smooth_edges)
    m.holder_compliance = float(holder_compliance)
    if chip is not None:
        m.chip = chip
    m.validate()
    return m


def model_for_cutter(cutter, *, feed_per_tooth: float, coefficients, inertia: str = "square",
                     load: str = "distributed", ap: float = 1.0, disk_height: float = 0.05) -> DeflectionModel:
    """A model from a netshape.cutter.Cutter (flat end mill): D, N, β, stick-out, E, the holder
    compliance and the runout from the cutter (the size effect from ``coefficients``)."""
    from .chip import chip_of

    if str(cutter.kind).split(".")[-1] != "flat":
        raise ValueError(f"tool kind = {str(cutter.kind).split('.')[-1]}: the deflection model needs a flat end mill")
    return make_model(diameter=2 * cutter.radius, flutes=cutter.flutes, helix_deg=math.degrees(cutter.helix),
                      stick_out=cutter.stick_out, youngs_modulus=cutter.youngs_modulus,
                      feed_per_tooth=feed_per_tooth, ap=ap, ae=2 * cutter.radius, mode="slot",
                      coefficients=coefficients, inertia=inertia, load=load, disk_height=disk_height,
                      holder_compliance=cutter.holder_compliance, chip=chip_of(None, cutter=cutter)[1])


def steady_wall(model: DeflectionModel, mode: str, levels: int = 21) -> dict:
    """Wall error of one steady straight cut: JSON-ready dict with ``wall_error_mm`` (bottom, middle,
    top) [mm], ``profile`` (``z_mm``, ``error_mm`` bottom to top, ``levels`` heights), ``max_force_N``
    and ``side``. Up milling: the left wall; down: the right wall; slot: both walls under ``walls``
    (``wall_error_mm`` / ``profile`` then hold the wall with the larger error)."""
    if levels < 3:
        raise ValueError(f"levels = {levels!r}: must be at least 3")
    ws = DeflectionWorkspace(model)
    a = model.force.axial_depth
    z = np.linspace(0.0, a, levels)
    sides = {"up": ["left"], "down": ["right"], "slot": ["left", "right"]}[mode]
    walls = {}
    for s in sides:
        side = _d.wall_side_from_string(s)
        e3 = wall_errors(model, ws, side, cut_levels(a)).error
        prof = wall_errors(model, ws, side, z).error
        walls[s] = {"wall_error_mm": dict(zip(_LEVELS, map(float, e3))),
                    "profile": {"z_mm": [float(v) for v in z], "error_mm": [float(v) for v in prof]}}
    main = max(sides, key=lambda s: max(abs(v) for v in walls[s]["profile"]["error_mm"]))
    out = {"side": main, "wall_error_mm": walls[main]["wall_error_mm"], "profile": walls[main]["profile"],
           "max_force_N": float(max_force(model, ws, 720))}
    if mode == "slot":
        out["walls"] = walls
    return out


# --- stock and program --------------------------------------------------------------------------

from netshape.stock.config import load_stock  # noqa: E402  (the one stock format, docs/stock.md)


def contour_of(program, spacing: float):
    """The program's cutting moves (lines and XY arcs with XY motion) as one polyline sampled at most
    ``spacing`` [mm] apart: ``(points (n, 3), first, last, feed_mm_s)`` where first/last are the block
    indices of the contour. ValueError unless they form one contiguous contour at constant Z."""
    pts, _, first, last, feed = contour_samples(program, spacing)
    return pts, first, last, feed


def contour_samples(program, spacing: float, density: int = 1):
    """Like :func:`contour_of`, with each block cut into ``density`` × ceil(length / spacing) equal
    pieces: ``(points (n, 3), owner (n), first, last, feed_mm_s)``, owner[i] the program block point i
    ends (the first point: the contour's first block). With density d, every d-th point of a block is
    the point :func:`contour_of` gives, so a sparser sampling is a subset of a denser one."""
    _check_positive("spacing", spacing)
    blocks = list(program.blocks)
    idx = [i for i, b in enumerate(blocks)
           if int(b.kind) != 0 and math.hypot(b.end[0] - b.start[0], b.end[1] - b.start[1]) > 1e-9]
    if not idx:
        raise ValueError("program: no cutting move with XY motion (nothing to evaluate)")
    first, last = idx[0], idx[-1]
    pts = [np.asarray(blocks[first].start, dtype=float)]
    owner = [first]
    for i in range(first, last + 1):
        b = blocks[i]
        if int(b.kind) == 0 or math.hypot(b.end[0] - b.start[0], b.end[1] - b.start[1]) <= 1e-9:
            raise ValueError(f"program line {b.line}: the contour must be one run of XY cutting moves "
                             f"(a rapid or a Z-only move interrupts it)")
        if abs(b.start[2] - pts[0][2]) > 1e-6 or abs(b.end[2] - pts[0][2]) > 1e-6:
            raise ValueError(f"program line {b.line}: the contour must stay at Z = {pts[0][2]:g} mm (2-D contour)")
        if int(b.kind) == 2 and str(b.plane).split(".")[-1] != "xy":
            raise ValueError(f"program line {b.line}: arcs of the contour must be in the XY plane (G17)")
        k = max(1, math.ceil(b.length() / spacing)) * int(density)
        for j in range(1, k + 1):
            pts.append(np.asarray(b.point_at(j / k), dtype=float))
            owner.append(i)
    return np.vstack(pts), np.asarray(owner, dtype=np.int64), first, last, float(blocks[first].feed)


@dataclass
class PathSetup:
    """What a path evaluation needs, assembled from a program, a tool, a stock and the cut data."""
    model: DeflectionModel
    cutter: object
    stock: object
    program: object
    nominal: np.ndarray
    first: int
    last: int
    side: object
    options: PathOptions
    owner: np.ndarray | None = None   # program block of each nominal point
    spacing: float = 0.5              # the nominal points' spacing [mm]


def setup_path(program, cutter, stock, *, coefficients, rpm: float, spacing: float = 0.5,
               inertia: str = "square", load: str = "distributed", side: str = "auto",
               disk_height: float = 0.05, profile_levels: int = 21,
               feed_per_tooth: float | None = None) -> PathSetup:
    """Sample the program's contour, derive the feed per tooth from its F and ``rpm`` (or take
    ``feed_per_tooth`` [mm] when given) and pick the wall side (``auto``: the side whose wall angle
    lies in the engaged window at most points)."""
    _check_positive("rpm", rpm)
    if cutter.stick_out <= 0 or cutter.youngs_modulus <= 0:
        raise ValueError(f"youngs_modulus = {cutter.youngs_modulus!r}: must be positive [MPa]")
    nominal, owner, first, last, feed = contour_samples(program, spacing)
    if feed <= 0:
        raise ValueError("program: the contour has no feed (F) programmed")
    c = feed * 60.0 / (rpm * cutter.flutes) if feed_per_tooth is None else _check_positive("feed_per_tooth",
                                                                                            feed_per_tooth)
    depth = max(stock.max_height() - float(nominal[0, 2]), 1e-3)
    if cutter.stick_out < min(depth, cutter.flute_length):
        raise ValueError(f"stick_out_mm = {cutter.stick_out:g}: shorter than the cut depth "
                         f"{min(depth, cutter.flute_length):g} mm")
    model = model_for_cutter(cutter, feed_per_tooth=c, coefficients=coefficients, inertia=inertia, load=load,
                             ap=min(depth, cutter.flute_length, cutter.stick_out), disk_height=disk_height)
    opt = PathOptions()
    opt.profile_levels = int(profile_levels)
    if side == "auto":
        opt.side = WallSide.right
        zero = np.zeros(len(nominal))
        r = path_wall_errors(model, cutter, stock, nominal, wall_normals(nominal, WallSide.right), zero, opt)
        if not np.any(r.engaged):
            raise ValueError("program: the contour never touches the stock")
        flags = np.asarray(r.wall_flags)
        left, right = int(np.sum(flags & 1 > 0)), int(np.sum(flags & 2 > 0))
        opt.side = WallSide.left if left > right else WallSide.right
    else:
        opt.side = _d.wall_side_from_string(side)
    return PathSetup(model, cutter, stock, program, nominal, first, last, opt.side, opt, owner, float(spacing))


def predict_path(setup: PathSetup):
    """Wall error along the nominal contour (PathWallErrors). ValueError if it never touches the stock."""
    n = len(setup.nominal)
    r = path_wall_errors(setup.model, setup.cutter, setup.stock, setup.nominal,
                         wall_normals(setup.nominal, setup.side), np.zeros(n), setup.options)
    if not np.any(r.engaged):
        raise ValueError("program: the contour never touches the stock")
    return r


def compensate_path(setup: PathSetup, *, scheme: str = "integrated", level: str = "middle",
                    tolerance: float = 5e-4, discount: float = 1.0, max_iterations: int = 50,
                    anderson_depth: int = 5) -> DeflectionCompensationResult:
    """Run a compensation scheme on the contour (C++ compensate_deflection)."""
    o = compensation_options(setup, scheme=scheme, level=level, tolerance=tolerance, discount=discount,
                             max_iterations=max_iterations, anderson_depth=anderson_depth)
    return compensate_deflection(setup.model, setup.cutter, setup.stock, setup.nominal, o)


def compensation_options(setup: PathSetup, *, scheme: str, level: str, tolerance: float, discount: float,
                         max_iterations: int, anderson_depth: int, active=None) -> DeflectionCompensationOptions:
    """The C++ options of a compensation of ``setup``'s contour (``active``: per point, see
    DeflectionCompensationOptions.active)."""
    o = DeflectionCompensationOptions()
    o.scheme = _comp.deflection_scheme_from_string(scheme)
    o.level = _comp.reference_level_from_string(level)
    o.tolerance = float(tolerance)
    o.discount = float(discount)
    o.max_iterations = int(max_iterations)
    o.anderson_depth = int(anderson_depth)
    if active is not None:
        o.active = np.asarray(active, dtype=np.int32)
    o.path = setup.options
    return o


def path_table(r: PathWallErrors, nominal: np.ndarray) -> dict:
    """Per-point table of a path evaluation (JSON-ready lists)."""
    e = np.asarray(r.error)
    return {
        "x_mm": nominal[:, 0].tolist(), "y_mm": nominal[:, 1].tolist(),
        "width_mm": np.asarray(r.width).tolist(), "depth_mm": np.asarray(r.depth).tolist(),
        "error_bottom_mm": e[:, 0].tolist(), "error_middle_mm": e[:, 1].tolist(), "error_top_mm": e[:, 2].tolist(),
        "normal_deflection_mm": np.asarray(r.normal_deflection).tolist(),
        "tangential_deflection_mm": np.asarray(r.tangential_deflection).tolist(),
        "fx_N": np.asarray(r.force)[:, 0].tolist(), "fy_N": np.asarray(r.force)[:, 1].tolist(),
    }


def max_wall_error(r: PathWallErrors) -> dict:
    """Largest |error| along the path per level [mm]."""
    e = np.abs(np.asarray(r.error))
    return dict(zip(_LEVELS, map(float, e.max(axis=0))))


from .writer import compensated_blocks, compensated_program  # noqa: E402  (the written program)


__all__ = [
    "KLINE_DEVOR_SETS", "Cantilever", "DeflectionCompensationOptions", "DeflectionCompensationResult",
    "DeflectionModel", "DeflectionScheme", "DeflectionWorkspace", "InertiaModel", "LoadModel", "PathOptions",
    "PathSetup", "PathWallErrors", "ReferenceLevel", "WallErrors", "WallSide", "compensate_deflection",
    "compensate_path", "compensated_blocks", "compensation_options", "contour_samples",
    "compensated_program", "contour_of", "cut_levels", "deflection_at", "disk_forces",
    "generation_angle", "load_stock", "make_model", "max_force", "max_wall_error", "model_for_cutter",
    "one_d_compensation", "parse_coefficients", "path_table", "path_wall_errors", "predict_path",
    "second_moment", "setup_path", "steady_wall", "wall_errors", "wall_normals",
]
