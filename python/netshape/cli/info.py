"""`netshape info PROGRAM [--json]`: what a G-code program does, read while streaming."""

from __future__ import annotations


_DESCRIPTION = """\
Read an RS274/NGC (LinuxCNC dialect) G-code program and print block counts by kind, rapid and feed
path lengths [mm], the bounding box of all motion including arcs [mm], and the time of the feed
moves at the programmed feed [s], G4 dwell time [s] and their sum, the total time (rapids and
accelerations not included). Inch programs (G20) are converted to mm. With --var / --tool-table the
positions are machine axis positions (program + work offset + tool length along Z). The program is streamed: memory does not grow with its
length. Unsupported codes (cutter compensation, canned cycles, NURBS, G92, o-words, ...) are
refused with file:line:column and the reason; exit code 2.
"""


def register(sub) -> None:
    p = sub.add_parser(
        "info",
        help="block counts, lengths, bounding box and time of a G-code program",
        description=_DESCRIPTION,
        epilog="example: netshape info part.ngc --json",
    )
    p.add_argument("program", metavar="PROGRAM", help="G-code file (.ngc, .nc, .gcode, ...)")
    p.add_argument("--json", action="store_true", help="print a JSON object instead of a table")
    from netshape.cli._offsets import add_offset_options

    add_offset_options(p)
    p.set_defaults(func=run)


def info_dict(program, *, work_offsets=None, tool_table=None) -> dict:
    """The figures `netshape info` prints, as a dict (keys carry their units)."""
    from netshape import toolpath

    d = toolpath.summary(program, work_offsets=work_offsets, tool_table=tool_table).to_dict()
    d = {"program": str(program), **d}
    d["bbox_min_mm"] = list(d["bbox_min_mm"])
    d["bbox_max_mm"] = list(d["bbox_max_mm"])
    return d


def format_table(d: dict) -> str:
    lo, hi = d["bbox_min_mm"], d["bbox_max_mm"]
    rows = [
        ("program", d["program"]),
        ("source lines", f"{d['source_lines']}"),
        ("blocks", f"{d['blocks']}  (rapid {d['rapids']}, line {d['lines']}, arc {d['arcs']})"),
        ("rapid length", f"{d['rapid_length_mm']:.3f} mm"),
        ("feed length", f"{d['feed_length_mm']:.3f} mm"),
        ("bounding box X", f"{lo[0]:.3f} … {hi[0]:.3f} mm"),
        ("bounding box Y", f"{lo[1]:.3f} … {hi[1]:.3f} mm"),
        ("bounding box Z", f"{lo[2]:.3f} … {hi[2]:.3f} mm"),
        ("feed time", f"{d['feed_time_s']:.3f} s  ({d['feed_time_s'] / 60.0:.2f} min, at programmed feed)"),
    ]
    if d["dwells"]:
        rows.append(("dwell time", f"{d['dwell_time_s']:.3f} s  ({d['dwells']} dwells)"))
        rows.append(("total time", f"{d['total_time_s']:.3f} s  (feed + dwell)"))
    width = max(len(k) for k, _ in rows)
    return "\n".join(f"{k:<{width}}  {v}" for k, v in rows)


def run(args) -> int:
    from netshape.cli._offsets import offset_kwargs, reader_warnings

    with reader_warnings("info"):
        d = info_dict(args.program, **offset_kwargs(args))
    if args.json:
        from netshape._json import dumps_json

        print(dumps_json(d, indent=2, cause=str(args.program)))
    else:
        print(format_table(d))
    return 0
