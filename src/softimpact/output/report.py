"""The HTML report: sections of text, tables and figures, rendered into one page."""

from __future__ import annotations

import base64
import html
from dataclasses import dataclass, field

from .. import __version__

__all__ = ["flagged_count", "Section", "render_report", "stem", "anchors"]


@dataclass
class Section:
    """A part of the HTML report: text, tables (header, rows) and figure paths; ``summary``: one-line results
    (made from the same objects as the section's tables) that render_report lists at the top, linked to the section."""

    title: str
    paragraphs: list[str] = field(default_factory=list)
    tables: list[tuple[str, list[str], list[list[str]]]] = field(default_factory=list)
    figures: list[tuple[str, str]] = field(default_factory=list)  # (path, caption)
    summary: list[str] = field(default_factory=list)
    # every row of the section's maps outside its models' validity, once per flag it raises: (map, row, flag), listed
    # grouped by map and flag in the report's "Warnings of the run"
    flagged: list[tuple[str, str, str]] = field(default_factory=list)
    units: str = ""  # the one unit system of its tables and figures, said at its head
    qualified: str = ""  # why its results hold only with a caveat (its warnings, its rows outside validity): marked in the summary


def flagged_count(sections: list[Section]) -> tuple[int, int]:
    """(rows outside validity, maps they are in) over ``sections``' :attr:`Section.flagged` (a row with several flags counted once)."""
    rows = {(m, r) for s in sections for m, r, _ in s.flagged}
    return len(rows), len({m for m, _ in rows})


def _flagged_html(sections: list[Section]) -> list[str]:
    """The flagged rows of every map, grouped by map, then by flag: a heading per map, a list per flag."""
    esc = html.escape
    groups: dict[str, dict[str, list[str]]] = {}
    for s in sections:
        for m, row, flag in s.flagged:
            groups.setdefault(m, {}).setdefault(flag, []).append(row)
    out = []
    for m, by_flag in groups.items():
        n = len({r for rows in by_flag.values() for r in rows})
        out.append(f"<h3>{esc(m)}: {n} row{'' if n == 1 else 's'} outside validity</h3><ul>")
        for flag, rows in by_flag.items():
            items = "; ".join(f"<span class='flagged-row' data-row='{esc(m + ' | ' + r, quote=True)}'>{esc(r)}</span>" for r in rows)
            out.append(f"<li>{esc(flag)} ({len(rows)}): {items}</li>")
        out.append("</ul>")
    return out


def anchors(titles: list[str]) -> list[str]:
    """A unique HTML id for each title (lower-case words joined by '-', a number appended to a repeat)."""
    out, seen = [], set()
    for title in titles:
        base = "-".join("".join(ch if ch.isalnum() else " " for ch in title.lower()).split()) or "section"
        name, k = base, 2
        while name in seen:
            name, k = f"{base}-{k}", k + 1
        seen.add(name)
        out.append(name)
    return out


def render_report(
    title: str,
    sections: list[Section],
    notes: list[str] = (),
    files: dict[str, bytes | str] | None = None,
    warnings: list[str] | tuple[str, ...] | None = None,
) -> str:
    """A self-contained HTML page: a table of contents and a summary of results (each section's ``summary``
    lines, linked to it) at the top; figures found in ``files`` are embedded (base64), so the page opens on
    its own when mailed; others are linked by relative path. ``warnings`` (the run's, None: not collected)
    are listed in a section of their own."""
    esc = html.escape
    extra = []
    if warnings is not None:
        extra.append(("Warnings of the run", "warnings"))
    if notes:
        extra.append(("Assumptions and errata", "assumptions-and-errata"))
    ids = anchors([s.title for s in sections] + [t for t, _ in extra])
    ids, extra = ids[: len(sections)], [(t, i) for (t, _), i in zip(extra, ids[len(sections) :], strict=True)]
    out = [
        "<!doctype html><html><head><meta charset='utf-8'>",
        f"<title>{esc(title)}</title>",
        "<style>body{font-family:sans-serif;max-width:1000px;margin:auto;padding:1em;line-height:1.4}"
        "table{border-collapse:collapse;margin:0.5em 0}td,th{border:1px solid #bbb;padding:2px 8px;text-align:left}"
        "th{background:#eee}figure{margin:1em 0}img{max-width:100%}figcaption{font-size:90%;color:#444}"
        "nav ol{columns:2;font-size:90%}.summary li{margin:0.2em 0}.summary li.qualified{color:#8a4b00}</style>",
        "</head><body>",
        f"<h1>{esc(title)}</h1>",
        f"<p>softimpact {esc(__version__)}</p>",
    ]
    items = [(line + (f" [qualified: {s.qualified}]" if s.qualified else ""), s.title, i) for s, i in zip(sections, ids, strict=True) for line in s.summary]
    if warnings is not None:
        wid = dict(extra)["Warnings of the run"]
        rows, maps = flagged_count(sections)
        line = f"{len(warnings)} warning{'' if len(warnings) == 1 else 's'} raised by the run"
        if rows:
            line += f"; {rows} row{'' if rows == 1 else 's'} of {maps} map{'' if maps == 1 else 's'} outside the models' validity, listed by map and flag"
        items.append((line, "Warnings of the run", wid))
    if items:
        out.append("<h2 id='summary'>Summary of results</h2><ul class='summary'>")
        out += [
            f"<li{' class=' + chr(39) + 'qualified' + chr(39) if '[qualified: ' in line else ''}>{esc(line)} (<a href='#{i}'>{esc(t)}</a>)</li>"
            for line, t, i in items
        ]
        out.append("</ul>")
    toc = [(s.title, i) for s, i in zip(sections, ids, strict=True)] + extra
    out.append("<nav><h2 id='contents'>Contents</h2><ol>" + "".join(f"<li><a href='#{i}'>{esc(t)}</a></li>" for t, i in toc) + "</ol></nav>")
    for s, sid in zip(sections, ids, strict=True):
        out.append(f"<h2 id='{sid}'>{esc(s.title)}</h2>")
        if s.units:
            out.append(f"<p class='units'><em>Units in this section: {esc(s.units)}.</em></p>")
        out += [f"<p>{esc(p)}</p>" for p in s.paragraphs]
        for caption, header, rows in s.tables:
            out.append(f"<table><caption>{esc(caption)}</caption><tr>" + "".join(f"<th>{esc(h)}</th>" for h in header) + "</tr>")
            out += ["<tr>" + "".join(f"<td>{esc(str(c))}</td>" for c in row) + "</tr>" for row in rows]
            out.append("</table>")
        out += [_figure_html(path, caption, files, s.title) for path, caption in s.figures]
    for t, i in extra:
        out.append(f"<h2 id='{i}'>{esc(t)}</h2>")
        if i == dict(extra).get("Warnings of the run"):
            out.append("<ul>" + "".join(f"<li>{esc(w)}</li>" for w in warnings) + "</ul>" if warnings else "<p>The run raised no warning.</p>")
            if any(sec.flagged for sec in sections):
                out.append(
                    "<p>Every row of the maps whose run lies outside its models' validity envelope, by map and by the flag "
                    "raised (a row with several flags is listed under each; the maps' CSVs have the ratios).</p>"
                )
                out += _flagged_html(sections)
        else:
            out.append("<ul>" + "".join(f"<li>{esc(n)}</li>" for n in notes) + "</ul>")
    out.append("</body></html>")
    return "\n".join(out)


def _figure_html(path: str, caption: str, files: dict | None, title: str) -> str:
    """A figure of the section ``title``: embedded (base64) when ``files`` holds its bytes, else linked by ``path``."""
    esc = html.escape
    src, mime = path, "image/png"
    if files is not None and isinstance(files.get(path), bytes):
        data = files[path]
        mime = "application/pdf" if data[:4] == b"%PDF" else "image/svg+xml" if data.lstrip()[:5] in (b"<?xml", b"<svg ") else "image/png"
        src = f"data:{mime};base64," + base64.b64encode(data).decode("ascii")
    shown = src if src != path else esc(path)
    alt = esc(caption or f"figure {path.rsplit('/', 1)[-1]} of the section {title}", quote=True)
    if mime == "application/pdf":  # --figure-format pdf: browsers show a PDF in an embed, not an img
        return f"<figure><embed src='{shown}' type='application/pdf' width='100%' height='480' title='{alt}'><figcaption>{esc(caption)}</figcaption></figure>"
    return f"<figure><img src='{shown}' alt='{alt}'><figcaption>{esc(caption)}</figcaption></figure>"


def stem(name: str) -> str:
    """``name`` made safe as part of a file name."""
    return "".join(ch if ch.isalnum() or ch in "-_." else "_" for ch in name)
