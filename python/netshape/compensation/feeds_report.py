"""What a feed schedule did: per program line the binding limit, feed, force and chip before and after;
the summary (``cycle_time_s``, ``binding``, ``max_force_N``, …); the plot of feed and force along the
path. The "after" forces are those of the written program re-simulated by
netshape.force.simulate_program (an independent check of the schedule)."""

from __future__ import annotations

import numpy as np

from .feeds import PHYSICAL, limit_name, stated

#: Columns of the per-line CSV.
CSV_COLUMNS = ("line", "binding", "pieces", "feed_before_mm_min", "feed_after_min_mm_min",
               "feed_after_max_mm_min", "force_before_N", "force_after_N", "chip_before_mm", "chip_after_mm")


def piece_of_samples(samples: dict, pieces: dict) -> np.ndarray:
    """(m) index of the piece each force sample lies in (a piece covers (start, end] of its block)."""
    shrink = 1.0 - 1e-9
    key_s = np.asarray(samples["block"], dtype=float) + np.asarray(samples["fraction"], dtype=float) * shrink
    key_p = np.asarray(pieces["block"], dtype=float) + np.asarray(pieces["end"], dtype=float) * shrink
    return np.clip(np.searchsorted(key_p, key_s - 1e-12, side="left"), 0, max(len(key_p) - 1, 0))


def chips(program, cutter, samples: dict, feed_mm_s: np.ndarray) -> np.ndarray:
    """(m) largest chip [mm] at each sample at the given feeds [mm/s]: c·max sin φ."""
    rpm = np.asarray(samples["spindle_rpm"], dtype=float)
    c = np.where(rpm > 0, feed_mm_s * 60.0 / (np.maximum(rpm, 1e-12) * cutter.flutes), 0.0)
    return c * np.asarray(samples["chip_factor"], dtype=float) * (np.asarray(samples["engaged"]) > 0)


def _max_by(keys: np.ndarray, values: np.ndarray, size: int) -> np.ndarray:
    """(size) largest value per key (0 where a key has none)."""
    out = np.zeros(size)
    if len(keys):
        np.maximum.at(out, keys, values)
    return out


def per_line(program, cutter, samples: dict, pieces: dict, after_forces) -> list[dict]:
    """One row per program line with feed pieces (CSV_COLUMNS). ``after_forces``: (line, peak resultant [N])
    arrays of the re-simulated written program, its samples' program lines."""
    blocks = program.blocks
    b_line = np.array([int(b.line) for b in blocks], dtype=np.int64)
    b_feed = np.array([float(b.feed) for b in blocks])
    p_block = np.asarray(pieces["block"], dtype=np.int64)
    s_block = np.asarray(samples["block"], dtype=np.int64)
    p_line, s_line = b_line[p_block], b_line[s_block]
    a_line, a_force = after_forces
    size = int(max(b_line.max(initial=0), np.max(a_line, initial=0))) + 1
    k = piece_of_samples(samples, pieces)
    feed = np.asarray(pieces["feed"], dtype=float)
    chip_b = chips(program, cutter, samples, b_feed[s_block])
    chip_a = chips(program, cutter, samples, feed[k]) if len(k) else chip_b
    force_b = _max_by(s_line, np.asarray(samples["force"], dtype=float), size)
    force_a = _max_by(np.asarray(a_line, dtype=np.int64), np.asarray(a_force, dtype=float), size)
    cb, ca = _max_by(s_line, chip_b, size), _max_by(s_line, chip_a, size)
    capped = pieces.get("capped", np.zeros(len(feed), dtype=bool))
    order = np.lexsort((feed, p_line))  # by line, slowest piece first
    rows = []
    starts = np.flatnonzero(np.r_[True, np.diff(p_line[order]) != 0])
    ends = np.r_[starts[1:], len(order)]
    for i0, i1 in zip(starts, ends):
        ps = order[i0:i1]
        low, ln = ps[0], int(p_line[ps[0]])
        rows.append({
            "line": ln,
            "binding": "acceleration" if capped[low] else limit_name(pieces["binding"][low]),
            "pieces": int(len(ps)),
            "feed_before_mm_min": float(b_feed[p_block[low]] * 60.0),
            "feed_after_min_mm_min": float(feed[ps].min() * 60.0),
            "feed_after_max_mm_min": float(feed[ps].max() * 60.0),
            "force_before_N": float(force_b[ln]),
            "force_after_N": float(force_a[ln]),
            "chip_before_mm": float(cb[ln]),
            "chip_after_mm": float(ca[ln]),
        })
    return rows


def summary(program_path, output_path, limits, pieces: dict, rows: list[dict], cycle_before: float,
            cycle_after: float, samples: dict, after_forces, after_deflection: dict | None = None) -> dict:
    """The summary JSON: ``cycle_time_s`` {original, optimized}, ``binding`` (pieces per limit),
    ``max_force_N`` {original, optimized}, ``max_chip_mm`` {original, optimized}, the limits stated,
    counts, and ``check``: per stated force, deflection or wall-error limit the largest re-simulated
    value and its ratio (``after_deflection``: {limit key: largest re-simulated value [mm]})."""
    names = ["acceleration" if c else limit_name(b) for b, c in
             zip(pieces["binding"], pieces.get("capped", np.zeros(len(pieces["binding"]), bool)))]
    binding = {n: 0 for n in [*(k for k in PHYSICAL if k in stated(limits)), "max_feed_mm_min"]}
    for n in names:
        binding[n] = binding.get(n, 0) + 1
    force_after = np.asarray(after_forces[1], dtype=float)
    max_after = float(force_after.max()) if len(force_after) else 0.0
    out = {
        "program": str(program_path),
        "output": str(output_path),
        "limits": stated(limits),
        "blocks": len(rows),
        "pieces": int(len(pieces["feed"])),
        "split_lines": int(sum(1 for r in rows if r["pieces"] > 1)),
        "cycle_time_s": {"original": float(cycle_before), "optimized": float(cycle_after)},
        "saving_percent": float(100.0 * (1.0 - cycle_after / cycle_before)) if cycle_before > 0 else 0.0,
        "binding": binding,
        "max_force_N": {"original": float(np.max(samples["force"], initial=0.0)), "optimized": max_after},
        "max_chip_mm": {"original": max((r["chip_before_mm"] for r in rows), default=0.0),
                        "optimized": max((r["chip_after_mm"] for r in rows), default=0.0)},
    }
    resimulated = {"max_force_N": max_after, **(after_deflection or {})}
    check = {key: {"limit": out["limits"][key], "resimulated_max": v, "ratio": v / out["limits"][key]}
             for key, v in resimulated.items() if key in out["limits"]}
    if check:
        out["check"] = check
    return out


def plot_feeds(samples: dict, pieces: dict, after_positions, after_forces, program, *, title: str = ""):
    """Feed (before/after) and force (before/after, re-simulated) along the path; a matplotlib Figure."""
    import matplotlib

    matplotlib.use("Agg", force=False)
    import matplotlib.pyplot as plt

    def dist(p):
        p = np.asarray(p, dtype=float)
        return np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(p, axis=0), axis=1))]) if len(p) else p

    s = dist(samples["positions"])
    k = piece_of_samples(samples, pieces)
    before = np.array([float(program.blocks[int(b)].feed) * 60 for b in samples["block"]])
    fig, (a1, a2) = plt.subplots(2, 1, figsize=(9, 5.5), sharex=True)
    a1.plot(s, before, lw=1, label="programmed")
    if len(k):
        a1.plot(s, np.asarray(pieces["feed"])[k] * 60, lw=1, label="scheduled")
    a1.set_ylabel("feed [mm/min]")
    a1.legend(loc="best", fontsize=8)
    a2.plot(s, samples["force"], lw=1, label="programmed")
    a2.plot(dist(after_positions), after_forces, lw=1, label="scheduled (re-simulated)")
    a2.set_ylabel("peak |F| [N]")
    a2.set_xlabel("path through the force samples [mm]")
    a2.legend(loc="best", fontsize=8)
    if title:
        a1.set_title(title, fontsize=9)
    fig.tight_layout()
    return fig
