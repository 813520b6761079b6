"""The machine stages of the job: its machine (errors scaled), the volumetric error along the program
and the volumetric compensation, all in machine coordinates (program point + active work offset, see
:mod:`netshape.job.program`); the samples along the feed moves they are measured at."""

from __future__ import annotations

from dataclasses import dataclass, field

import numpy as np

from .spec import Job


def load_job_machine(job: Job):
    """The job's machine with its errors scaled by ``machine.error_scale`` and its tool length from
    ``offsets.tool_length_mm`` when given."""
    from netshape import machine as nm

    m = nm.load_machine(job.machine)
    if job.offsets.get("tool_length_mm") is not None:
        m.tool_length = job.offsets["tool_length_mm"]
    if job.error_scale != 1.0:
        scale_machine_errors(m, job.error_scale)
    m.validate()
    return m


def scale_machine_errors(m, s: float) -> None:
    """Multiply every error of ``m`` (the 18 error motions, squareness, spindle tilt, cyclic amplitudes,
    backlash, thermal drift amplitudes) by ``s``."""
    axes = []
    for ax in m.axes:
        funcs = []
        for f in ax.errors:
            kind = f.kind.name
            if kind == "polynomial":
                f.coefficients = [s * c for c in f.coefficients]
            elif kind == "table":
                f.values = [s * v for v in f.values]
            funcs.append(f)
        ax.errors = funcs
        ax.cyclic = [type(t)(amplitude=s * t.amplitude, period=t.period, phase=t.phase) for t in ax.cyclic]
        ax.backlash = s * ax.backlash
        axes.append(ax)
    m.axes = axes
    m.ec0y, m.eb0z, m.ea0z = s * m.ec0y, s * m.eb0z, s * m.ea0z
    m.thermal = [type(t)(axis=t.axis, amplitude=s * t.amplitude, time_constant=t.time_constant) for t in m.thermal]
    m.spindle_tilt_a, m.spindle_tilt_b = s * m.spindle_tilt_a, s * m.spindle_tilt_b


def feed_segments(tp, chord_tolerance: float = 1e-4) -> tuple[np.ndarray, np.ndarray]:
    """Start and end points (m, 3) of the feed moves of ``tp`` with arcs split into chords [mm]."""
    from netshape import toolpath as tpm

    split = tp.split_arcs(chord_tolerance)
    a, b = [], []
    for blk in split.blocks:
        if blk.kind == tpm.MotionKind.rapid:
            continue
        a.append(blk.start)
        b.append(blk.end)
    if not a:
        return np.zeros((0, 3)), np.zeros((0, 3))
    return np.asarray(a, dtype=float), np.asarray(b, dtype=float)


def distance_to_path(points: np.ndarray, a: np.ndarray, b: np.ndarray, spacing: float) -> np.ndarray:
    """Distance [mm] of each point to the polyline segments (a[i], b[i]): candidate segments from a
    k-d tree of points every ``spacing`` mm along them, then the exact point-to-segment distance."""
    from scipy.spatial import cKDTree

    if len(points) == 0:
        return np.zeros(0)
    L = np.linalg.norm(b - a, axis=1)
    n = np.maximum(1, np.ceil(L / spacing).astype(np.int64)) + 1
    owner = np.repeat(np.arange(len(a)), n)
    first = np.concatenate([[0], np.cumsum(n)[:-1]])
    t = (np.arange(owner.size) - np.repeat(first, n)) / np.repeat(n - 1, n)
    samples = a[owner] + t[:, None] * (b[owner] - a[owner])
    k = min(16, len(samples))
    _, idx = cKDTree(samples).query(points, k=k)
    idx = np.atleast_2d(idx).reshape(len(points), -1)
    segs = owner[idx]                                     # (p, k)
    A, B = a[segs], b[segs]                               # (p, k, 3)
    AB = B - A
    L2 = np.einsum("pkj,pkj->pk", AB, AB)
    tt = np.einsum("pkj,pkj->pk", points[:, None, :] - A, AB) / np.where(L2 > 0, L2, 1.0)
    tt = np.clip(np.where(L2 > 0, tt, 0.0), 0.0, 1.0)
    d = np.linalg.norm(points[:, None, :] - (A + tt[..., None] * AB), axis=2)
    return d.min(axis=1)


@dataclass
class VolumetricResult:
    """Deviation of the actual tool-tip path from the nominal path [mm] (machine frame)."""

    s_before_mm: np.ndarray
    before_mm: np.ndarray
    points_mm: np.ndarray                 # nominal sample points, machine frame
    error_vectors_mm: np.ndarray          # tip error e(p) at them
    s_after_mm: np.ndarray | None = None
    after_mm: np.ndarray | None = None
    compensated: object = None            # Toolpath, machine frame
    report: dict = field(default_factory=dict)


#: Largest volumetric error accepted [mm]: larger ones come from a wrong machine file or error_scale.
MAX_TIP_ERROR_MM = 1e3


def check_tip_errors(job: Job, pts: np.ndarray, e: np.ndarray) -> None:
    """Refuse volumetric errors that are not finite or exceed MAX_TIP_ERROR_MM, naming the job key that
    made them (machine.error_scale when it is not 1, else machine.file) and the first such point."""
    with np.errstate(over="ignore", invalid="ignore"):
        size = np.linalg.norm(e, axis=1)
    bad = ~(size <= MAX_TIP_ERROR_MM)
    if not bad.any():
        return
    i = int(np.argmax(bad))
    p = pts[i]
    what = (f"a volumetric error of {size[i]:.3g} mm at machine point ({p[0]:g}, {p[1]:g}, {p[2]:g}) mm "
            f"(more than {MAX_TIP_ERROR_MM:g} mm is refused)")
    if job.error_scale != 1.0:
        raise ValueError(f"machine.error_scale = {job.error_scale:g}: gives {what}")
    raise ValueError(f"machine.file = {str(job.machine)!r}: gives {what}")


def state_offsets(machine, tp, pts: np.ndarray, s: np.ndarray, departing: bool = False) -> np.ndarray:
    """Backlash and thermal drift (n, 3) [mm] at points ``pts`` sampled along the feed moves of ``tp`` at
    feed-path distances ``s`` [mm] (Toolpath.sample): each axis' direction along the samples, arriving
    at the point (or ``departing`` from it; steps below 1 µm ignored: a compensation's own corrections),
    the program time interpolated in the feed-path distance between the feed blocks' ends
    (block_end_times, programmed feeds)."""
    if not machine.has_state_errors() or len(pts) == 0:
        return np.zeros_like(pts)
    from netshape import machine as nm
    from netshape._core import compensation as _c

    t_end = np.asarray(_c.block_end_times(tp), dtype=float)
    feed = [i for i, b in enumerate(tp.blocks) if b.kind.name != "rapid"]
    dist = np.cumsum([tp.blocks[i].length() for i in feed])
    t = np.interp(s, np.concatenate([[0.0], dist]), np.concatenate([[0.0], t_end[feed]]))
    if departing:
        d = nm.approach_directions(pts[::-1], [1.0, 1.0, 1.0], 1e-3)[::-1] * -1.0
    else:
        d = nm.approach_directions(pts, [1.0, 1.0, 1.0], 1e-3)
    return nm.state_error(machine, np.ascontiguousarray(d), t)


def state_deviation(machine, tp, pts: np.ndarray, s: np.ndarray, a: np.ndarray, b: np.ndarray,
                    spacing: float) -> tuple[np.ndarray, np.ndarray]:
    """(distance [mm] of the actual tip to the nominal segments (a, b), tip error (n, 3)) at the samples.
    With backlash the direction at a point where an axis reverses is ambiguous (it arrives one way and
    leaves the other; a compensation's take-up move sits there): the state that gives the smaller
    distance is taken, arriving elsewhere."""
    from netshape import machine as nm

    e = nm.tip_error(machine, pts)
    arr = e + state_offsets(machine, tp, pts, s)
    dev = distance_to_path(pts + arr, a, b, spacing)
    if not any(ax.backlash for ax in machine.axes):
        return dev, arr
    dep = e + state_offsets(machine, tp, pts, s, departing=True)
    dev_dep = distance_to_path(pts + dep, a, b, spacing)
    return np.minimum(dev, dev_dep), np.where((dev_dep < dev)[:, None], dep, arr)


def stage_volumetric(job: Job, machine, tp_machine) -> VolumetricResult:
    """Volumetric error along the feed moves: at points every ``cutting.error_spacing_mm`` the actual tip
    p + e(p) and its distance to the nominal path (machine frame)."""
    from netshape import machine as nm

    a, b = feed_segments(tp_machine)
    pts, s = tp_machine.sample(job.cutting["error_spacing_mm"])
    if len(pts) == 0:
        raise ValueError(f"program = {str(job.program)!r}: no feed moves to predict the volumetric error of")
    check_tip_errors(job, pts, nm.tip_error(machine, pts))
    dev, e = state_deviation(machine, tp_machine, pts, s, a, b, job.cutting["error_spacing_mm"])
    return VolumetricResult(s_before_mm=s, before_mm=dev, points_mm=pts, error_vectors_mm=e)


def stage_volumetric_compensation(job: Job, machine, tp_machine, vol: VolumetricResult) -> VolumetricResult:
    """Compensate the program (machine frame) so the actual tip lands on the nominal path
    (netshape.compensation.compensate_program), then re-predict: sample the compensated program, move
    every point by the machine's error and measure its distance to the nominal path."""
    from netshape import compensation as nc

    comp, report = nc.compensate_program(machine, tp_machine, job.compensate["chord_tolerance_mm"])
    a, b = feed_segments(tp_machine)
    pts, s = comp.sample(job.cutting["error_spacing_mm"])
    vol.after_mm, _ = state_deviation(machine, comp, pts, s, a, b, job.cutting["error_spacing_mm"])
    vol.s_after_mm = s
    vol.compensated = comp
    vol.report = report.to_dict()
    return vol
