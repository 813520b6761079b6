"""Report of a Diagnosis: PNG plots of the residuals before and after, against the covariate where
each added effect shows, and an HTML page that embeds them. Files are written atomically."""

from __future__ import annotations

import html
import json
import math
from pathlib import Path

import numpy as np

from netshape._atomic import atomic_save_figure, atomic_write

from .force_effects import harmonic_power


def _figure(nrows=1, ncols=1, size=(9.0, 3.2)):
    import matplotlib

    matplotlib.use("Agg", force=False)
    from matplotlib.figure import Figure

    fig = Figure(figsize=(size[0], size[1] * nrows))
    axes = fig.subplots(nrows, ncols, squeeze=False)
    return fig, axes


def plot_residuals(diagnosis):
    """Residual per experiment before and after (against the sample index), one row per axis."""
    p = diagnosis.problem
    rb, ra = p.residuals(diagnosis.spec_before), p.residuals(diagnosis.spec_after)
    ncol = rb[0].shape[1]
    fig, axes = _figure(ncol, 1)
    names = ("x", "y", "z") if ncol == 3 else ("",)
    for a in range(ncol):
        ax = axes[a][0]
        off = 0
        for i, (b, af) in enumerate(zip(rb, ra)):
            idx = np.arange(off, off + len(b))
            ax.plot(idx, b[:, a], color="tab:red", lw=0.6, label="before" if i == 0 else None)
            ax.plot(idx, af[:, a], color="tab:blue", lw=0.6, label="after" if i == 0 else None)
            off += len(b)
            ax.axvline(off, color="0.8", lw=0.5)
        ax.set_ylabel(f"residual {names[a]} [{p.unit}]")
        ax.legend(loc="upper right", fontsize=7)
    axes[ncol - 1][0].set_xlabel("sample (experiments in order)")
    fig.suptitle(
        f"{diagnosis.kind}: rms {diagnosis.rms_before:.4g} → {diagnosis.rms_after:.4g} {p.unit} "
        f"(noise {diagnosis.noise_estimate:.4g})"
    )
    fig.tight_layout()
    return fig


def plot_covariate(diagnosis, covariate: str, label: str = ""):
    """Residual before/after against ``covariate`` (forces: angle, feed, frequency; volumetric:
    position, time, direction, tool_length)."""
    p = diagnosis.problem
    sb, sa = diagnosis.spec_before, diagnosis.spec_after
    rb, ra = p.residuals(sb), p.residuals(sa)
    cov = p.covariates(sa)
    if covariate == "angle":
        i = int(np.argmax([np.sqrt(np.mean(r**2)) for r in rb]))
        fig, axes = _figure(3, 1)
        th = np.degrees(cov["angle"][i])
        o = np.argsort(th)
        for a in range(3):
            ax = axes[a][0]
            ax.plot(th[o], rb[i][o, a], ".", ms=1.5, color="tab:red", label="before")
            ax.plot(th[o], ra[i][o, a], ".", ms=1.5, color="tab:blue", label="after")
            ax.set_ylabel(f"residual {'xyz'[a]} [N]")
        axes[0][0].legend(fontsize=7)
        axes[2][0].set_xlabel(f"angle of flute 1 [deg] — {Path(p.experiments[i].file).name}")
    elif covariate == "feed":
        fig, axes = _figure(1, 1, (7, 3.6))
        ax = axes[0][0]
        c = np.array(cov["feed"])
        for a, col in enumerate(("tab:red", "tab:green", "tab:blue")):
            ax.plot(c, [r[:, a].mean() for r in rb], "o", color=col, label=f"{'xyz'[a]} before")
            ax.plot(c, [r[:, a].mean() for r in ra], "x", color=col, label=f"{'xyz'[a]} after")
        ax.axhline(0, color="0.6", lw=0.5)
        ax.set_xlabel("feed per tooth [mm]")
        ax.set_ylabel("mean residual [N]")
        ax.legend(fontsize=7, ncol=3)
    elif covariate == "frequency":
        fig, axes = _figure(1, 1, (8, 3.6))
        ax = axes[0][0]
        for r, col, lab in ((rb, "tab:red", "before"), (ra, "tab:blue", "after")):
            freqs, amps = [], []
            for i, e in enumerate(p.experiments):
                th = np.mod(cov["angle"][i], 2 * np.pi)
                H = 60
                amp = np.sqrt(harmonic_power(th, r[i], H))
                freqs.append(np.arange(1, H + 1) * p.omega[i] / (2 * np.pi))
                amps.append(amp)
            ax.plot(np.concatenate(freqs), np.concatenate(amps), ".", color=col, label=lab)
        ax.set_xlabel("frequency [Hz] (revolution harmonics)")
        ax.set_ylabel("residual amplitude [N]")
        ax.legend(fontsize=7)
    elif covariate in ("position", "time", "direction", "tool_length"):
        if covariate == "position":
            fig, axes = _figure(3, 3, (10, 2.6))
            P = np.concatenate(cov["position"])
            B, A = np.concatenate(rb), np.concatenate(ra)
            for i in range(3):
                for j in range(3):
                    ax = axes[i][j]
                    ax.plot(P[:, j], B[:, i] * 1e3, ".", ms=2, color="tab:red")
                    ax.plot(P[:, j], A[:, i] * 1e3, ".", ms=2, color="tab:blue")
                    ax.set_xlabel(f"{'xyz'[j]} [mm]", fontsize=7)
                    ax.set_ylabel(f"e{'xyz'[i]} residual [µm]", fontsize=7)
        else:
            fig, axes = _figure(3, 1, (8, 2.4))
            v = np.concatenate(cov[covariate])
            B, A = np.concatenate(rb), np.concatenate(ra)
            for i in range(3):
                ax = axes[i][0]
                ax.plot(v, B[:, i] * 1e3, ".", ms=2, color="tab:red", label="before")
                ax.plot(v, A[:, i] * 1e3, ".", ms=2, color="tab:blue", label="after")
                ax.set_ylabel(f"e{'xyz'[i]} residual [µm]")
            axes[0][0].legend(fontsize=7)
            axes[2][0].set_xlabel(
                {"time": "t [s]", "direction": "approach direction", "tool_length": "tool length [mm]"}[
                    covariate
                ]
            )
    elif covariate in ("normal_force", "revolution_phase"):
        fig, axes = _figure(1, 1, (8, 3.4))
        ax = axes[0][0]
        v = np.concatenate(cov[covariate])
        B, A = np.concatenate(rb)[:, 0], np.concatenate(ra)[:, 0]
        ax.plot(v, B * 1e3, ".", ms=2, color="tab:red", label="before")
        ax.plot(v, A * 1e3, ".", ms=2, color="tab:blue", label="after")
        ax.set_ylabel("wall error residual [µm]")
        ax.set_xlabel(
            {"normal_force": "force along the wall normal at the generating instant [N]",
             "revolution_phase": "revolution phase of the generating pass [deg] (0: flute 1)"}[covariate]
        )
        ax.legend(fontsize=7)
    else:
        raise ValueError(f"covariate = {covariate!r}: unknown")
    fig.suptitle(label or f"residual against {covariate}: before (red) and after (blue)")
    fig.tight_layout()
    return fig


def plot_unexplained(diagnosis, max_rows: int = 6):
    """One row per ``unexplained`` finding (at most ``max_rows``): the final residual of its component
    against its covariate (points) and its mean in 60 bins (line), the finding in the title."""
    p = diagnosis.problem
    comps, covs = p.structure_covariates(diagnosis.spec_after)
    r = np.concatenate(p.residuals(diagnosis.spec_after))
    found = diagnosis.unexplained[:max_rows]
    fig, axes = _figure(len(found), 1, (9.0, 2.6))
    for ax, fnd in zip((a[0] for a in axes), found):
        v = np.asarray(covs[fnd["covariate"]], float)
        y = r[:, comps.index(fnd["component"])]
        ax.plot(v, y, ".", ms=1.5, color="0.6")
        edges = np.linspace(v.min(), v.max(), 61)
        idx = np.clip(np.digitize(v, edges) - 1, 0, 59)
        cnt = np.bincount(idx, minlength=60)
        mean = np.bincount(idx, y, minlength=60) / np.maximum(cnt, 1)
        ok = cnt > 0
        ax.plot(((edges[:-1] + edges[1:]) / 2)[ok], mean[ok], color="tab:red", lw=1.0)
        extra = f", period {fnd['period']:.4g}" if "period" in fnd else (f", at {fnd['at']:.4g}" if "at" in fnd else "")
        ax.set_title(f"{fnd['component']}: {fnd['form']} against {fnd['covariate']}{extra}, rms {fnd['rms']:.3g} {p.unit}",
                     fontsize=9)
        ax.set_xlabel(fnd["covariate"])
        ax.set_ylabel(f"{fnd['component']} residual [{p.unit}]")
    fig.tight_layout()
    return fig


def write_report(diagnosis, out_dir) -> list:
    """Write residuals.png, one <effect>.png per added effect (or the first candidate's covariate
    when none was added) and index.html into ``out_dir`` (created if missing). Returns the paths."""
    from .catalogue import catalogue

    out = Path(out_dir)
    out.mkdir(parents=True, exist_ok=True)
    written = []
    figs = [("residuals.png", plot_residuals(diagnosis), "Residuals before and after")]
    cat = catalogue(diagnosis.kind)
    shown = [e["effect"] for e in diagnosis.effects]
    if not shown and diagnosis.candidates:
        shown = [min(diagnosis.candidates, key=lambda c: c["bic"])["effect"]]
    seen = set()
    for name in shown:
        eff = cat.get(name)
        if eff is None or not eff.covariate or eff.covariate in seen:
            continue
        seen.add(eff.covariate)
        figs.append(
            (
                f"{name}.png",
                plot_covariate(diagnosis, eff.covariate, f"{name}: residual against {eff.covariate}"),
                f"Residual against {eff.covariate}, where {name} shows",
            )
        )
    if diagnosis.unexplained:
        figs.append(("unexplained.png", plot_unexplained(diagnosis),
                     "Unexplained structure: the final residual against where it was found"))
    for fname, fig, _ in figs:
        atomic_save_figure(fig, out / fname, dpi=90)
        written.append(out / fname)
    d = diagnosis
    u = d.unit

    def f(v):
        return "—" if v is None or (isinstance(v, float) and not math.isfinite(v)) else f"{v:.4g}"

    def status(c):
        if c.get("rejected"):
            return html.escape(c["rejected"])
        if c.get("converged") is False:
            return "fit not converged"
        return "ok"

    rows = "".join(
        f"<tr><td>{html.escape(c['effect'])}</td><td>{f(c['rms'])}</td><td>{f(c['cv_rms'])}</td>"
        f"<td>{f(c['bic'])}</td><td>{status(c)}</td></tr>"
        for c in d.candidates
    )
    un_rows = "".join(
        f"<tr><td>{html.escape(x['component'])}</td><td>{html.escape(x['covariate'])}</td>"
        f"<td>{html.escape(x['form'])}</td><td>{f(x.get('period'))}</td><td>{f(x['rms'])}</td></tr>"
        for x in getattr(d, "unexplained", [])
    )
    if un_rows:
        unexplained = ("<h2>Unexplained structure (after the added effects)</h2><table><tr><th>component</th>"
                       f"<th>covariate</th><th>form</th><th>period</th><th>rms [{u}]</th></tr>{un_rows}</table>")
    elif d.rms_after <= 1.1 * d.noise_estimate:
        unexplained = "<p>The residual is consistent with the noise.</p>"
    else:
        unexplained = "<p>The residual exceeds the noise, but no trend, step or period was located.</p>"
    eff_rows = (
        "".join(
            f"<tr><td>{html.escape(e['effect'])}</td><td>{html.escape(json.dumps(e['parameters']))}</td>"
            f"<td>{f(e['rms_after'])}</td></tr>"
            for e in d.effects
        )
        or "<tr><td colspan=3>"
        + ("no missing effect found" if d.rms_after <= 1.1 * d.noise_estimate and not getattr(d, "unexplained", [])
           else "no catalogue effect added")
        + "</td></tr>"
    )
    notes = "".join(f"<li>{html.escape(n)}</li>" for n in d.notes)
    skipped = "".join(f"<li>{html.escape(k)}: {html.escape(v)}</li>" for k, v in d.skipped.items())
    imgs = "".join(f'<h3>{html.escape(t)}</h3><img src="{fn}" alt="{html.escape(t)}">' for fn, _, t in figs)
    page = f"""<!doctype html>
<html><head><meta charset="utf-8"><title>netshape diagnose: {html.escape(d.kind)}</title>
<style>body{{font-family:sans-serif;max-width:1000px;margin:2em auto}}table{{border-collapse:collapse}}
td,th{{border:1px solid #ccc;padding:2px 8px}}img{{max-width:100%}}</style></head><body>
<h1>Discrepancy diagnosis ({html.escape(d.kind)})</h1>
<p>rms before {f(d.rms_before)} {u}, after {f(d.rms_after)} {u}; noise estimate {f(d.noise_estimate)} {u} (source: {html.escape(getattr(d, "noise_source", ""))}).</p>
<h2>Effects added</h2><table>
<tr><th>effect</th><th>parameters</th><th>rms after [{u}]</th></tr>{eff_rows}</table>
<h2>Candidates (first round)</h2><table>
<tr><th>effect</th><th>rms [{u}]</th><th>held-out rms [{u}]</th><th>BIC</th><th>status</th></tr>{rows}</table>
{unexplained}
<h2>Where the residual was systematic (before)</h2>
<pre>{html.escape(json.dumps(_plain(d.localisation), indent=1))}</pre>
<h2>Experiments</h2><pre>{html.escape(json.dumps(_plain(d.experiments), indent=1))}</pre>
<ul>{notes}</ul>{("<h2>Not tried</h2><ul>" + skipped + "</ul>") if skipped else ""}
{imgs}
</body></html>
"""
    with atomic_write(out / "index.html") as fh:
        fh.write(page)
    written.append(out / "index.html")
    return written


def _plain(v):
    from .workflow import _clean

    return _clean(v)
