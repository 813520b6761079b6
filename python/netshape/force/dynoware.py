"""Reader for Kistler DynoWare CSV exports (the format of the leekunhwee-flat-slot recordings: Jianhui
Li's slot cuts with a 2-flute flat end mill, published at github.com/leekunhwee/ForceCalculation).

Layout: header lines ``key:,value`` (DynoWare version, file names, ``Sampling rate [Hz]:,10000``,
``Measuring time [s]``, ``Samples per channel`` …), then a line of channel names
(``Time,Fx,Fy,Fz``), a line of units (``s,N,N,N``) and the samples.

Frames. A dynamometer measures the force on the WORKPIECE, W = −C (C = force on the cutter). Its axes
are the instrument's: for the Kistler 9257B family Z points down into the plate. netshape's force
models give C in the cutting frame of docs/conventions.md §2 (X feed, Z tool axis up into the
spindle, Y = Z × X).
Readings map to the cutting frame by a 3×3 matrix T with C = T·F_dyn, which combines the sign flip
W → C with the mounting of the plate. For the leekunhwee-flat-slot recordings (its README: ref
Fy = dyn Fx, ref Fx = dyn Fy, X = feed) the plate axes are e_dx = −Y, e_dy = −X, e_dz = −Z (a proper
rotation: Z down, as Kistler plates are), so C = (F_dy, F_dx, F_dz): T is the swap below. Checks
from physics in the data (docs/force.md): C̄x = mean dyn Fy < 0 (in slotting the radial force pushes
the cutter back against the feed), C̄y = mean dyn Fx > 0 (the tangential force on the flutes in the
front half points to +Y for a clockwise cutter), and the phase-fitted time series of the model
matches the measured waveform (the mirrored mapping fits far worse, see the example).
"""

from __future__ import annotations

import os
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from netshape._text import read_controller_text
from netshape.errors import ParseError

#: C = T · F_dyn for the leekunhwee-flat-slot set-up (see the module docstring).
DYNAMOMETER_TO_CUTTER_LEEKUNHWEE = np.array([[0.0, 1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])


@dataclass
class DynoWareRecording:
    """One DynoWare export.

    times: (n,) [s]; forces: (n, 3) [N] (after ``to_cutter`` if given, else the raw channels);
    raw: (n, 3) [N] dynamometer channels Fx, Fy, Fz as recorded; sampling_rate [Hz];
    metadata: header keys → text; channels / units: column names and units; path.
    """

    times: np.ndarray
    forces: np.ndarray
    raw: np.ndarray
    sampling_rate: float
    metadata: dict = field(default_factory=dict)
    channels: tuple = ()
    units: tuple = ()
    path: str = ""
    frame: str = "dynamometer"

    def to_dict(self) -> dict:
        return {
            "path": self.path,
            "samples": int(self.times.size),
            "sampling_rate": self.sampling_rate,
            "frame": self.frame,
            "metadata": dict(self.metadata),
            "channels": list(self.channels),
            "units": list(self.units),
        }


_FORCE_CHANNELS = ("Fx", "Fy", "Fz")


def _parse_error(path: Path, line: int, column: int, what: str) -> ParseError:
    where = f"{path}:{line}" if line > 0 else str(path)
    return ParseError(f"{where}: {what}", str(path), line, column, what)


def read_dynoware(path: str | os.PathLike, to_cutter: np.ndarray | str | None = None) -> DynoWareRecording:
    """Read a Kistler DynoWare CSV export.

    Parameters
    ----------
    path : file name.
    to_cutter : None (keep the dynamometer channels), ``"leekunhwee"`` (the mapping of the
        leekunhwee-flat-slot set-up) or a (3, 3) matrix T with C = T·F_dyn giving the force on the
        cutter in the cutting frame of docs/conventions.md §2.

    Returns
    -------
    DynoWareRecording with ``times`` (n,) [s] and ``forces`` (n, 3) [N].

    Raises ParseError (a ValueError) naming the file and line on a malformed file.
    """
    p = Path(path)
    text = read_controller_text(p).splitlines()
    meta: dict[str, str] = {}
    header_at = None
    for i, line in enumerate(text[:200]):
        cells = [c.strip() for c in line.split(",")]
        if cells and cells[0].lower() == "time":
            header_at = i
            break
        if len(cells) >= 1 and cells[0].endswith(":"):
            meta[cells[0][:-1].strip()] = ",".join(cells[1:]).strip()
        elif i == 0 and cells[0]:
            meta["Program"] = ",".join(cells).strip()
    if header_at is None:
        raise _parse_error(p, 0, 0, "no 'Time,...' channel line in the first 200 lines: not a DynoWare CSV export")
    channels = tuple(c.strip() for c in text[header_at].split(","))
    if header_at + 1 >= len(text):
        raise _parse_error(p, header_at + 2, 0, "missing the units line after the channel names")
    units = tuple(c.strip() for c in text[header_at + 1].split(","))
    missing = [c for c in _FORCE_CHANNELS if c not in channels]
    if missing:
        raise _parse_error(p, header_at + 1, 0, f"channels {channels} lack {missing}")
    for name, unit in zip(channels, units):
        if name in _FORCE_CHANNELS and unit != "N":
            raise _parse_error(p, header_at + 2, 0, f"channel {name} has unit {unit!r}; expected N")
    rows = text[header_at + 2 :]
    try:
        data = np.array([[float(c) for c in r.split(",")[: len(channels)]] for r in rows if r.strip()], dtype=float)
    except ValueError as exc:
        # find the offending line for the message
        for k, r in enumerate(rows):
            try:
                [float(c) for c in r.split(",")[: len(channels)]] if r.strip() else None
            except ValueError:
                raise _parse_error(p, header_at + 3 + k, 0, f"not a number in {r.strip()!r}") from exc
        raise
    if data.ndim != 2 or data.shape[0] < 2 or data.shape[1] != len(channels):
        raise _parse_error(p, header_at + 3, 0, "fewer than 2 complete sample rows")
    if not np.all(np.isfinite(data)):
        bad = int(np.argwhere(~np.isfinite(data))[0][0])
        raise _parse_error(p, header_at + 3 + bad, 0, "non-finite sample")
    times = data[:, channels.index("Time")]
    raw = np.column_stack([data[:, channels.index(c)] for c in _FORCE_CHANNELS])
    rate_text = meta.get("Sampling rate [Hz]")
    if rate_text:
        try:
            rate = float(rate_text)
        except ValueError:
            raise _parse_error(p, 0, 0, f"Sampling rate [Hz] = {rate_text!r}: not a number") from None
    else:
        rate = 1.0 / float(np.median(np.diff(times)))
    if not (rate > 0 and np.isfinite(rate)):
        raise _parse_error(p, 0, 0, f"sampling rate = {rate}: must be positive")
    frame = "dynamometer"
    forces = raw.copy()
    if to_cutter is not None:
        if isinstance(to_cutter, str):
            if to_cutter != "leekunhwee":
                raise ValueError(f"to_cutter = {to_cutter!r}: known mappings are 'leekunhwee' or a (3, 3) matrix")
            T = DYNAMOMETER_TO_CUTTER_LEEKUNHWEE
        else:
            T = np.asarray(to_cutter, dtype=float)
            if T.shape != (3, 3) or not np.all(np.isfinite(T)):
                raise ValueError(f"to_cutter shape = {T.shape}: must be a finite (3, 3) matrix")
        forces = raw @ T.T
        frame = "cutter"
    return DynoWareRecording(times=times, forces=forces, raw=raw, sampling_rate=rate, metadata=meta,
                             channels=channels, units=units, path=str(p), frame=frame)
