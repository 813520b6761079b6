"""The one configuration layer (netshape._config): every reader refuses a bad value as
``SOURCE: KEY = VALUE: WHY`` in the error type the area chose; the job's corner rules are the plan's."""

from __future__ import annotations

import sys

import pytest

from netshape import _config as cfg

if sys.version_info >= (3, 11):
    import tomllib
else:  # pragma: no cover
    import tomli as tomllib


class AreaError(ValueError):
    pass


@pytest.mark.parametrize("value, kw, why", [
    ("3", {}, "must be a finite number"), (True, {}, "must be a finite number"),
    (float("nan"), {}, "must be a finite number"), (0, {"positive": True}, "must be positive"),
    (-1.5, {"nonneg": True}, "must be ≥ 0")])
def test_number_names_source_key_and_value(value, kw, why):
    with pytest.raises(AreaError) as exc:
        cfg.number("f.toml", "a.b_mm", value, error=AreaError, **kw)
    assert str(exc.value) == f"f.toml: a.b_mm = {value!r}: {why}"
    assert cfg.number("f.toml", "k", 2, positive=True) == 2.0


def test_readers_without_source_and_for_missing_keys():
    with pytest.raises(ValueError, match=r"^k = 'x': must be a finite number$"):
        cfg.number(None, "k", "x")
    assert str(cfg.field_error("f.toml", "k", cfg.MISSING, "missing")) == "f.toml: k: missing"
    with pytest.raises(ValueError, match=r"^f.toml: t.zz = 1: unknown key \(known: a, b\)$"):
        cfg.check_keys("f.toml", "t", {"zz": 1}, {"b", "a"})
    with pytest.raises(ValueError, match=r"v\[1\] = 'y'"):
        cfg.vec3("f.toml", "v", [1, "y", 3])
    with pytest.raises(ValueError, match="must be one of a, b"):
        cfg.one_of("f.toml", "r", "c", ("a", "b"))


def test_job_takes_the_corner_rules_of_plan(tmp_path):
    """The job's limits.rule accepts what netshape.motion.plan does, smooth included (it lacked smooth)."""
    from netshape.job import JobError, job_from_dict
    from netshape.motion import PLAN_RULES

    from .job.conftest import DEMO

    doc = tomllib.loads((DEMO / "job.toml").read_text())
    for rule in PLAN_RULES:
        doc["limits"]["rule"] = rule
        assert job_from_dict(doc, source="job.toml", base_dir=DEMO).limits["rule"] == rule
    doc["limits"]["rule"] = "fast"
    with pytest.raises(JobError, match="job.toml: limits.rule = 'fast': must be one of .*, blend, smooth$"):
        job_from_dict(doc, source="job.toml", base_dir=DEMO)


def test_job_feed_plan_with_the_smooth_rule():
    """limits.rule = "smooth": the job's feed plan is netshape.motion.plan's smoothing then blend."""
    from netshape.job import job_from_dict
    from netshape.job.program import stage_program
    from netshape.job.stages import stage_feed_plan

    from .job.conftest import DEMO

    doc = tomllib.loads((DEMO / "job.toml").read_text())
    doc["limits"]["rule"] = "smooth"
    job = job_from_dict(doc, source="job.toml", base_dir=DEMO)
    traj = stage_feed_plan(job, stage_program(job).toolpath)
    assert traj.stats["cycle_time_s"] > 0 and "runs_smoothed" in traj.stats
