"""The edge itself: quantities parsed once, warnings warned again at the user's line, files written
with errors in the API's terms. Private to :mod:`softimpact.api`."""

from __future__ import annotations

import math
import os
import sys
import warnings
from pathlib import Path

from ..errors import HeldWarnings, InputError

# --- quantities at the edge ---------------------------------------------------------------------


def _si(value, kind: str, name: str, positive: bool = True) -> float:
    """``value`` (a unit string or a pint quantity) as an SI float of ``kind``, positive unless ``positive`` is False (a
    position) and within its physical range (:data:`softimpact.input.toml.PHYSICAL_RANGES`); an InputError naming
    ``name``, the argument the user gave, and echoing the value as given, with its unit (``length: must be positive,
    got '-250 mm'``), never the layers' own names and SI floats."""
    from .. import units
    from ..input.toml import check_physical

    if hasattr(value, "magnitude") and hasattr(value, "to"):  # a pint quantity, of any registry
        try:
            si = float(value.to(units.SI_UNITS[kind]).magnitude)
        except Exception:  # pint's DimensionalityError and friends
            raise InputError(f"{name}: {value!r} is not {units.a_or_an(kind)}") from None
        if not math.isfinite(si):
            raise InputError(f"{name}: {value!r} is not a finite {kind}")
        shown = str(value)
    else:
        si, shown = units.parse(value, kind, name), value
    if positive and not si > 0:
        raise InputError(f"{name}: must be positive, got {shown!r}")
    return check_physical(si, kind, name, shown, positive)


def _text(value, kind: str, name: str) -> str | None:
    """A quantity as the text an app function parses; None stays None. Checked here (an error names
    ``name``); a unit string passes as given (the app parses it with the same :func:`softimpact.units.parse`,
    to the same float, and its lines and warnings then quote the user's units as the command line's do),
    a pint quantity as its SI value (``"0.0127 m"``)."""
    if value is None:
        return None
    from ..units import SI_UNITS

    si = _si(value, kind, name)
    return value if isinstance(value, str) else f"{si!r} {SI_UNITS[kind]}"


def _material(value, name: str):
    from ..models.materials import Material, lookup

    if isinstance(value, Material):
        return value
    if not isinstance(value, str):
        raise InputError(f"{name}: expected a catalogue material name or a Material, got {type(value).__name__}")
    return lookup(value, name)


def _point(value, name: str) -> tuple[float, float]:
    if isinstance(value, str) or not hasattr(value, "__len__") or len(value) != 2:
        raise InputError(f"{name}: expected a point (x, y) of two lengths, got {value!r}")
    return (_si(value[0], "length", f"{name}[0]", positive=False), _si(value[1], "length", f"{name}[1]", positive=False))


def _elements(value, count: int, name: str) -> tuple[int, ...]:
    values = (value,) if isinstance(value, int) and count == 1 else tuple(value) if hasattr(value, "__len__") else ()
    if len(values) != count or not all(isinstance(n, int) and not isinstance(n, bool) and n >= 1 for n in values):
        raise InputError(f"{name}: expected {count} positive integer(s), got {value!r}")
    return values


# --- keywords at the edge ---------------------------------------------------------------------------


class KeywordError(InputError, TypeError):
    """A keyword the function or class does not take (a misspelling, most often): an :class:`InputError` naming it
    with the nearest keyword it takes, and a TypeError, what Python itself raises for an unknown keyword."""


def misspelt(name: str, known, what: str) -> KeywordError:
    """The error for the keyword ``name`` that ``what`` (``"si.Plate"``) does not take among ``known``: the nearest
    of them suggested (difflib, as a case file's misspelt key is), all of them listed otherwise."""
    import difflib

    near = difflib.get_close_matches(name, list(known), n=1, cutoff=0.6)
    hint = f"did you mean {near[0]!r}?" if near else f"it takes {', '.join(known)}"
    return KeywordError(f"{name}: not a keyword of {what} ({hint})", name)


def keywords(what: str):
    """Decorate an API function (or a class's ``__init__``) so that a keyword it does not take is a
    :class:`KeywordError` naming it and suggesting the nearest it takes (``lenght`` → ``length``), not Python's bare
    TypeError; everything else passes to the function unchanged."""
    import functools
    import inspect

    def decorate(fn):
        sig = inspect.signature(fn)
        known = [p.name for p in sig.parameters.values() if p.name != "self" and p.kind in (p.POSITIONAL_OR_KEYWORD, p.KEYWORD_ONLY)]
        takes_any = any(p.kind is p.VAR_KEYWORD for p in sig.parameters.values())

        @functools.wraps(fn)
        def wrapper(*args, **kwargs):
            if not takes_any:
                for name in kwargs:
                    if name not in known:
                        raise misspelt(name, known, what)
            return fn(*args, **kwargs)

        return wrapper

    return decorate


# --- warnings at the edge --------------------------------------------------------------------------

_PACKAGE = tuple({os.path.dirname(os.path.dirname(__file__)) + os.sep, str(Path(__file__).resolve().parent.parent) + os.sep})  # as imported, and resolved


def _one_line(text) -> str:
    """A warning's text on one line, as the command line shows it and keeps it for manifest.json."""
    return " ".join(str(text).split())


class _Heard(HeldWarnings):
    """Collects the warnings raised below one API call and, on leaving, warns them again at the user's line.

    The command line shows each :class:`~softimpact.errors.SoftimpactWarning` raised below a command
    (:func:`softimpact.models.validity.warn` and friends) as a ``softimpact: warning:`` line and keeps
    it for manifest.json; here each is warned again, a SoftimpactWarning pointing at the first frame
    outside softimpact (the user's call), and its one-line text kept in :attr:`texts` for the result's
    manifest.json. Any other warning passes on unchanged (:class:`~softimpact.errors.HeldWarnings`).
    Used as ``with _Heard() as heard: ...``.
    """

    def __enter__(self):
        self.texts: list[str] = []
        return super().__enter__()

    def __exit__(self, *exc):
        super().__exit__(*exc)
        level, frame = 1, sys._getframe(0)
        while frame is not None and frame.f_code.co_filename.startswith(_PACKAGE):
            level, frame = level + 1, frame.f_back
        for w in self.held:
            self.texts.append(_one_line(w.message))
            warnings.warn(w.message, stacklevel=level)
        return False


def _write(out, files: dict, inputs, manifest: dict, force: bool) -> list[Path]:
    """:func:`softimpact.output.files.write_outputs`, its errors naming ``write`` and ``force=True``
    (the API's terms) where the command line's name ``--out`` and ``--force``."""
    from ..output.files import write_outputs

    try:
        return write_outputs(out, files, inputs=inputs, manifest=manifest, force=force)
    except InputError as exc:
        text = str(exc)
        if not text.startswith("--out: "):
            raise
        text = "write: " + text.removeprefix("--out: ")
        raise InputError(text.replace("`softimpact --force ...`", "write(..., force=True)"), exc.argument) from None


def _naming():
    """Errors of the problem classes name the API's arguments (time_step, at, gauges)."""
    from ..input.toml import naming

    return naming({"position": "at", "gauges": "gauges", "time_step": "time_step", "duration": "duration"})
