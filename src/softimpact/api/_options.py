"""The API's keyword arguments from the tables the command line reads (:mod:`softimpact.app.options`),
and errors in the API's terms. Private to :mod:`softimpact.api`.

:func:`takes` gives a function the signature and the Parameters of its table; :func:`given` checks the
keywords of one call against it before anything is computed (an unknown keyword is a TypeError, as
Python's own; a bad value an InputError naming the keyword); :func:`python_terms` re-raises an
InputError of the layers below, written for the command line (``--measured``, ``softimpact
--ignore-limits``), in the API's words (``measured``, the environment variable).
"""

from __future__ import annotations

import inspect
import math
import os
import re
from contextlib import contextmanager

from ..errors import InputError
from ._edge import _text, misspelt

__all__ = ["takes", "given", "python_terms"]

_MARK = "{options}"  # the line of a docstring's Parameters section where the table's entries go


def _type_text(o) -> str:
    """The numpydoc type of an option."""
    if o.kind is not None:
        text = "str or pint.Quantity"
    elif o.choices:
        text = "{" + ", ".join(repr(c) for c in o.choices) + "}"
    elif o.file:
        text = "str or Path"
    else:
        text = o.type.__name__
    return text + (", optional" if o.default is None and not o.required else "")


# A help text's table placeholders (:data:`softimpact.app.options.HELP_TABLES`) in a docstring, which is written when
# the API is imported (the tables import numpy: the command line fills them when --help is shown)
_TABLE_WORDS = {
    "contact_laws": "the contact laws si.catalogue() lists",
    "projectiles": "the projectiles si.catalogue() lists",
    "scaling_presets": "the presets' own names",
    "materials": "a material si.catalogue() lists",
}


def _entry(o, indent: str) -> str:
    """The Parameters entry of an option: its help (its tables' placeholders in words), the unit kind in brackets, the default."""
    text = o.help
    for key, words in _TABLE_WORDS.items():
        text = text.replace("{" + key + "}", words)
    help = text if o.kind is None else f"{text} [{o.kind}]"
    default = f" Default {o.default!r}." if o.default is not None else ""
    return f"{indent}{o.name} : {_type_text(o)}\n{indent}    {help}{default}"


def takes(table, *leading: str):
    """Decorate an API function ``fn(*leading, **options)``: its signature becomes the ``leading``
    positional parameters, its own keyword-only ones (``sweep(spec, *, out, **options)``'s ``out``) and the
    options of ``table`` (keyword-only, with their defaults), and the line
    ``{options}`` of its docstring the table's Parameters entries. The function itself is returned (its
    doctests stay its module's)."""

    def decorate(fn):
        params = [inspect.Parameter(n, inspect.Parameter.POSITIONAL_OR_KEYWORD) for n in leading]
        params += [p for p in inspect.signature(fn).parameters.values() if p.kind is inspect.Parameter.KEYWORD_ONLY]  # its own (sweep's out)
        for o in table:
            default = inspect.Parameter.empty if o.required else o.default
            params.append(inspect.Parameter(o.name, inspect.Parameter.KEYWORD_ONLY, default=default))
        fn.__signature__ = inspect.Signature(params, return_annotation=inspect.signature(fn).return_annotation)
        lines = fn.__doc__.splitlines()
        (at,) = [k for k, line in enumerate(lines) if line.strip() == _MARK]
        indent = lines[at][: len(lines[at]) - len(lines[at].lstrip())]
        lines[at : at + 1] = [_entry(o, indent) for o in table]
        fn.__doc__ = "\n".join(lines)
        fn.options = table
        return fn

    return decorate


def given(fn, options: dict) -> dict:
    """The options of one call of ``fn`` (decorated by :func:`takes`), every one present and checked:
    an unknown or missing keyword a TypeError (Python's words), a value of the wrong type, an unknown
    choice or a quantity without its unit an :class:`InputError` naming the keyword; a quantity becomes
    the text the app parses (:func:`softimpact.api._edge._text`)."""
    out = {}
    for name in options:
        if name not in {o.name for o in fn.options}:
            raise misspelt(name, [o.name for o in fn.options], f"si.{fn.__name__}")  # an InputError and a TypeError
    for o in fn.options:
        if o.required and o.name not in options:
            raise TypeError(f"{fn.__name__}() missing required keyword-only argument: {o.name!r}")
        out[o.name] = _checked(o, options.get(o.name, o.default))
    return out


def _checked(o, value):
    """One option's value, checked as :func:`given` says."""
    if value is None and not o.required:
        return None
    if o.kind is not None:
        if value is None:
            raise InputError(f"{o.name}: required (a quantity with its unit)")
        return _text(value, o.kind, o.name)
    if o.type is bool:
        if not isinstance(value, bool):
            raise InputError(f"{o.name}: expected True or False, got {value!r}")
    elif o.type is int:
        if isinstance(value, bool) or not isinstance(value, int):
            raise InputError(f"{o.name}: expected an integer, got {value!r}")
    elif o.type is float:
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
            raise InputError(f"{o.name}: expected a finite number, got {value!r}")
        return float(value)
    elif o.file and isinstance(value, os.PathLike):
        return os.fspath(value)
    elif not isinstance(value, str):
        raise InputError(f"{o.name}: expected a text, got {value!r}")
    if o.choices and value not in o.choices:
        raise InputError(f"{o.name}: {value!r} is not one of {', '.join(o.choices)}")
    return value


# the command line's words for what the API says otherwise: its guard's way past, its --out and --force
_PHRASES = (
    (re.compile(r"run `softimpact --ignore-limits \.\.\.` \((\w+)=1\)"), r"set the environment variable \1=1"),
    (re.compile(r"`softimpact --force \.\.\.`"), "write(..., force=True)"),
)
_FLAG = re.compile(r"(?<![\w-])--([a-z][a-z-]*)")


@contextmanager
def python_terms(table=()):
    """Re-raise an :class:`InputError` raised inside the block, its command-line flags (``--measured``,
    ``--out``) as the API's keywords (``measured``, ``write``'s ``out``) and the command line's advice in the
    API's terms; the error's class and ``argument`` kept."""
    try:
        yield
    except InputError as exc:
        text = str(exc)
        for pattern, words in _PHRASES:
            text = pattern.sub(words, text)
        names = {o.flag: o.name for o in table}
        text = _FLAG.sub(lambda m: names.get(m.group(0), m.group(1).replace("-", "_")), text)
        if text == str(exc):
            raise
        raise type(exc)(text, exc.argument) from None
