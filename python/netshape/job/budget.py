"""The work a job's numbers imply, checked before any stage runs (docs/job.md, Limits).

From the program's block arrays (read once, fast) and the job's keys:

- feeds after ``cutting.feed_scale`` must stay within the writer's F ≤ 1e8 mm/min
  (netshape.toolpath.max_feed_mm_per_min);
- the feed per tooth F / (S · flutes) that ``cutting.spindle_rpm`` (or a program S word) implies must be
  finite and below the tool radius (a chip thicker than the tool is no cut, and its forces are inf);
- force samples (feed length / ``cutting.step_mm``), error samples (feed length /
  ``cutting.error_spacing_mm``) and feed-plan samples (the cycle time's lower bound / ``limits.ts2_s``)
  must stay within the budgets of netshape._budget.

Each refusal is a JobError naming the job file, the key and the value.
"""

from __future__ import annotations

import math
import warnings

import numpy as np

from netshape import _budget as B

from .spec import Job, JobError


def _arrays(job: Job) -> dict:
    from netshape import toolpath as tpm

    with warnings.catch_warnings():
        warnings.simplefilter("ignore", tpm.GcodeWarning)
        a = tpm.read_gcode_arrays(job.program, arcs="keep")
    return {k: np.asarray(v) for k, v in a.items()}


def _refuse(job: Job, key: str, value, estimate: float, limit: float, what: str, hint: str) -> None:
    try:
        B.refuse_over(f"{job.source}: {key} = {value!r}", estimate, limit, what, hint)
    except ValueError as exc:
        raise JobError(str(exc)) from None


def check_job_work(job: Job) -> None:
    """Raise JobError when a job's numbers ask for more work than the budgets allow (module docstring)."""
    from netshape.toolpath import block_lengths, max_feed_mm_per_min

    a = _arrays(job)
    if len(a["kind"]) == 0:
        return
    c, p = job.cutting, job.predict
    scale = c["feed_scale"]
    feed = a["feed"] * scale  # [mm/s]
    cutting = a["kind"] != 0
    lengths = block_lengths(a)
    if feed.size and np.max(feed, initial=0.0) > max_feed_mm_per_min / 60.0:
        k = int(np.argmax(feed))
        key, value = ("cutting.feed_scale", scale) if scale != 1.0 else (f"program line {int(a['line'][k])} F",
                                                                          float(a["feed"][k]) * 60.0)
        raise JobError(f"{job.source}: {key} = {value!r}: gives F {feed[k] * 60.0:.3g} mm/min on line "
                       f"{int(a['line'][k])} of {job.program.name}, over the largest feed written, "
                       f"F {max_feed_mm_per_min:g} mm/min")
    _check_feed_per_tooth(job, a, feed, cutting)
    feed_length = float(np.sum(lengths[cutting]))
    n_cut = int(np.count_nonzero(cutting))
    if p["forces"] or p["deflection"]:
        _refuse(job, "cutting.step_mm", c["step_mm"], feed_length / c["step_mm"] + n_cut, B.MAX_JOB_STEPS,
                f"force samples along {feed_length:g} mm of feed moves", "use a larger step")
    if p["volumetric"] or p["deflection"]:
        _refuse(job, "cutting.error_spacing_mm", c["error_spacing_mm"], feed_length / c["error_spacing_mm"] + n_cut,
                B.MAX_JOB_ERROR_SAMPLES, f"error samples along {feed_length:g} mm of feed moves",
                "use a larger spacing")
    if p["feed_plan"] and job.limits is not None:
        from netshape.motion import AxisLimits
        from netshape.motion.budget import min_motion_time

        lim = job.limits
        limits = AxisLimits(lim["vmax_mm_s"], lim["amax_mm_s2"], lim.get("jmax_mm_s3", [math.inf] * 3))
        bound = min_motion_time({**a, "feed": feed}, limits)
        if bound.time_s / 1e-4 <= B.MAX_PLAN_SAMPLES:  # fits at a 0.1 ms period: the period asks for it
            key, value = "limits.ts2_s", lim["ts2_s"]
        elif bound.limit != "feed":
            key = {"vmax": "limits.vmax_mm_s", "amax": "limits.amax_mm_s2", "jmax": "limits.jmax_mm_s3"}[bound.limit]
            value = lim[key.split(".")[1]]
        elif scale != 1.0:
            key, value = "cutting.feed_scale", scale
        else:
            key, value = "program", str(job.program)
        _refuse(job, key, value, bound.time_s / lim["ts2_s"], B.MAX_PLAN_SAMPLES,
                f"feed-plan samples (at least {bound.time_s:.3g} s of motion, one every limits.ts2_s)",
                "the plan would not fit in memory")


def _check_feed_per_tooth(job: Job, a: dict, feed: np.ndarray, cutting: np.ndarray) -> None:
    c = job.cutting
    if c["feed_per_tooth_mm"] is not None or not np.any(cutting):
        return
    flutes = int(job.tool.get("flutes", 1) or 1)
    radius = 0.5 * float(job.tool.get("diameter_mm", math.inf))
    rpm = c["spindle_rpm"]
    with np.errstate(divide="ignore", invalid="ignore", over="ignore"):
        if rpm is not None:
            fz = feed[cutting] / (rpm * flutes)
        else:  # the program's S words; blocks without a speed are another check's business
            s = np.abs(a["spindle_rpm"][cutting])
            fz = np.where(s > 0, feed[cutting] / (s * flutes), 0.0)
    bad = ~(fz < radius) if math.isfinite(radius) else ~np.isfinite(fz)
    if not np.any(bad):
        return
    k = int(np.flatnonzero(cutting)[np.argmax(bad)])
    worst = float(fz[np.argmax(bad)])
    key, value = (("cutting.spindle_rpm", rpm) if rpm is not None
                  else (f"program line {int(a['line'][k])} S", float(abs(a['spindle_rpm'][k]))))
    raise JobError(f"{job.source}: {key} = {value!r}: gives a feed per tooth of {worst:.3g} mm at F "
                   f"{feed[k] * 60.0:.6g} mm/min with {flutes} flutes (line {int(a['line'][k])}), not below the "
                   f"tool radius {radius:g} mm")
