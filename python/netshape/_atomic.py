"""Output files (docs/conventions.md §6): checked before any work, written whole or not at all, with the
user's umask.

- :func:`check_output_file` / :func:`check_output_folder` refuse, with a ValueError naming the option and
  the path the user gave, an output that is a folder where a file is expected (or a file where a folder
  is), that lies under a file, that is a device or other non-regular file (``/dev/null``), or whose
  folder cannot be written. Commands call them for every output before they start working.
- :func:`atomic_write` / :func:`atomic_path` write a temporary file beside the target, then rename it over
  the target; errors name the target, never the temporary file.
- :func:`all_or_nothing`: inside it every rename waits for the end of the block; if the block fails,
  every temporary file is deleted and no target is touched, so a command writes all its outputs or none.
"""

from __future__ import annotations

import contextlib
import contextvars
import errno
import os
import stat
import tempfile
from pathlib import Path
from typing import IO, Iterator

#: Renames waiting for the end of the innermost :func:`all_or_nothing` block: (temporary, target).
_PENDING: contextvars.ContextVar[list | None] = contextvars.ContextVar("netshape_pending_outputs", default=None)


def _umask() -> int:
    try:
        with open("/proc/self/status", encoding="ascii") as fh:
            for line in fh:
                if line.startswith("Umask:"):
                    return int(line.split()[1], 8)
    except (OSError, ValueError):
        pass
    mask = os.umask(0o022)  # no other way to read it; set it straight back
    os.umask(mask)
    return mask


def _shown(option: str, path) -> str:
    return f"{option} = {os.fspath(path)!r}" if option else f"output {os.fspath(path)!r}"


def _first_existing(p: Path) -> Path:
    """``p`` or the nearest ancestor that exists (the current folder at worst)."""
    q = p
    while not os.path.lexists(q):
        if q.parent == q or str(q.parent) in ("", "."):
            return q.parent if os.path.lexists(q.parent) else Path(".")
        q = q.parent
    return q


def _probe_writable(folder: Path, shown: str) -> None:
    """Create and delete a file in ``folder`` (os.access ignores read-only mounts and root's rights)."""
    try:
        fd, tmp = tempfile.mkstemp(prefix=".netshape-probe.", dir=folder)
    except OSError as exc:
        raise ValueError(f"{shown}: folder {str(folder)!r} is not writable ({exc.strerror or exc})") from None
    os.close(fd)
    with contextlib.suppress(OSError):
        os.unlink(tmp)


def _check_parent(p: Path, shown: str) -> None:
    """The folder that will hold ``p``: an existing folder, or one that can be made (no file on the way)."""
    parent = p.parent if str(p.parent) else Path(".")
    anc = _first_existing(parent)
    if not anc.is_dir():
        raise ValueError(f"{shown}: lies under {str(anc)!r}, which is a file, not a folder")
    _probe_writable(anc, shown)


def check_output_file(path, option: str = "", *, make_parent: bool = False) -> Path:
    """Refuse an output file path that cannot be written (see the module doc); returns it as a Path.
    Without ``make_parent`` its folder must exist."""
    p = Path(os.fspath(path))
    shown = _shown(option, path)
    if not str(path):
        raise ValueError(f"{shown}: empty path")
    if os.path.lexists(p):
        st = os.stat(p) if p.exists() else os.lstat(p)
        if stat.S_ISDIR(st.st_mode):
            raise ValueError(f"{shown}: is a folder, not a file")
        if not stat.S_ISREG(st.st_mode):
            raise ValueError(f"{shown}: is not a regular file (a device, pipe or socket); give a file path")
    parent = p.parent if str(p.parent) else Path(".")
    if not make_parent and not parent.is_dir():
        anc = _first_existing(parent)
        if os.path.lexists(anc) and not anc.is_dir():
            raise ValueError(f"{shown}: lies under {str(anc)!r}, which is a file, not a folder")
        raise ValueError(f"{shown}: folder {str(parent)!r} does not exist")
    _check_parent(p, shown)
    return p


def check_output_folder(path, option: str = "") -> Path:
    """Refuse an output folder path that is a file, lies under a file or cannot be written (it is made
    later, by the writer). Returns it as a Path."""
    p = Path(os.fspath(path))
    shown = _shown(option, path)
    if not str(path):
        raise ValueError(f"{shown}: empty path")
    if os.path.lexists(p):
        if not p.is_dir():
            raise ValueError(f"{shown}: is a file, not a folder")
        _probe_writable(p, shown)
        return p
    _check_parent(p, shown)
    return p


def make_output_folder(path, option: str = "") -> Path:
    """:func:`check_output_folder`, then make it (and its parents)."""
    p = check_output_folder(path, option)
    try:
        p.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise ValueError(f"{_shown(option, path)}: cannot make the folder ({exc.strerror or exc})") from None
    return p


def _os_error(target: Path, exc: OSError) -> ValueError:
    why = exc.strerror or str(exc)
    if exc.errno == errno.ENOSPC:
        why = "no space left on the device"
    return ValueError(f"output {str(target)!r}: cannot be written ({why})")


def _finish(tmp: str, target: Path) -> None:
    """Give ``tmp`` the mode a new file of the user's gets (or the mode of the file it replaces), then
    rename it over ``target``, or leave that to the enclosing :func:`all_or_nothing`."""
    try:
        mode = stat.S_IMODE(os.stat(target).st_mode) if target.is_file() else 0o666 & ~_umask()
        os.chmod(tmp, mode)
        pending = _PENDING.get()
        if pending is not None:
            pending.append((tmp, target))
        else:
            os.replace(tmp, target)
    except OSError as exc:
        raise _os_error(target, exc) from None


def _temporary(target: Path) -> tuple[int, str]:
    directory = target.parent if str(target.parent) else Path(".")
    if not directory.is_dir():
        anc = _first_existing(directory)
        if os.path.lexists(anc) and not anc.is_dir():
            raise ValueError(f"output {str(target)!r}: lies under {str(anc)!r}, which is a file, not a folder")
        raise ValueError(f"output {str(target)!r}: folder {str(directory)!r} does not exist")
    if target.is_dir():
        raise ValueError(f"output {str(target)!r}: is a folder, not a file")
    if os.path.lexists(target) and target.exists() and not target.is_file():
        raise ValueError(f"output {str(target)!r}: is not a regular file (a device, pipe or socket)")
    try:
        return tempfile.mkstemp(prefix=f".{target.name}.", suffix=".tmp", dir=directory)
    except OSError as exc:
        raise _os_error(target, exc) from None


@contextlib.contextmanager
def atomic_write(path: str | os.PathLike, mode: str = "w", **kwargs) -> Iterator[IO]:
    """Open a temporary file next to ``path``; on success rename it to ``path``, on error delete it.

    ``mode`` is ``"w"`` (text, UTF-8 unless ``encoding`` is given) or ``"wb"``.
    """
    if mode not in ("w", "wb"):
        raise ValueError(f"mode = {mode!r}: must be 'w' or 'wb'")
    target = Path(path)
    if mode == "w":
        kwargs.setdefault("encoding", "utf-8")
    fd, tmp = _temporary(target)
    try:
        try:
            with os.fdopen(fd, mode, **kwargs) as fh:
                yield fh
                fh.flush()
                os.fsync(fh.fileno())
        except OSError as exc:
            raise _os_error(target, exc) from None
        _finish(tmp, target)
    except BaseException:
        with contextlib.suppress(FileNotFoundError):
            os.unlink(tmp)
        raise


@contextlib.contextmanager
def atomic_path(path: str | os.PathLike) -> Iterator[str]:
    """A temporary path next to ``path`` for a writer that takes a path (the C++ STL writer); renamed to
    ``path`` when the block succeeds, deleted when it fails. Errors naming the temporary file are
    re-raised naming ``path``."""
    target = Path(path)
    fd, tmp = _temporary(target)
    os.close(fd)
    try:
        try:
            yield tmp
        except (ValueError, OSError, RuntimeError) as exc:
            msg = str(exc)
            if os.path.basename(tmp) in msg:
                raise ValueError(msg.replace(tmp, str(target)).replace(os.path.basename(tmp), target.name)) from None
            raise
        _finish(tmp, target)
    except BaseException:
        with contextlib.suppress(FileNotFoundError):
            os.unlink(tmp)
        raise


@contextlib.contextmanager
def all_or_nothing() -> Iterator[None]:
    """Every output written inside the block (atomic_write, atomic_path, atomic_save_figure) is renamed
    into place only when the whole block succeeds; on any error all of them are deleted."""
    outer = _PENDING.get()
    pending: list = []
    token = _PENDING.set(pending)
    try:
        yield
    except BaseException:
        _PENDING.reset(token)
        for tmp, _ in pending:
            with contextlib.suppress(OSError):
                os.unlink(tmp)
        raise
    _PENDING.reset(token)
    if outer is not None:  # nested: the outer block decides
        outer.extend(pending)
        return
    for i, (tmp, target) in enumerate(pending):
        try:
            os.replace(tmp, target)
        except OSError as exc:
            for t, _ in pending[i:]:
                with contextlib.suppress(OSError):
                    os.unlink(t)
            raise _os_error(target, exc) from None


def atomic_save_figure(fig, path: str | os.PathLike, **kwargs) -> None:
    """Save a matplotlib figure atomically (format from the suffix of ``path``)."""
    target = Path(path)
    fmt = kwargs.pop("format", None) or (target.suffix.lstrip(".") or "png")
    with atomic_write(target, "wb") as fh:
        fig.savefig(fh, format=fmt, **kwargs)
