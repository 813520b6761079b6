"""Virtual measurements of a machine: what a volumetric check would record on a machine whose true
errors are a machine TOML (tests, bench/, examples/volumetric_learning.py), and the tool tip's error
when a (compensated) program runs on it.

A grid is measured along a serpentine: X moves along each line, alternately + and −; the
``direction`` column records that approach direction (the bundle applies it to every axis with
backlash, docs/discrepancy.md), ``t_s`` the time of each point (``dt_s`` apart).
"""

from __future__ import annotations

import copy
import os
from pathlib import Path

import numpy as np

from netshape._core import compensation as _c
from netshape._core import machine as _m
from netshape.machine import machine_from_dict, state_error


def serpentine(lo, hi, counts) -> tuple[np.ndarray, np.ndarray]:
    """Grid points (n, 3) [mm] from ``lo`` to ``hi`` (3,) with ``counts`` (nx, ny, nz) levels, X
    fastest and alternating; and the X approach direction (n,) (±1)."""
    xs, ys, zs = (np.linspace(a, b, int(n)) for a, b, n in zip(lo, hi, counts))
    pts, dirs, s = [], [], 1
    for z in zs:
        for y in ys:
            for x in xs if s > 0 else xs[::-1]:
                pts.append((x, y, z))
                dirs.append(s)
            s = -s
    return np.array(pts, float), np.array(dirs, float)


def _machine(path: Path, tool_length: float | None = None):
    from netshape._text import read_toml

    doc = read_toml(path)
    if tool_length is not None:
        doc = copy.deepcopy(doc)
        doc.setdefault("tool", {})["length_mm"] = float(tool_length)
    return machine_from_dict(doc, path.parent, str(path))


def measure_grid(truth: str | os.PathLike, folder: str | os.PathLike, *, model: str | os.PathLike | None = None,
                 lo=(-200.0, -150.0, -200.0), hi=(200.0, 150.0, 0.0), counts=(17, 5, 3),
                 tool_lengths=(100.0, 220.0), dt_s: float = 20.0, noise_mm: float = 5e-4, seed: int = 0) -> Path:
    """Write a volumetric_error bundle to ``folder``: the grid measured on the machine ``truth``
    (TOML) once per tool length, errors = tip error + backlash and thermal drift (machine/state_error)
    + Gaussian noise σ = ``noise_mm``. The manifest's ``[model]`` holds the polynomial components and
    constants of the machine ``model`` (the current model), if given."""
    from .bundle import VOLUMETRIC_MODEL_KEYS
    from .volumetric_machine import MachineModel

    folder = Path(folder)
    folder.mkdir(parents=True, exist_ok=True)
    truth = Path(truth)
    rng = np.random.default_rng(seed)
    pts, dirs = serpentine(lo, hi, counts)
    exps, t0 = [], 0.0
    for i, L in enumerate(tool_lengths):
        m = _machine(truth, L)
        t = t0 + dt_s * np.arange(len(pts))
        t0 = t[-1] + dt_s
        e = np.asarray(_m.tip_error(m, pts)) + state_error(m, np.repeat(dirs[:, None], 3, axis=1), t)
        e = e + rng.normal(0.0, noise_mm, e.shape)
        name = f"grid{i + 1}.csv"
        np.savetxt(folder / name, np.column_stack([pts, e, t, dirs]), delimiter=",", fmt="%.10g", comments="",
                   header="x_mm,y_mm,z_mm,ex_mm,ey_mm,ez_mm,t_s,direction")
        exps.append(f'[[experiment]]\nfile = "{name}"\ntool_length_mm = {float(L)!r}\n')
    base = _machine(truth)
    axes = "XYZ"
    lines = ['kind = "volumetric_error"', "[machine]",
             f"tool_side = {[axes[k] for k in base.tool_chain]!r}".replace("'", '"'),
             f"workpiece_side = {[axes[k] for k in base.workpiece_chain]!r}".replace("'", '"'),
             f"tool_length_mm = {float(tool_lengths[0])!r}", "[model]"]
    if model is not None:
        for k, v in MachineModel(model).initial_model().items():
            if k in VOLUMETRIC_MODEL_KEYS:
                lines.append(f"{k} = [{', '.join(repr(float(c)) for c in v)}]")
    (folder / "manifest.toml").write_text("\n".join(lines) + "\n\n" + "\n".join(exps))
    return folder


def program_tip_errors(truth, commanded, nominal) -> np.ndarray:
    """The tool tip's error (n, 3) [mm] at the end of each motion block of ``nominal`` (a Toolpath)
    when ``commanded`` (its compensation, or ``nominal`` itself) runs on the machine ``truth`` (a
    Machine or TOML path): actual tip − nominal end point, the actual tip c + e(c) + s(d, t) at the
    block's commanded end c, with d each axis' approach direction along the nominal path and t from
    the programmed feeds (the state model of compensation/program_compensation.hpp)."""
    m = truth if isinstance(truth, _m.Machine) else _machine(Path(truth))
    nb = list(nominal.blocks)
    nom = np.array([b.end for b in nb], float).reshape(-1, 3)
    path = np.vstack([np.asarray(nb[0].start, float)[None, :], nom])
    d = _m.approach_directions(path)[1:]
    t = np.asarray(_c.block_end_times(nominal), float)
    last = {}  # source line → end of its last commanded block (take-up moves and pieces come first)
    for b in commanded.blocks:
        last[b.line] = np.asarray(b.end, float)
    c = np.array([last[b.line] for b in nb], float)
    return c + np.asarray(_m.tip_error(m, c)) + state_error(m, d, t) - nom


def _rms(e) -> float:
    e = np.asarray(e, float)
    return float(np.sqrt(np.mean(np.sum(e * e, axis=1)))) if len(e) else 0.0


def closed_loop(truth, machine, folder, program, *, seed: int = 0, chord_tolerance: float = 5e-4,
                effects=None, **grid) -> dict:
    """One round of the learning loop on a virtual machine: measure the grid on ``truth`` (TOML,
    :func:`measure_grid` with ``grid``), diagnose it against ``machine`` (TOML), write the updated
    machine to ``folder/machine_updated.toml``, diagnose again against it, and run ``program`` (a
    Toolpath) compensated with either machine on the truth. ``effects``: the catalogue entries both
    diagnoses consider (default all). Returns {diagnosis, again, updated,
    error_original_mm, error_updated_mm} (rms over the block ends of the tip error, mm)."""
    from netshape.compensation import compensate_program
    from netshape.machine import load_machine

    from .workflow import diagnose

    folder = Path(folder)
    bundle = measure_grid(truth, folder / "bundle", model=machine, seed=seed, **grid)
    d = diagnose(bundle, machine=machine, effects=effects)
    updated = folder / "machine_updated.toml"
    updated.write_text(d.apply(Path(machine)))
    again = diagnose(bundle, machine=updated, effects=effects)
    err = {}
    for key, m in (("error_original_mm", machine), ("error_updated_mm", updated)):
        cmd, _ = compensate_program(load_machine(m), program, chord_tolerance=chord_tolerance)
        err[key] = _rms(program_tip_errors(truth, cmd, program))
    return {"diagnosis": d, "again": again, "updated": updated, **err}
