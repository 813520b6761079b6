"""The job's ``[optimize]`` table: feed scheduling from the physics (docs/feeds.md) on the job's program,
tool, stock, coefficients and feed-plan limits. Keys are those of ``netshape feeds``
(netshape.compensation.feeds.LIMIT_KEYS and SPLIT_KEYS); the scheduled program is written as
``<program>_feeds.ngc`` and its summary under ``summary["optimize"]``."""

from __future__ import annotations

from typing import Any


def optimize_from_dict(src: str, v: Any) -> dict:
    """The validated ``[optimize]`` table (the limits checked now, so a bad key fails at load naming it)."""
    from netshape.compensation.feeds import feed_limits_from_dict

    try:
        feed_limits_from_dict(v, source="optimize")
    except ValueError as exc:
        raise ValueError(f"{src}: {exc}") from None
    return dict(v)


def check_optimize_needs(src: str, optimize: dict | None, limits, coefficients) -> None:
    """``[optimize]`` needs the feed plan's ``[limits]`` and the cutting ``coefficients``."""
    if optimize is None:
        return
    if limits is None:
        raise ValueError(f"{src}: limits: missing: [optimize] needs [limits] vmax_mm_s, amax_mm_s2 "
                         "(the feed plan)")
    if coefficients is None:
        raise ValueError(f"{src}: coefficients: missing: [optimize] needs cutting coefficients")


def stage_optimize(job, stock0) -> tuple[dict, str, object]:
    """(summary, scheduled program text, FeedsResult) of the job's program under its ``[optimize]``
    limits."""
    import math

    from netshape import motion as nmo
    from netshape._text import read_text
    from netshape.compensation.feeds import feed_limits_from_dict
    from netshape.compensation.feeds_run import optimize_program

    from .program import job_work_offsets
    from .stages import coefficients_for, make_cutter

    from netshape.cutter import spindle_limits

    cutter = make_cutter(job.tool)
    # the tool's spindle limits apply unless [optimize] states its own
    limits, split = feed_limits_from_dict(spindle_limits(job.tool) | job.optimize, source="optimize")
    lim = job.limits
    axis = nmo.AxisLimits(lim["vmax_mm_s"], lim["amax_mm_s2"], lim.get("jmax_mm_s3", [math.inf] * 3))
    options = nmo.make_options(lim["rule"], ts1=lim["ts1_s"], ts2=lim["ts2_s"], lookahead=lim["lookahead"],
                               tolerance=lim["tolerance_mm"])
    c = job.cutting
    sampling = {"step": c["step_mm"], "samples_per_revolution": c["samples_per_revolution"],
                "disk_height": c["disk_height_mm"], "spindle_rpm": c["spindle_rpm"] or 0.0}
    coeffs = coefficients_for(job, cutter)
    res = optimize_program(read_text(job.program), str(job.program), stock0, cutter, coeffs, limits,
                           axis_limits=axis, plan_options=options, split=split, sampling=sampling,
                           work_offsets=job_work_offsets(job))
    return res.summary, res.text, res


def plot_optimize(res, title: str):
    """The feed and force plot of a FeedsResult (netshape.compensation.feeds_report.plot_feeds)."""
    from netshape.compensation.feeds_report import plot_feeds

    return plot_feeds(res.schedule.samples, res.pieces, res.after.positions, res.after.peak_resultant,
                      res.program, title=title)
