"""Output files: CSV and JSON text, figures as bytes, and atomic writes into a folder.

:func:`write_outputs` is the only way results reach the disk: every file is
first written into a hidden staging folder inside DIR, then moved into place
with :func:`os.replace`, so a run that fails leaves no half-written file that
looks complete, and an input file is never overwritten.

With a manifest, the run also writes ``manifest.json`` (last): its files and
their SHA-256, the inputs and theirs, the package version, status and command.
A reused DIR never mixes runs: the files the previous manifest lists that this
run does not rewrite are removed (only those, and only while unchanged since
that run wrote them). The staging folder is named ``.softimpact-<pid>-…``; it is
removed on SIGTERM, and one left by a killed run is removed by the next run.
"""

from __future__ import annotations

import hashlib
import io
import json
import math
import os
import shutil
import signal
import tempfile
import threading
import time
from dataclasses import asdict, is_dataclass
from pathlib import Path

import numpy as np

from .. import __version__
from ..errors import InputError

__all__ = ["csv_text", "json_text", "jsonable", "figure_bytes", "write_outputs", "check_writable", "sha256", "MANIFEST", "STAGING_PREFIX"]

MANIFEST = "manifest.json"
STAGING_PREFIX = ".softimpact-"  # staging folders: .softimpact-<pid>-<random>
STALE_AGE = 3600.0  # s: a staging folder without a readable pid this old is a leftover


def strain_peaks(time: np.ndarray, eps: np.ndarray, window_end: bool = False) -> dict:
    """A gauge's peak tensile and compressive strain and their times, the fields every
    command's summary gives; with ``window_end``, which of them sit on the run's last sample
    (the strain may still be growing there)."""
    kmax, kmin = int(np.argmax(eps)), int(np.argmin(eps))
    out = {
        "peak_tensile_strain": float(eps[kmax]),
        "time_of_peak_tensile_strain_s": float(time[kmax]),
        "peak_compressive_strain": float(eps[kmin]),
        "time_of_peak_compressive_strain_s": float(time[kmin]),
    }
    if window_end:
        last = len(time) - 1
        out["peak_at_window_end"] = [name for name, k in (("tensile", kmax), ("compressive", kmin)) if k == last]
    return out


def energy_balance(energy) -> float:
    """Largest |kinetic + strain − work| over the run (:class:`softimpact.fem.energies.Energies`), relative to the largest work."""
    return float(np.max(np.abs(energy.balance_error)) / max(np.max(np.abs(energy.work)), 1e-300))


def csv_text(columns: dict[str, np.ndarray]) -> str:
    """CSV text of equal-length columns, full precision (repr of float64); text cells holding a
    comma, quote or line break are quoted (RFC 4180), so the file reads back column for column."""
    names = list(columns)
    data = [np.asarray(columns[n]) for n in names]
    lengths = {len(d) for d in data}
    if len(lengths) != 1:
        raise ValueError(f"columns of unequal length: {dict(zip(names, map(len, data)))}")
    cells = [_column(d) for d in data]
    buf = io.StringIO()
    buf.write(",".join(map(_quoted, names)) + "\n")
    for row in zip(*cells):
        buf.write(",".join(row) + "\n")
    return buf.getvalue()


def _column(d: np.ndarray) -> list[str]:
    """The cells of one column: floats as the shortest repr that reads back exactly, NaN empty."""
    if d.dtype.kind == "f":
        return ["" if c == "nan" else c for c in map(repr, d.tolist())]
    return [_cell(v) for v in d]


def _quoted(text: str) -> str:
    text = str(text)
    return '"' + text.replace('"', '""') + '"' if any(c in text for c in ',"\n\r') else text


def _cell(v) -> str:
    if isinstance(v, (str, np.str_)):
        return _quoted(v)
    f = float(v)
    return "" if math.isnan(f) else repr(f)


def jsonable(obj):
    """Dataclasses, numpy scalars and arrays, NaN → JSON-ready values (NaN → null)."""
    if is_dataclass(obj) and not isinstance(obj, type):
        return jsonable(asdict(obj))
    if isinstance(obj, dict):
        return {str(k): jsonable(v) for k, v in obj.items()}
    if isinstance(obj, (list, tuple)):
        return [jsonable(v) for v in obj]
    if isinstance(obj, np.ndarray):
        return jsonable(obj.tolist())
    if isinstance(obj, (np.floating, float)):
        f = float(obj)
        return f if math.isfinite(f) else None
    if isinstance(obj, (np.integer,)):
        return int(obj)
    if isinstance(obj, (np.bool_,)):
        return bool(obj)
    return obj


def json_text(obj) -> str:
    """Indented JSON with ``softimpact_version`` added to a top-level dict."""
    data = jsonable(obj)
    if isinstance(data, dict):
        data = {**data, "softimpact_version": __version__}
    return json.dumps(data, indent=2, allow_nan=False) + "\n"


def figure_bytes(fig, fmt: str = "png") -> bytes:
    """Render a matplotlib figure to bytes and close it."""
    import matplotlib.pyplot as plt

    buf = io.BytesIO()
    fig.savefig(buf, format=fmt, dpi=120, bbox_inches="tight")
    plt.close(fig)
    return buf.getvalue()


def sha256(data: bytes | str) -> str:
    """Hex SHA-256 of bytes (text is encoded as UTF-8, as written)."""
    return hashlib.sha256(data.encode("utf-8") if isinstance(data, str) else data).hexdigest()


def _file_sha256(path: Path) -> str | None:
    h = hashlib.sha256()
    try:
        with open(path, "rb") as fh:
            for block in iter(lambda: fh.read(1 << 20), b""):
                h.update(block)
    except OSError:
        return None
    return h.hexdigest()


def check_writable(out_dir) -> None:
    """Refuse an output folder that cannot be created or written (before any computing).

    Nothing is left behind: an empty folder is made and removed in the folder
    itself, or in its nearest existing parent.
    """
    out = Path(out_dir)
    if out.exists() and not out.is_dir():
        raise InputError(f"--out: {out} exists and is not a folder")
    probe = out
    while not probe.exists():
        if probe.parent == probe:
            break
        probe = probe.parent
    if not probe.is_dir():
        raise InputError(f"--out: cannot create {out}: {probe} is not a folder")
    try:  # the only sure test (read-only mounts, /proc, root on a chmod-ed folder): make and remove a folder
        os.rmdir(tempfile.mkdtemp(prefix=f"{STAGING_PREFIX}{os.getpid()}-probe-", dir=probe))
    except OSError as exc:
        raise InputError(f"--out: cannot write into {out} ({exc.strerror or exc} at {probe})") from None


def _pid_alive(pid: int) -> bool:
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except (PermissionError, OSError):
        return True
    return True


def _remove_stale_staging(out: Path) -> None:
    """Remove staging folders left by killed runs (their pid is gone, or they are old)."""
    for entry in out.glob(STAGING_PREFIX + "*"):
        if not entry.is_dir():
            continue
        pid_text = entry.name[len(STAGING_PREFIX) :].split("-", 1)[0]
        if pid_text.isdigit():
            stale = int(pid_text) != os.getpid() and not _pid_alive(int(pid_text))
        else:
            try:
                stale = time.time() - entry.stat().st_mtime > STALE_AGE
            except OSError:
                stale = False
        if stale:
            shutil.rmtree(entry, ignore_errors=True)


def _previous_files(out: Path) -> dict[str, str]:
    """The files (name → sha256) listed by a previous run's manifest in ``out`` (empty if none or unreadable)."""
    try:
        data = json.loads((out / MANIFEST).read_text(encoding="utf-8"))
        files = data.get("files", {})
        return {str(k): str(v) for k, v in files.items()} if isinstance(files, dict) else {}
    except (OSError, ValueError, AttributeError):
        return {}


def _remove_previous(out: Path, previous: dict[str, str], keep) -> None:
    """Remove the previous run's files not rewritten now: only listed names inside ``out``, unchanged since."""
    root = out.resolve()
    for name, digest in previous.items():
        if name in keep or name == MANIFEST:
            continue
        path = (out / name).resolve()
        if root not in path.parents or not path.is_file() or path.is_symlink():
            continue
        if _file_sha256(path) == digest:
            path.unlink()
            parent = path.parent
            while parent != root and parent.is_dir() and not any(parent.iterdir()):
                parent.rmdir()
                parent = parent.parent


class _RemoveOnTerm:
    """While active, SIGTERM removes the staging folder and exits (143) instead of leaving it behind."""

    def __init__(self, staging: Path):
        self.staging, self.previous = staging, None

    def __enter__(self):
        if threading.current_thread() is threading.main_thread():
            self.previous = signal.signal(signal.SIGTERM, self._handle)
        return self

    def _handle(self, signum, frame):
        shutil.rmtree(self.staging, ignore_errors=True)
        raise SystemExit(128 + signum)

    def __exit__(self, *exc):
        if self.previous is not None:
            signal.signal(signal.SIGTERM, self.previous)
        return False


def write_outputs(out_dir, files: dict[str, bytes | str], inputs=(), manifest: dict | None = None) -> list[Path]:
    """Write ``files`` (relative name → content) into ``out_dir`` atomically.

    All files are staged in a hidden folder inside ``out_dir`` and moved into
    place only once all are written. Refuses to overwrite any of ``inputs``.
    With ``manifest`` (a dict: status, command, …) ``manifest.json`` is added
    with the files' and inputs' SHA-256 and the version, and the previous run's
    files this run does not rewrite are removed (see the module docstring).
    Returns the paths written (the manifest not included).
    """
    out = Path(out_dir)
    protected = {Path(p).resolve() for p in inputs}
    names = list(files) + ([MANIFEST] if manifest is not None else [])
    targets = {name: (out / name) for name in names}
    for name, target in targets.items():
        if target.resolve() in protected:
            raise InputError(f"--out: writing {name} would overwrite the input {target}")
    check_writable(out)
    try:
        out.mkdir(parents=True, exist_ok=True)
        _remove_stale_staging(out)
        staging = Path(tempfile.mkdtemp(prefix=f"{STAGING_PREFIX}{os.getpid()}-", dir=out))
    except OSError as exc:
        raise InputError(f"--out: cannot write into {out} ({exc.strerror})") from None
    try:
        with _RemoveOnTerm(staging):
            content_of = dict(files)
            if manifest is not None:
                content_of[MANIFEST] = _manifest_text(files, inputs, manifest)
            for name, content in content_of.items():
                path = staging / name
                path.parent.mkdir(parents=True, exist_ok=True)
                if isinstance(content, str):
                    path.write_text(content, encoding="utf-8")
                else:
                    path.write_bytes(content)
            if manifest is not None:
                _remove_previous(out, _previous_files(out), set(files))
            for name, target in targets.items():  # the manifest last: it lists a complete run
                target.parent.mkdir(parents=True, exist_ok=True)
                os.replace(staging / name, target)
    except OSError as exc:
        raise InputError(f"--out: cannot write into {out} ({exc.strerror or exc})") from None
    finally:
        shutil.rmtree(staging, ignore_errors=True)
    return [targets[name] for name in files]


def _manifest_text(files: dict, inputs, manifest: dict) -> str:
    """manifest.json: status and command (from ``manifest``), files and inputs with their SHA-256, version."""
    listed_inputs = {}
    for p in inputs:
        digest = _file_sha256(Path(p))
        listed_inputs[str(p)] = digest
    data = {
        **manifest,
        "files": {name: sha256(content) for name, content in sorted(files.items())},
        "inputs": listed_inputs,
    }
    return json_text(data)
