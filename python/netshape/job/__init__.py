"""netshape.job — the main job end to end (`netshape run job.toml`, `netshape demo`, `netshape batch`).

    import netshape.job as nj
    job = nj.load_job("job.toml")          # validated; JobError (a ValueError) names the bad key
    summary = nj.run_job(job, "out/")      # stages, compensated program, summary.json, report.html

The job file's keys and units are in docs/job.md. Batch studies over a parameter grid on Dask:
:func:`netshape.job.batch.run_batch` (needs the ``batch`` extra: ``pip install netshape[batch]``).
"""

from __future__ import annotations

from .run import StageFailed, run_job, stage_names, versions
from .spec import COMPENSATIONS, PREDICTIONS, WORK_OFFSETS, Job, JobError, job_from_dict, load_job, set_dotted

__all__ = ["COMPENSATIONS", "Job", "JobError", "PREDICTIONS", "StageFailed", "WORK_OFFSETS", "job_from_dict",
           "load_job", "run_job", "set_dotted", "stage_names", "versions"]
