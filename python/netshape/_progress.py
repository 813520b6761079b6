"""Progress bars for the long C++ computations, and how Ctrl-C reaches them.

The C++ core reports from its long loops (a Z-map sweep, a deflection compensation, a feed plan, a
posture plan) at most 20 times a second. The extension always checks for Ctrl-C then, so a long
computation stops within ~50 ms with ``KeyboardInterrupt`` and the command exits 130 without
writing its outputs. Inside :func:`progress` the reports also drive one tqdm bar per stage on
stderr.
"""

from __future__ import annotations

import sys
from contextlib import contextmanager
from typing import Iterator

from netshape import _core


@contextmanager
def progress(label: str, enabled: bool | None = None) -> Iterator[None]:
    """Shows the C++ stages run inside the block as progress bars named ``label: stage``.

    ``enabled=None`` shows them when stderr is a terminal. Bars are removed when the block ends.
    """
    if enabled is None:
        enabled = sys.stderr.isatty()
    if not enabled:
        yield
        return
    from tqdm import tqdm

    bars: dict[str, tqdm] = {}

    def report(what: str, done: int, total: int) -> None:
        bar = bars.get(what)
        if bar is None or done < bar.n:  # a new call of the same stage starts over
            if bar is not None:
                bar.close()
            bar = bars[what] = tqdm(total=total or None, desc=f"{label}: {what}", file=sys.stderr,
                                    leave=False, mininterval=0.2)
        bar.update(done - bar.n)

    _core.set_progress(report)
    try:
        yield
    finally:
        _core.set_progress(None)
        for bar in bars.values():
            bar.close()
