"""Output files: CSV and JSON text, figures as bytes, and atomic writes into a folder.

:func:`write_outputs` is the only way results reach the disk: every file is
first written into a hidden staging folder inside DIR, then moved into place
with :func:`os.replace`, so a run that fails leaves no half-written file that
looks complete, and an input file is never overwritten.

With a manifest, the run also writes ``manifest.json`` (last): its files and
their SHA-256, the inputs and theirs, the package version, status and command,
signed as softimpact's (``generator`` and ``signature``: a SHA-256 over the files'
names and hashes). A reused DIR never mixes runs: the files the previous manifest
lists that this run does not rewrite are removed (only those, only while unchanged
since that run wrote them, never a file this run reads — a law.json an earlier
``identify`` wrote there, now a case's input —, and only when that manifest is softimpact's own: another
tool's ``manifest.json`` lists nothing softimpact may touch, and is itself the
user's file). Every writer takes the folder's lock (:data:`LOCK`), the command line
for the whole run (:func:`claim_output`), a Python ``.write()`` for its write. The staging folder is named ``.softimpact-<pid>-…``; it is
removed on SIGTERM, and one left by a killed run is removed by the next run.
"""

from __future__ import annotations

import contextvars
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
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path

import numpy as np

from ..errors import InputError
from ..formats._json import json_text, jsonable  # noqa: F401  (re-exported: the writers of output/ use them from here)

__all__ = [
    "case_record",
    "with_units",
    "csv_text",
    "json_text",
    "jsonable",
    "figure_bytes",
    "FIGURE_FORMATS",
    "figure_format",
    "with_figure_format",
    "write_outputs",
    "check_writable",
    "claim_output",
    "foreign_files",
    "sha256",
    "MANIFEST",
    "STAGING_PREFIX",
    "LOCK",
]

MANIFEST = "manifest.json"
STAGING_PREFIX = ".softimpact-"  # staging folders: .softimpact-<pid>-<random>
STALE_AGE = 3600.0  # s: a staging folder without a readable pid this old is a leftover
GENERATOR = "softimpact"  # manifest.json's "generator": the manifests softimpact trusts as its own
SIGNATURE_TAG = "softimpact-manifest-1\n"  # prefix of the text a manifest's "signature" hashes
LOCK = ".softimpact.lock"  # held in DIR while a run computes and writes: a second run into DIR exits 2 at once
# What a softimpact run may write: a file in DIR with one of these suffixes that no previous manifest lists
# unchanged is the user's, and stops a run before any computing (``force`` to proceed).
STATE_FOLDERS = ("checkpoints",)  # a resumable run's own state (sweep checkpoints): read and rewritten by the next run, never the user's
OUTPUT_SUFFIXES = (".csv", ".json", ".png", ".svg", ".pdf", ".html", ".parquet", ".xdmf", ".h5", ".vtu")


def case_record(problem) -> dict:
    """summary.json's ``case_SI``: the resolved problem's fields (SI), as written before; an ``impactor``
    without a material of its own (a coupled case's, whose material is its ``impactor_material``) is
    written as its mass, diameter and velocity."""
    from dataclasses import fields

    out = {f.name: getattr(problem, f.name) for f in fields(problem)}  # the fields by name, in their declared order (asdict's)
    imp = out.get("impactor")
    if imp is not None and imp.material is None:
        out["impactor"] = {"mass": imp.mass, "diameter": imp.diameter, "velocity": imp.velocity}
    return out


def with_units(summary: dict, units: str) -> dict:
    """summary.json's content with the display system ``units`` written into its resolved case
    (``case_SI.units``, and ``case_SI.target.units`` of an impact's target), as the problems carried it
    before: the display is the edges' choice (app, api), the problems hold SI only."""
    case = summary.get("case_SI")
    if case is None:
        return summary
    case = dict(case) if isinstance(case, dict) else case_record(case)
    target = case.get("target")
    if target is not None:
        case["target"] = {**(dict(target) if isinstance(target, dict) else case_record(target)), "units": units}
    case["units"] = units
    return {**summary, "case_SI": case}


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


FIGURE_FORMATS = ("png", "svg", "pdf")  # raster (FIGURE_DPI) or vector
FIGURE_DPI = 120
# report.html shows a figure at most 968 px wide (body 1000 px less 1 em of padding each side): a figure this wide
# [in] is shown unshrunk, so its text keeps its size; REPORT_TEXT_PT the least text size of the report's figures
REPORT_WIDTH_IN = (1000 - 2 * 16) / FIGURE_DPI
REPORT_TEXT_PT = 9
# The format figures are drawn in for the command being run (``--figure-format``): the CLI sets it
# around one command and resets it after; the names stay "*.png" until :func:`with_figure_format`.
figure_format: contextvars.ContextVar[str] = contextvars.ContextVar("softimpact_figure_format", default="png")


def figure_bytes(fig, fmt: str | None = None) -> bytes:
    """Render a matplotlib figure to bytes (``fmt``, default the run's :data:`figure_format`) and close it."""
    import matplotlib.pyplot as plt

    buf = io.BytesIO()
    fmt = fmt or figure_format.get()
    fig.savefig(buf, format=fmt, dpi=FIGURE_DPI, bbox_inches="tight")
    plt.close(fig)
    return _small_png(buf.getvalue()) if fmt == "png" else buf.getvalue()


PNG_COLOURS = 256  # a figure's PNG as a palette of this many colours, when that changes no pixel visibly (_small_png)


def _small_png(data: bytes) -> bytes:
    """A matplotlib PNG (RGBA, opaque) about 2.5 times smaller (55 ms a figure): its colours reduced to a palette of
    PNG_COLOURS (median cut, no dithering: a plot's few hundred distinct colours plus its anti-aliasing);
    kept as it was when the palette moves the pixels' channels by more than half a level of 255 on average (a figure
    of many shades: none of the report's, measured 0.05-0.3), or when the result is not smaller."""
    import numpy as np
    from PIL import Image

    with Image.open(io.BytesIO(data)) as image:
        if image.mode not in ("RGB", "RGBA") or (image.mode == "RGBA" and image.getextrema()[3][0] < 255):
            return data  # a transparent figure keeps its alpha
        rgb = image.convert("RGB")
    palette = rgb.quantize(PNG_COLOURS, method=Image.Quantize.MEDIANCUT, dither=Image.Dither.NONE)
    # every third row: the mean to well within its threshold at a third of the cost
    error = np.abs(np.asarray(palette.convert("RGB"), dtype=np.int16)[::3] - np.asarray(rgb, dtype=np.int16)[::3])
    if error.mean() > 0.5:
        return data
    out = io.BytesIO()
    palette.save(out, format="PNG")  # zlib's default level: optimize=True or level 9 would save 9 % more for twice the time
    return out.getvalue() if out.tell() < len(data) else data


def with_figure_format(files: dict[str, bytes | str], fmt: str) -> dict[str, bytes | str]:
    """The outputs with their figures named for ``fmt`` ("x.png" → "x.svg"), and the names
    rewritten in the HTML reports that link them; unchanged for png."""
    if fmt == "png":
        return files
    renamed = {n: n[: -len(".png")] + "." + fmt for n, v in files.items() if n.endswith(".png") and isinstance(v, bytes)}
    out = {}
    for name, value in files.items():
        if name.endswith(".html") and isinstance(value, str):
            for old, new in renamed.items():
                value = value.replace(f"'{old}'", f"'{new}'").replace(f'"{old}"', f'"{new}"')
        out[renamed.get(name, name)] = value
    return out


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


def _resolved(paths) -> set[Path]:
    """The files ``paths`` resolved (symlinks followed): a run's inputs, whatever path named them."""
    out = set()
    for p in paths:
        try:
            out.add(Path(p).resolve())
        except (OSError, RuntimeError, ValueError):
            continue
    return out


def check_writable(out_dir) -> None:
    """Refuse, before any computing, an output folder that cannot be created or written.

    ``--out`` must be a non-empty path; a symlink that points nowhere is refused (it would
    be created through, somewhere the user did not name). Nothing is left behind: an empty
    folder is made and removed in the folder itself, or in its nearest existing parent.
    """
    if out_dir is None or not str(out_dir).strip():
        raise InputError("--out: give a folder (an empty path would write into the working folder)")
    out = Path(out_dir)
    if out.is_symlink() and not out.exists():
        raise InputError(f"--out: {out} is a symlink to {os.readlink(out)}, which does not exist")
    if out.exists() and not out.is_dir():
        raise InputError(f"--out: {out} exists and is not a folder")
    probe = out
    while not probe.exists():
        if probe.is_symlink():
            raise InputError(f"--out: cannot create {out}: {probe} is a symlink to {os.readlink(probe)}, which does not exist")
        if probe.parent == probe:
            break
        probe = probe.parent
    if not probe.is_dir():
        raise InputError(f"--out: cannot create {out}: {probe} is not a folder")
    try:  # the only sure test (read-only mounts, /proc, root on a chmod-ed folder): make and remove a folder
        os.rmdir(tempfile.mkdtemp(prefix=f"{STAGING_PREFIX}{os.getpid()}-probe-", dir=probe))
    except OSError as exc:
        raise InputError(f"--out: cannot write into {out} ({exc.strerror or exc} at {probe})") from None


def foreign_files(out_dir, inputs=(), names=None) -> list[Path]:
    """Files in ``out_dir`` a run could replace that are not a previous run's.

    ``names``: the run's exact output names (relative): those present that the previous manifest
    does not list, or that changed since it wrote them (checked when writing). None: before
    computing, when the names are not known yet, every file with an output suffix
    (:data:`OUTPUT_SUFFIXES`) that no previous manifest lists (an edited output is caught when
    writing, and only if this run writes it). ``inputs`` are never counted (write_outputs refuses
    to write over them anyway)."""
    out = Path(out_dir)
    if not out.is_dir():
        return []
    previous = _previous_files(out)
    protected = _resolved(inputs)
    if names is None:  # before computing, this run's inputs are not all known yet: the previous run's read files are the user's too
        protected |= _previous_inputs(out)
        candidates = [
            p
            for p in out.rglob("*")
            if p.suffix.lower() in OUTPUT_SUFFIXES
            and not any(part.startswith(STAGING_PREFIX) for part in p.relative_to(out).parts)
            and p.relative_to(out).parts[0] not in STATE_FOLDERS
        ]
    else:
        candidates = [out / n for n in names]
    found = []
    for path in candidates:
        if not (path.is_file() or path.is_symlink()) or path.resolve() in protected:
            continue
        name = path.relative_to(out).as_posix()
        if name == MANIFEST:
            if _foreign_manifest(out):
                found.append(path)
            continue
        if path.is_symlink() or name not in previous or (names is not None and previous[name] != _file_sha256(path)):
            found.append(path)
    return sorted(found)


def _foreign_error(out: Path, found: list[Path]) -> InputError:
    names = ", ".join(p.relative_to(out).as_posix() for p in found[:3]) + (f" and {len(found) - 3} more" if len(found) > 3 else "")
    return InputError(
        f"--out: {out} holds {names}, which no earlier softimpact run wrote there (or which changed since): "
        "a run would overwrite it; choose a fresh folder, or `softimpact --force ...` to replace it"
    )


@contextmanager
def claim_output(out_dir, *, force: bool = False, inputs=()) -> Iterator[Path]:
    """Hold ``out_dir`` for one run, checked before any computing (exit 2 on any problem).

    The folder must be writable (:func:`check_writable`); it is created if needed and locked
    (:data:`LOCK`, a :class:`filelock.FileLock`): a second run into it fails at once instead of
    both reporting success. Unless ``force``, a file of the user's that the run could replace
    (:func:`foreign_files`) stops it. On leaving, the lock is released and its file removed, and a
    folder this call created and nothing was written into is removed again.
    """
    from filelock import FileLock, Timeout

    check_writable(out_dir)
    out = Path(out_dir)
    created = not out.exists()
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise InputError(f"--out: cannot create {out} ({exc.strerror or exc})") from None
    lock = FileLock(str(out / LOCK), timeout=0)
    try:
        lock.acquire()
    except Timeout:
        raise InputError(f"--out: another softimpact run is writing into {out} (it holds {out / LOCK}); wait for it or choose another folder") from None
    except OSError as exc:
        raise InputError(f"--out: cannot lock {out} ({exc.strerror or exc})") from None
    _HELD.add(out.resolve())
    try:
        if not force:
            found = foreign_files(out, inputs)
            if found:
                raise _foreign_error(out, found)
        yield out
    finally:
        _HELD.discard(out.resolve())
        lock.release()
        try:
            (out / LOCK).unlink()
        except OSError:
            pass
        if created:
            try:
                out.rmdir()  # only if empty: the run wrote nothing
            except OSError:
                pass


_HELD: set[Path] = set()  # folders whose lock this process holds (claim_output): its own writes go ahead


@contextmanager
def _folder_lock(out: Path) -> Iterator[None]:
    """The folder's lock for one write, unless this process already holds it (:func:`claim_output`):
    a Python ``.write()`` into a folder a running command holds is refused, not silently mixed."""
    from filelock import FileLock, Timeout

    here = out.resolve()
    if here in _HELD or any(held in here.parents for held in _HELD):  # inside a folder this run holds
        yield
        return
    lock = FileLock(str(out / LOCK), timeout=0)
    try:
        lock.acquire()
    except Timeout:
        raise InputError(f"--out: another softimpact run is writing into {out} (it holds {out / LOCK}); wait for it or choose another folder") from None
    except OSError as exc:
        raise InputError(f"--out: cannot lock {out} ({exc.strerror or exc})") from None
    try:
        yield
    finally:
        lock.release()
        try:
            (out / LOCK).unlink()
        except OSError:
            pass


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


def signature(files: dict[str, str]) -> str:
    """A manifest's ``signature``: the SHA-256 of its files' names and hashes (``files``: name → sha256),
    after :data:`SIGNATURE_TAG`. Not a secret: it tells softimpact's manifests from another tool's
    ``manifest.json`` (and from one edited by hand), whose listed files are never softimpact's to replace."""
    return sha256(SIGNATURE_TAG + json.dumps(dict(sorted(files.items())), separators=(",", ":")))


def _own_manifest(out: Path) -> dict | None:
    """The files (name → sha256) of ``out``'s manifest.json when softimpact signed it; None when it has
    none, or one softimpact did not write (another tool's, an edited one, an unreadable one)."""
    try:
        data = json.loads((out / MANIFEST).read_text(encoding="utf-8"))
    except (OSError, ValueError):
        return None
    files = data.get("files") if isinstance(data, dict) else None
    if not isinstance(files, dict) or data.get("generator") != GENERATOR:
        return None
    files = {str(k): str(v) for k, v in files.items()}
    return files if data.get("signature") == signature(files) else None


def _previous_files(out: Path) -> dict[str, str]:
    """The files (name → sha256) listed by a previous softimpact run's signed manifest in ``out``
    (empty if none, or if the manifest there is not softimpact's)."""
    return _own_manifest(out) or {}


def _previous_inputs(out: Path) -> set[Path]:
    """The files a previous softimpact run into ``out`` read (its signed manifest's ``inputs``), resolved."""
    if _own_manifest(out) is None:
        return set()
    try:
        listed = json.loads((out / MANIFEST).read_text(encoding="utf-8")).get("inputs")
    except (OSError, ValueError, AttributeError):
        return set()
    return _resolved(listed) if isinstance(listed, dict) else set()


def _foreign_manifest(out: Path) -> bool:
    """Whether ``out`` holds a manifest.json softimpact did not write (the user's or another tool's)."""
    path = out / MANIFEST
    return (path.is_file() or path.is_symlink()) and (path.is_symlink() or _own_manifest(out) is None)


def _remove_previous(out: Path, previous: dict[str, str], keep, inputs=()) -> None:
    """Remove the previous run's files not rewritten now: only listed names inside ``out``, unchanged since, and
    never a file this run reads (``inputs``: a law.json an earlier ``identify`` wrote into ``out``, read by this
    run's case, stays where it is, the earlier run's manifest notwithstanding)."""
    root = out.resolve()
    protected = _resolved(inputs)
    for name, digest in previous.items():
        if name in keep or name == MANIFEST:
            continue
        path = (out / name).resolve()
        if root not in path.parents or not path.is_file() or (out / name).is_symlink() or path in protected:
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


def write_outputs(out_dir, files: dict[str, bytes | str], inputs=(), manifest: dict | None = None, force: bool = False) -> list[Path]:
    """Write ``files`` (relative name → content) into ``out_dir`` atomically.

    All files are staged in a hidden folder inside ``out_dir`` and moved into
    place only once all are written. Refuses to overwrite any of ``inputs``.
    With ``manifest`` (a dict: status, command, …) ``manifest.json`` is added
    with the files' and inputs' SHA-256 and the version, and the previous run's
    files this run does not rewrite are removed (see the module docstring).
    A file with an output's name that no previous manifest lists unchanged is the user's: it is
    never replaced (InputError naming it, nothing written) unless ``force``.
    Returns the paths written (the manifest not included).
    """
    if "\x00" in str(out_dir):  # no file system takes it (os raises ValueError, not OSError)
        raise InputError(f"--out: {str(out_dir)!r} holds a NUL character, which no folder name can")
    out = Path(out_dir)
    protected = _resolved(inputs)
    names = list(files) + ([MANIFEST] if manifest is not None else [])
    targets = {name: (out / name) for name in names}
    for name, target in targets.items():
        if target.resolve() in protected:
            raise InputError(f"--out: writing {name} would overwrite the input {target}")
    check_writable(out)
    if not force:
        found = foreign_files(out, inputs, names)
        if found:
            raise _foreign_error(out, found)
    try:
        out.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise InputError(f"--out: cannot write into {out} ({exc.strerror})") from None
    with _folder_lock(out):
        return _write_staged(out, files, inputs, manifest, targets)


def _write_staged(out: Path, files: dict, inputs, manifest: dict | None, targets: dict) -> list[Path]:
    """:func:`write_outputs`' write, the folder held: staged, then moved into place, the manifest last."""
    try:
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
                _remove_previous(out, _previous_files(out), set(files), inputs)
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
    listed = {name: sha256(content) for name, content in sorted(files.items())}
    data = {
        **manifest,
        "files": listed,
        "inputs": listed_inputs,
        "generator": GENERATOR,
        "signature": signature(listed),
    }
    return json_text(data)
