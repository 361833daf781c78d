"""The HTML report: sections of text, tables and figures, rendered into one page."""

from __future__ import annotations

import base64
import html
from dataclasses import dataclass, field

from .. import __version__

__all__ = ["Section", "render_report", "stem"]


@dataclass
class Section:
    """A part of the HTML report: text, tables (header, rows) and figure paths."""

    title: str
    paragraphs: list[str] = field(default_factory=list)
    tables: list[tuple[str, list[str], list[list[str]]]] = field(default_factory=list)
    figures: list[tuple[str, str]] = field(default_factory=list)  # (path, caption)


def render_report(title: str, sections: list[Section], notes: list[str] = (), files: dict[str, bytes | str] | None = None) -> str:
    """A self-contained HTML page: figures found in ``files`` are embedded (base64),
    so the page opens on its own when mailed; others are linked by relative path."""
    esc = html.escape
    out = [
        "<!doctype html><html><head><meta charset='utf-8'>",
        f"<title>{esc(title)}</title>",
        "<style>body{font-family:sans-serif;max-width:1000px;margin:auto;padding:1em;line-height:1.4}"
        "table{border-collapse:collapse;margin:0.5em 0}td,th{border:1px solid #bbb;padding:2px 8px;text-align:left}"
        "th{background:#eee}figure{margin:1em 0}img{max-width:100%}figcaption{font-size:90%;color:#444}</style>",
        "</head><body>",
        f"<h1>{esc(title)}</h1>",
        f"<p>softimpact {esc(__version__)}</p>",
    ]
    for s in sections:
        out.append(f"<h2>{esc(s.title)}</h2>")
        out += [f"<p>{esc(p)}</p>" for p in s.paragraphs]
        for caption, header, rows in s.tables:
            out.append(f"<table><caption>{esc(caption)}</caption><tr>" + "".join(f"<th>{esc(h)}</th>" for h in header) + "</tr>")
            out += ["<tr>" + "".join(f"<td>{esc(str(c))}</td>" for c in row) + "</tr>" for row in rows]
            out.append("</table>")
        for path, caption in s.figures:
            src, mime = path, "image/png"
            if files is not None and isinstance(files.get(path), bytes):
                data = files[path]
                mime = "application/pdf" if data[:4] == b"%PDF" else "image/svg+xml" if data.lstrip()[:5] in (b"<?xml", b"<svg ") else "image/png"
                src = f"data:{mime};base64," + base64.b64encode(data).decode("ascii")
            shown = src if src != path else esc(path)
            if mime == "application/pdf":  # --figure-format pdf: browsers show a PDF in an embed, not an img
                out.append(f"<figure><embed src='{shown}' type='application/pdf' width='100%' height='480'><figcaption>{esc(caption)}</figcaption></figure>")
            else:
                out.append(f"<figure><img src='{shown}' alt='{esc(caption)}'><figcaption>{esc(caption)}</figcaption></figure>")
    if notes:
        out.append("<h2>Assumptions and errata</h2><ul>" + "".join(f"<li>{esc(n)}</li>" for n in notes) + "</ul>")
    out.append("</body></html>")
    return "\n".join(out)


def stem(name: str) -> str:
    """``name`` made safe as part of a file name."""
    return "".join(ch if ch.isalnum() or ch in "-_." else "_" for ch in name)
