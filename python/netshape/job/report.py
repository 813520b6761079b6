"""Report of a job run: PNG plots (matplotlib, Agg) and one self-contained HTML page that shows them
beside the numbers of ``summary.json`` (images are files next to the page; no network)."""

from __future__ import annotations

import html
import math

import numpy as np

#: File names of the report plots, in the order the page shows them.
PLOTS = {
    "force": "force.png",
    "wall_error": "wall_error.png",
    "volumetric": "volumetric_error.png",
    "feed": "feed.png",
    "zmap": "zmap.png",
}
#: The plot of the ``[optimize]`` table (feed and force along the path), written when the job has one.
OPTIMIZE_PLOT = {"optimize": "feeds.png"}


def _figure(w=8.0, h=3.6):
    from matplotlib.figure import Figure

    fig = Figure(figsize=(w, h))
    fig.subplots_adjust(left=0.1, right=0.97, bottom=0.14 if h < 5 else 0.09, top=0.9 if h < 5 else 0.93,
                        hspace=0.45)
    return fig


def _note(ax, text):
    ax.text(0.5, 0.5, text, ha="center", va="center", transform=ax.transAxes, fontsize=11, color="0.35", wrap=True)
    ax.set_xticks([])
    ax.set_yticks([])


def plot_force(forces):
    """Peak and mean resultant force on the cutter [N] against path distance [mm]."""
    fig = _figure()
    ax = fig.add_subplot()
    if forces is None:
        _note(ax, "forces not predicted")
        return fig
    pos = np.asarray(forces.positions)
    s = np.concatenate([[0.0], np.cumsum(np.linalg.norm(np.diff(pos, axis=0), axis=1))]) if len(pos) else pos
    ax.plot(s, forces.peak_resultant, lw=0.8, label="peak per revolution")
    ax.plot(s, forces.mean_resultant, lw=0.8, label="mean per revolution")
    ax.set_xlabel("path distance [mm]")
    ax.set_ylabel("resultant force on the cutter [N]")
    ax.set_title("Cutting force along the path")
    ax.grid(alpha=0.3)
    ax.legend(loc="upper right", fontsize=8)
    return fig


def _broken(s_mm, values):
    """(s, v) with NaN between contours (a jump in s of more than 5 sample spacings), so the plot does
    not draw a line across the moves between two contours."""
    s_mm, values = np.asarray(s_mm, float), np.asarray(values, float)
    if len(s_mm) < 3:
        return s_mm, values
    ds = np.diff(s_mm)
    cut = np.flatnonzero(ds > 5.0 * np.median(ds)) + 1
    return np.insert(s_mm, cut, np.nan), np.insert(values, cut, np.nan)


def plot_wall_error(defl, vol, order_text):
    """Error along the path before and after compensation [µm], one panel per source."""
    fig = _figure(8.0, 5.6)
    axs = fig.subplots(2, 1)
    ax = axs[0]
    if defl is not None and defl.available:
        ax.plot(*_broken(defl.s_mm, 1e3 * defl.before_mm), lw=0.8, label="before")
        if defl.after_mm is not None:
            s_after = defl.s_after_mm if defl.s_after_mm is not None else defl.s_mm
            ax.plot(*_broken(s_after, 1e3 * defl.after_mm), lw=0.8, label="after (written program)")
        ax.set_ylabel("final-wall error [µm]")
        ax.legend(fontsize=8)
        ax.grid(alpha=0.3)
    else:
        _note(ax, "deflection wall error: " + (defl.reason if defl is not None else "not predicted"))
    ax.set_title("Wall error from tool deflection")
    ax = axs[1]
    if vol is not None:
        ax.plot(vol.s_before_mm, 1e3 * vol.before_mm, lw=0.8, label="before")
        if vol.after_mm is not None:
            ax.plot(vol.s_after_mm, 1e3 * vol.after_mm, lw=0.8, label="after")
        ax.set_yscale("symlog", linthresh=1e-3)
        ax.set_ylabel("path deviation [µm]")
        ax.set_xlabel("path distance [mm]")
        ax.legend(fontsize=8)
        ax.grid(alpha=0.3)
    else:
        _note(ax, "volumetric error not predicted")
    ax.set_title(f"Tool-tip path deviation from machine errors ({order_text})", fontsize=10)
    return fig


def plot_volumetric_map(vol):
    """Volumetric error |e| [µm] at the sampled path points, seen from above (machine frame)."""
    fig = _figure(8.0, 4.2)
    fig.subplots_adjust(right=0.9)
    if vol is None:
        _note(fig.add_subplot(), "volumetric error not predicted")
        return fig
    ax = fig.add_subplot()
    p = vol.points_mm
    ve = 1e3 * np.linalg.norm(vol.error_vectors_mm, axis=1)
    sc = ax.scatter(p[:, 0], p[:, 1], c=ve, s=4, cmap="plasma")
    fig.colorbar(sc, ax=ax, label="volumetric error |e| [µm]")
    ax.set_aspect("equal", adjustable="datalim")
    ax.set_xlabel("machine X [mm]")
    ax.set_ylabel("machine Y [mm]")
    ax.set_title(f"Volumetric error along the program: {ve.min():.2f} – {ve.max():.2f} µm")
    return fig


def plot_feed(traj, traj_comp):
    """Planned path feed [mm/s] against time [s] for the original and the compensated program."""
    fig = _figure()
    ax = fig.add_subplot()
    if traj is None:
        _note(ax, "feed plan not predicted")
        return fig
    step = max(1, len(traj.t) // 20000)
    ax.plot(traj.t[::step], traj.feed[::step], lw=0.8, label=f"original ({traj.stats['cycle_time_s']:.2f} s)")
    if traj_comp is not None:
        step = max(1, len(traj_comp.t) // 20000)
        ax.plot(traj_comp.t[::step], traj_comp.feed[::step], lw=0.8, ls="--",
                label=f"compensated ({traj_comp.stats['cycle_time_s']:.2f} s)")
    ax.set_xlabel("time [s]")
    ax.set_ylabel("path feed [mm/s]")
    ax.set_title("Feed profile (look-ahead plan)")
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8)
    return fig


def plot_zmap(zmap):
    """Final Z-map heights [mm]."""
    from netshape.stock import plot_heights

    return plot_heights(zmap, title="Stock after the program (Z-map heights)")


def _fmt(v) -> str:
    if v is None:
        return "—"
    if isinstance(v, float):
        if not math.isfinite(v):
            return str(v)
        return f"{v:.6g}"
    return html.escape(str(v))


def summary_rows(summary: dict) -> list[tuple[str, str, object]]:
    """(key path, label, value) of every number the page's summary table shows."""
    rows = []
    for src in ("deflection", "volumetric", "total"):
        e = summary["errors"][src]
        for k in ("max_before_mm", "max_after_mm", "rms_before_mm", "rms_after_mm"):
            rows.append((f"errors.{src}.{k}", f"{src}: {k}", e[k]))
    for k, v in summary["cycle_time_s"].items():
        rows.append((f"cycle_time_s.{k}", f"cycle time, {k} [s]", v))
    for k, v in summary["run_time_s"].items():
        rows.append((f"run_time_s.{k}", f"run time of stage {k} [s]", v))
    return rows + optimize_rows(summary)


def optimize_rows(summary: dict) -> list[tuple[str, str, object]]:
    """(key path, label, value) of the ``[optimize]`` results: cycle time before and after, the saving,
    pieces per binding limit, the largest force before and after, the re-simulated checks."""
    o = summary.get("optimize")
    if not o:
        return []
    rows = [(f"optimize.cycle_time_s.{k}", f"cycle time, {k} [s]", v) for k, v in o["cycle_time_s"].items()]
    rows.append(("optimize.saving_percent", "cycle-time saving [%]", o["saving_percent"]))
    rows += [(f"optimize.binding.{k}", f"pieces bound by {k}", v) for k, v in o["binding"].items()]
    rows += [(f"optimize.max_force_N.{k}", f"largest force, {k} [N]", v) for k, v in o["max_force_N"].items()]
    rows += [(f"optimize.check.{k}.ratio", f"re-simulated {k} / limit", c["ratio"])
             for k, c in o.get("check", {}).items()]
    return rows


def _optimize_html(summary: dict) -> list[str]:
    """The ``[optimize]`` section: limits stated and optimize_rows as a table."""
    o = summary.get("optimize")
    if not o:
        return []
    limits = ", ".join(f"{html.escape(k)} {_fmt(v)}" for k, v in o.get("limits", {}).items())
    out = ["<h2>Feed scheduling ([optimize])</h2>",
           f"<p>Program written: <code>{html.escape(summary.get('files', {}).get('optimized_program', ''))}"
           f"</code>; limits: {limits or 'none'}; {o.get('pieces', 0)} pieces.</p>",
           '<table id="optimize"><tr><th>quantity</th><th>value</th></tr>']
    out += [f'<tr><td>{html.escape(label)}</td><td data-key="{key}">{_fmt(v)}</td></tr>'
            for key, label, v in optimize_rows(summary)]
    out.append("</table>")
    return out


def write_html(path, summary: dict, images: dict[str, str]) -> None:
    """The report page: title, the compensation order, stage notes, the summary table (every cell
    carries ``data-key`` = its key path in summary.json) and the plots (relative file names)."""
    from netshape._atomic import atomic_write

    title = f"netshape job report — {summary['job']['name']}"
    out = [
        "<!DOCTYPE html>",
        '<html lang="en"><head><meta charset="utf-8">',
        f"<title>{html.escape(title)}</title>",
        "<style>body{font-family:sans-serif;max-width:60em;margin:1em auto;padding:0 1em;color:#222}"
        "table{border-collapse:collapse}td,th{border:1px solid #bbb;padding:.2em .6em;text-align:right}"
        "td:first-child,th:first-child{text-align:left}img{max-width:100%;display:block;margin:.5em 0 1.5em}"
        ".note{color:#a40}</style></head><body>",
        f"<h1>{html.escape(title)}</h1>",
        f"<p>Program <code>{html.escape(summary['job']['program'])}</code>; predictions: "
        f"{html.escape(', '.join(summary['job']['predictions']) or 'none')}.</p>",
        f"<p>Compensations applied, in this order: <b>{html.escape(' → '.join(summary['job']['compensations']) or 'none')}"
        f"</b> (requested: {html.escape(', '.join(summary['job'].get('requested_compensations', [])) or 'none')}; "
        "deflection is always applied first, then volumetric on the deflection-compensated path).</p>",
    ]
    notes = [f"{k}: {v}" for k, v in summary.get("stages", {}).items() if v != "ok"]
    if summary.get("stale_files"):
        notes.append("files in this folder that this run did not write: " + ", ".join(summary["stale_files"]))
    if notes:
        out.append("<ul>" + "".join(f'<li class="note">{html.escape(n)}</li>' for n in notes) + "</ul>")
    mach = summary.get("machine")
    if mach and mach.get("terms"):
        out.append(f'<h2>Machine terms</h2><p><code>{html.escape(mach["file"])}</code></p><table id="machine-terms">'
                   "<tr><th>term</th><th>value</th><th>from</th></tr>" + "".join(
                       f"<tr><td>{html.escape(t['term'])}</td><td>{html.escape(t['value'])}</td>"
                       f"<td>{html.escape(t['source'])}</td></tr>" for t in mach["terms"]) + "</table>")
    warns = summary.get("warnings") or []
    if warns:
        out.append('<h2>Warnings</h2><ul id="warnings">' + "".join(
            f'<li class="note">{html.escape(w["kind"])} (line {w["line"]}): {html.escape(w["message"])}</li>'
            for w in warns) + "</ul>")
    dfl = summary.get("deflection")
    if dfl and dfl.get("reason"):
        out.append(f'<p class="note">deflection: {html.escape(dfl["reason"])}</p>')
    if dfl:
        out.append('<h2>Deflection: contours</h2><table id="contours"><tr><th>line</th><th>final wall</th>'
                   "<th>converged</th><th>iterations</th><th>max residual [mm]</th></tr>")
        for c in dfl.get("contours", []):
            out.append(f"<tr><td>{c['line']}</td><td>{'yes' if c['final_wall'] else 'no (cut away later)'}</td>"
                       f"<td>{_fmt(c.get('converged'))}</td><td>{_fmt(c.get('iterations'))}</td>"
                       f"<td>{_fmt(c.get('max_residual_mm'))}</td></tr>")
        out.append("</table>")
        lv = dfl.get("levels_mm", {})
        if lv:
            out.append("<p>Largest final-wall error per level [mm] (a 2-D offset moves the whole tool, so the "
                       "levels other than the reference keep the taper of the bent tool): "
                       + "; ".join(f"{html.escape(w)}: " + ", ".join(f"{k} {_fmt(v)}" for k, v in d.items())
                                   for w, d in lv.items()) + "</p>")
        for c in dfl.get("contours_skipped", []):
            out.append(f'<p class="note">skipped contour at line {c["line"]}: {html.escape(c["reason"])}</p>')
        pts = dfl.get("unconverged_points", [])
        if pts:
            out.append('<p class="note">Points above the tolerance after compensation: '
                       + ", ".join(f"line {p['line']} ({p['x_mm']:.3f}, {p['y_mm']:.3f}) {p['error_mm'] * 1e3:.2f} µm"
                                   for p in pts[:20]) + (" …" if len(pts) > 20 else "") + "</p>")
    out.append("<h2>Errors [mm]</h2>")
    out.append('<table id="errors"><tr><th>source</th><th>max before</th><th>max after</th><th>RMS before</th>'
               "<th>RMS after</th></tr>")
    for src in ("deflection", "volumetric", "total"):
        e = summary["errors"][src]
        cells = "".join(f'<td data-key="errors.{src}.{k}">{_fmt(e[k])}</td>'
                        for k in ("max_before_mm", "max_after_mm", "rms_before_mm", "rms_after_mm"))
        out.append(f"<tr><td>{src}</td>{cells}</tr>")
    out.append("</table>")
    out.append('<h2>Cycle time [s]</h2><table id="cycle"><tr><th>program</th><th>cycle time</th></tr>')
    for k, v in summary["cycle_time_s"].items():
        out.append(f'<tr><td>{k}</td><td data-key="cycle_time_s.{k}">{_fmt(v)}</td></tr>')
    out.append("</table>")
    out += _optimize_html(summary)
    out.append('<h2>Run time per stage [s]</h2><table id="runtime"><tr><th>stage</th><th>time</th></tr>')
    for k, v in summary["run_time_s"].items():
        out.append(f'<tr><td>{k}</td><td data-key="run_time_s.{k}">{_fmt(v)}</td></tr>')
    out.append("</table>")
    out.append("<p>Deflection errors are those of the walls that remain at the end of the program (signed, "
               "+ material left); volumetric errors are distances of the predicted tool-tip path from the "
               "nominal one. Total: on final walls the deflection error plus the machine's tip error along "
               "the wall normal (before), or plus the volumetric residual in the adverse direction (after, "
               "whose direction the residual distance does not give); elsewhere the volumetric error.</p>")
    out.append("<h2>Plots</h2>")
    captions = {"force": "Cutting force along the path", "wall_error": "Error before and after compensation",
                "volumetric": "Volumetric error map", "feed": "Feed profile", "zmap": "Z-map heights",
                "optimize": "Scheduled feed and force along the path ([optimize])"}
    for key, name in images.items():
        out.append(f"<h3>{html.escape(captions.get(key, key))}</h3>")
        out.append(f'<img src="{html.escape(name)}" alt="{html.escape(captions.get(key, key))}">')
    files = summary.get("files", {})
    if files:
        out.append("<h2>Files</h2><ul>")
        for k, v in files.items():
            if v and not v.endswith(".png") and v != "report.html":
                out.append(f'<li>{html.escape(k)}: <a href="{html.escape(v)}">{html.escape(v)}</a></li>')
        out.append("</ul>")
    v = summary.get("versions", {})
    out.append(f"<p><small>netshape {html.escape(str(v.get('netshape', '')))}, Python "
               f"{html.escape(str(v.get('python', '')))}, NumPy {html.escape(str(v.get('numpy', '')))}</small></p>")
    out.append("</body></html>")
    with atomic_write(path, "w") as fh:
        fh.write("\n".join(out) + "\n")
