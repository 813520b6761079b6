"""Run a job: the stages in order (each timed), then the outputs, each written whole or not at all.

Stages: program → stock (box/heights + pre-cuts) → cut (Z-map removal) → forces → deflection (wall
error; compensation) → volumetric (error; compensation) → feed plan (original and compensated) →
outputs (compensated program, summary.json, Z-map STL, PNG plots, report.html).

The output folder is checked before the first stage (a file, under a file, not writable: refused).
A stage that raises stops the run with :class:`StageFailed` naming the stage; the outputs are written
all or nothing (each to a temporary file, all renamed into place at the end), so a failed run leaves
the folder as it was. Files of an earlier run in the same folder that this run does not write are
removed when the earlier summary.json lists them (netshape wrote them) and reported otherwise
(``summary["stale_files"]`` and a warning on stderr).
"""

from __future__ import annotations

import platform
import sys
import time
from pathlib import Path

import numpy as np

from . import program as pg
from . import stage_volumetric as sv
from . import stages as st
from .spec import Job
from .stage_deflection import stage_deflection
from .warnings import outside_travel


class StageFailed(Exception):
    """A stage of the job failed; ``stage`` names it, ``cause`` is the original exception."""

    def __init__(self, stage: str, cause: BaseException):
        super().__init__(f"stage {stage} failed: {' '.join(str(cause).split()) or type(cause).__name__}")
        self.stage = stage
        self.cause = cause


def versions() -> dict:
    import matplotlib
    import scipy

    import netshape

    return {"netshape": netshape.__version__, "python": platform.python_version(), "numpy": np.__version__,
            "scipy": scipy.__version__, "matplotlib": matplotlib.__version__}


class _Stages:
    """Times stages, advances the progress bar and turns an exception into StageFailed."""

    def __init__(self, names: list[str], quiet: bool):
        self.times: dict[str, float] = {}
        self.bar = None
        if not quiet:
            from tqdm import tqdm

            self.bar = tqdm(total=len(names), unit="stage", file=sys.stderr, leave=True,
                            bar_format="{desc:<44}{bar}| {n_fmt}/{total_fmt} [{elapsed}]")

    def run(self, name: str, fn, *args, **kwargs):
        if self.bar is not None:
            self.bar.set_description_str(f"netshape run: {name}")
        t0 = time.perf_counter()
        try:
            out = fn(*args, **kwargs)
        except (KeyboardInterrupt, SystemExit):
            raise
        except BaseException as exc:
            self.close()
            raise StageFailed(name, exc) from exc
        self.times[name] = round(time.perf_counter() - t0, 4)
        if self.bar is not None:
            self.bar.update(1)
        return out

    def skip(self, name: str) -> None:
        """A stage of the list that has nothing to do in this run: no time, the bar moves on."""
        self.times[name] = 0.0
        if self.bar is not None:
            self.bar.update(1)

    def sub_progress(self, name: str, total: int, unit: str):
        """A callable ``f(done)`` that shows the progress inside a long stage on a second bar (None when
        quiet or when the stage is short)."""
        if self.bar is None or total <= 1000:
            return None
        from tqdm import tqdm

        self.sub = tqdm(total=total, unit=unit, file=sys.stderr, leave=False, desc=f"  {name}")

        def update(done: int) -> None:
            self.sub.update(done - self.sub.n)

        return update

    def close_sub(self):
        if getattr(self, "sub", None) is not None:
            self.sub.close()
            self.sub = None

    def close(self):
        self.close_sub()
        if self.bar is not None:
            self.bar.close()
            self.bar = None


def _check_results(job: Job, summary: dict) -> None:
    """Refuse a summary holding NaN/inf, naming the job key its first such figure comes from."""
    from netshape._json import NonFiniteResult, first_non_finite

    found = first_non_finite(summary)
    if not found:
        return
    key = found[0]
    causes = (("errors.volumetric", f"machine = {str(job.machine)!r} (error_scale = {job.error_scale!r})"),
              ("volumetric_compensation", f"machine = {str(job.machine)!r} (error_scale = {job.error_scale!r})"),
              ("forces", f"cutting.spindle_rpm = {job.cutting['spindle_rpm']!r} (feed_per_tooth_mm = "
                         f"{job.cutting['feed_per_tooth_mm']!r})"),
              ("errors.deflection", f"tool.stick_out_mm = {job.tool.get('stick_out_mm')!r} (diameter_mm = "
                                    f"{job.tool.get('diameter_mm')!r})"),
              ("cycle_time_s", "limits"))
    cause = next((c for prefix, c in causes if key.startswith(prefix)), None)
    raise NonFiniteResult(key, found[1], f"{job.source}: {cause}" if cause else str(job.source))


def stage_names(job: Job) -> list[str]:
    p, c = job.predict, job.compensate
    names = ["program", "stock", "cut"]
    if p["forces"]:
        names.append("forces")
    if p["deflection"]:
        names.append("deflection")
    if p["volumetric"]:
        names.append("volumetric")
    if c["volumetric"]:
        names.append("volumetric_compensation")
    if p["feed_plan"]:
        names += ["feed_plan", "feed_plan_compensated"]
    if job.optimize is not None:
        names.append("optimize")
    names.append("report")
    return names


def _owned_earlier(folder: Path) -> set[str]:
    """Files an earlier run wrote into ``folder``, as its summary.json lists them (empty if none, or if
    that summary.json is not one netshape wrote)."""
    try:
        from netshape._text import read_json

        doc = read_json(folder / "summary.json")
        files = doc.get("files", {})
        ours = "netshape" in doc.get("versions", {})
    except (OSError, ValueError, AttributeError, TypeError):
        return set()
    if not ours or not isinstance(files, dict):
        return set()
    return {v for v in files.values() if isinstance(v, str) and v and Path(v).name == v}


def _tidy_folder(folder: Path, earlier: set[str], written: set[str]) -> None:
    """Remove the files an earlier run wrote (``earlier``) that this run did not write."""
    for name in sorted(earlier - written):
        p = folder / name
        if p.is_file():
            p.unlink()


def run_job(job: Job, out: str | Path | None = None, *, quiet: bool = True, out_option: str = "--out") -> dict:
    """Run ``job`` writing into ``out`` (default ``job.output``); returns the summary (also in
    summary.json). Raises ValueError naming ``out`` (``out_option``) or the job's ``output`` key when the
    folder cannot be written, before any stage runs (and the work its numbers imply, job.budget); StageFailed naming the stage that failed."""
    from netshape._atomic import all_or_nothing, check_output_folder, make_output_folder

    from .budget import check_job_work

    t_start = time.perf_counter()
    check_job_work(job)  # before anything is written: the work the job's numbers imply
    folder = Path(out) if out is not None else job.output
    shown = out_option if out is not None else f"{job.source}: output"
    check_output_folder(folder, shown)
    S = _Stages(stage_names(job), quiet)
    p, c = job.predict, job.compensate
    status: dict[str, str] = {}

    prog = S.run("program", pg.stage_program, job)
    stock0 = S.run("stock", st.stage_stock, job)
    warnings: list[dict] = []  # trouble met while running: {"kind", "line", "message"}
    zfinal, removed = S.run("cut", st.stage_cut, job, stock0, prog, warnings)
    if any(w["kind"] == "rapid_through_material" for w in warnings):
        status["cut"] = "rapid_through_material"

    forces = None
    if p["forces"]:
        forces = S.run("forces", st.stage_forces, job, stock0, prog, progress=S.sub_progress(
            "forces", len(prog.toolpath.blocks), "block"))
        S.close_sub()

    defl = None
    if p["deflection"]:
        defl = S.run("deflection", stage_deflection, job, stock0, prog, compensate=c["deflection"])
        status["deflection"] = defl.status
        if defl.available and defl.after_mm is None:
            defl.after_mm = defl.before_mm  # program not changed for deflection: the same error after
    # the program handed to the volumetric stage (program coordinates): deflection-compensated where that
    # was applied (it works in the stock's frame, whose offsets the tool path carries)
    target = defl.compensated.to_program() if (defl is not None and defl.compensated is not None) else None
    target_prog = pg.Program(toolpath=target, offsets=prog.offsets) if target is not None else prog

    vol = None
    machine = None
    compensated_program = None   # Toolpath, program coordinates
    if p["volumetric"]:
        def _volumetric():
            m = sv.load_job_machine(job)
            tp_m = pg.machine_frame_toolpath(prog)
            return m, sv.stage_volumetric(job, m, tp_m), outside_travel(m, tp_m)

        machine, vol, outside = S.run("volumetric", _volumetric)
        warnings.extend(outside)
        # outside the travel the machine's error is extrapolated and compensation would be refused
        status["volumetric"] = "outside_travel" if outside else "ok"
        if c["volumetric"] and outside:
            S.skip("volumetric_compensation")
            vol.after_mm, vol.s_after_mm = vol.before_mm, vol.s_before_mm
            vol.report = {"status": "skipped", "reason": outside[0]["message"]}
        elif c["volumetric"]:
            target_machine = pg.machine_frame_toolpath(target_prog)
            vol = S.run("volumetric_compensation", sv.stage_volumetric_compensation, job, machine,
                        target_machine, vol)
            compensated_program = vol.compensated.to_program()
        else:
            vol.after_mm, vol.s_after_mm = vol.before_mm, vol.s_before_mm
    if compensated_program is None and target is not None:
        compensated_program = target

    traj = traj_c = None
    if p["feed_plan"]:
        traj = S.run("feed_plan", st.stage_feed_plan, job, prog.toolpath)
        traj_c = (S.run("feed_plan_compensated", st.stage_feed_plan, job, compensated_program)
                  if compensated_program is not None else None)
        if traj_c is None:
            S.skip("feed_plan_compensated")

    optimized = None
    if job.optimize is not None:
        from .optimize import stage_optimize

        optimized = S.run("optimize", stage_optimize, job, stock0)

    # ---- summary
    errors = {
        "deflection": st.error_stats(*((defl.before_mm, defl.after_mm) if defl is not None and defl.available
                                       else (None, None))),
        "volumetric": st.error_stats(*((vol.before_mm, vol.after_mm) if vol is not None else (None, None))),
        "total": st.error_stats(
            st.total_error(defl, vol, "before", machine, lambda p: np.asarray(p) + prog.offsets[0]),
            st.total_error(defl, vol, "after")),
    }
    applied = job.compensations
    if defl is not None and defl.compensated is None and "deflection" in applied:
        applied = [a for a in applied if a != "deflection"]
    if vol is not None and vol.compensated is None and "volumetric" in applied:
        applied = [a for a in applied if a != "volumetric"]
    stem = job.program.stem
    files = {"summary": "summary.json", "report": "report.html"}
    if compensated_program is not None:
        files["compensated_program"] = f"{stem}_compensated.ngc"
    if job.report["zmap_stl"]:
        files["zmap_stl"] = "zmap.stl"
    if optimized is not None:
        files["optimized_program"] = f"{stem}_feeds.ngc"
    summary = {
        "job": {"name": job.name, "source": str(job.source), "program": str(job.program),
                "predictions": [k for k, v in p.items() if v], "compensations": applied,
                "requested_compensations": job.compensations},
        "errors": errors,
        "cycle_time_s": {"original": traj.stats["cycle_time_s"] if traj is not None else None,
                         "compensated": (traj_c.stats["cycle_time_s"] if traj_c is not None
                                         else (traj.stats["cycle_time_s"] if traj is not None else None))},
        "run_time_s": S.times,
        "stages": status,
        "removed_volume_mm3": removed,
        "warnings": warnings,
        "versions": versions(),
        "files": files,
    }
    if defl is not None:
        summary["deflection"] = {"status": defl.status, "reason": defl.reason, **defl.info,
                                 "levels_mm": defl.levels_mm, "unconverged_points": defl.unconverged_points}
    if forces is not None:
        summary["forces"] = {"max_peak_resultant_N": float(np.max(forces.peak_resultant, initial=0.0)),
                             "samples": int(len(forces.peak_resultant))}
    if machine is not None:
        from netshape.machine import machine_terms

        summary["machine"] = {"file": str(job.machine), "terms": machine_terms(job.machine)}
    if optimized is not None:
        summary["optimize"] = optimized[0]
    if vol is not None and vol.report:
        summary["volumetric_compensation"] = {k: v for k, v in vol.report.items() if isinstance(v, (int, float, str))}

    def _outputs():
        from netshape import toolpath as tpm
        from netshape._atomic import atomic_path, atomic_save_figure, atomic_write

        if compensated_program is not None:
            header = (f"netshape compensated {job.program.name}: {' then '.join(applied)}; "
                      f"run with the work offsets of the original")
            with atomic_write(folder / files["compensated_program"], "w", encoding=tpm.gcode_encoding(job.program),
                              errors="replace") as fh:
                fh.write(pg.write_program_text(compensated_program, header))
        if optimized is not None:
            with atomic_write(folder / files["optimized_program"], "w") as fh:
                fh.write(optimized[1])
        if job.report["zmap_stl"]:
            with atomic_path(folder / "zmap.stl") as tmp:
                zfinal.to_stl(tmp)
        from . import report as rp

        order = "compensations: " + (" → ".join(applied) or "none")
        figs = {}
        if job.report["plots"]:
            figs = {"force": rp.plot_force(forces), "wall_error": rp.plot_wall_error(defl, vol, order),
                    "volumetric": rp.plot_volumetric_map(vol), "feed": rp.plot_feed(traj, traj_c),
                    "zmap": rp.plot_zmap(zfinal)}
            if optimized is not None:
                from .optimize import plot_optimize

                figs["optimize"] = plot_optimize(optimized[2], f"{job.program.name}: feeds scheduled")
        for key, fig in figs.items():
            name = {**rp.PLOTS, **rp.OPTIMIZE_PLOT}[key]
            atomic_save_figure(fig, folder / name, dpi=job.report["dpi"])
            files[f"plot_{key}"] = name
        return rp

    _check_results(job, summary)  # no output of a run whose results are not finite
    make_output_folder(folder, shown)
    earlier = _owned_earlier(folder)
    with all_or_nothing():
        rp = S.run("report", _outputs)
        summary["run_time_s"]["report"] = S.times["report"]
        summary["run_time_s"]["total"] = round(time.perf_counter() - t_start, 4)
        written = set(files.values())
        stale = sorted(p.name for p in folder.iterdir() if p.is_file() and not p.name.startswith(".")
                       and p.name not in written and p.name not in earlier)
        if stale:
            summary["stale_files"] = stale
        shown_plots = {**rp.PLOTS, **(rp.OPTIMIZE_PLOT if optimized is not None else {})}
        rp.write_html(folder / "report.html", summary, shown_plots if job.report["plots"] else {})
        from netshape._json import write_json

        write_json(folder / "summary.json", summary, cause=str(job.source))
    _tidy_folder(folder, earlier, written)
    S.close()
    return summary
