# SPDX-License-Identifier: Apache-2.0
"""html: the report as ONE self-contained HTML file (report.html beside report.md).

The Markdown is converted with the `markdown` package (extensions tables, toc, attr_list);
every figure (`![caption](figures/x.png)`) is embedded as a base64 data: URI, the CSS is
inline, and nothing is fetched from the network (no fonts, no scripts), so the file can be
mailed or opened offline. Links to other files (recordings, dashboards) stay relative links,
so they work when report.html sits in the campaigns root next to them. A figure the Markdown
references but the figure directory lacks is an error (HtmlError), never a broken image.

Pure functions: to_html(md_text, base_dir) -> str; write(md_path) writes the .html beside it.
"""
import base64
import html as html_mod
import os
import re

import markdown

MIME = {".png": "image/png", ".jpg": "image/jpeg", ".jpeg": "image/jpeg", ".svg": "image/svg+xml",
        ".gif": "image/gif", ".webp": "image/webp"}
IMG_SRC = re.compile(r'(<img\b[^>]*?\bsrc=")([^"]*)(")')
TD_CELL = re.compile(r"<td>(.*?)</td>", re.S)
LONG_CELL_CHARS = 40  # a text cell this long gets a minimum width (no one-word columns)
CHARS_PER_EM = 5.0    # its minimum width: length / this [em], within LONG_CELL_EM
LONG_CELL_EM = (14.0, 36.0)
# A table cell that is a number (possibly with ±, a CI "[a, b]", a range "a–b", %, ×, "n = 20")
_NUM_CHARS = r"\s+\-−±–0-9.,eE×·%()\[\]/≈~n="
NUMERIC = re.compile(rf"^[{_NUM_CHARS}<>≤≥]*\d[{_NUM_CHARS}]*$")

CSS = """
:root { --fg: #1d2330; --muted: #5b6475; --line: #d5dae3; --head: #e8edf5; --zebra: #f6f8fb;
        --accent: #1f5fa8; --code: #f1f3f7; }
* { box-sizing: border-box; }
body { margin: 0; color: var(--fg); background: #fff; line-height: 1.55;
       font: 15px/1.55 system-ui, -apple-system, "Segoe UI", Roboto, "DejaVu Sans", sans-serif; }
.layout { display: flex; gap: 28px; max-width: 1420px; margin: 0 auto; padding: 0 20px; }
nav.toc { flex: 0 0 260px; position: sticky; top: 0; align-self: flex-start;
          max-height: 100vh; overflow-y: auto; padding: 18px 6px 24px 0; font-size: 13px;
          border-right: 1px solid var(--line); }
nav.toc .toc-title { font-weight: 600; margin: 0 0 6px 0; color: var(--muted);
                     text-transform: uppercase; letter-spacing: .05em; font-size: 11.5px; }
nav.toc ul { list-style: none; margin: 0; padding-left: 12px; }
nav.toc > div > ul { padding-left: 0; }
nav.toc li { margin: 3px 0; }
nav.toc a { color: var(--fg); text-decoration: none; }
nav.toc a:hover { color: var(--accent); text-decoration: underline; }
main { flex: 1 1 auto; min-width: 0; max-width: 1100px; padding: 8px 0 60px 0; }
h1 { font-size: 1.75em; line-height: 1.25; margin: .8em 0 .5em 0; }
h2 { font-size: 1.4em; margin: 1.8em 0 .5em 0; padding-bottom: .2em;
     border-bottom: 2px solid var(--line); }
h3 { font-size: 1.15em; margin: 1.4em 0 .4em 0; }
h2, h3, h4 { scroll-margin-top: 10px; }
a { color: var(--accent); }
code { background: var(--code); padding: 0 .25em; border-radius: 3px; font-size: .9em;
       font-family: "DejaVu Sans Mono", Menlo, Consolas, monospace; }
pre { background: var(--code); padding: 10px; overflow-x: auto; border-radius: 4px; }
pre code { padding: 0; }
img { max-width: 100%; height: auto; display: block; margin: 10px auto 2px auto; }
p > img + em, p > em:only-child { color: var(--muted); }
.table-wrap { overflow-x: auto; margin: 10px 0 16px 0; border: 1px solid var(--line);
              border-radius: 4px; }
table { border-collapse: collapse; font-size: 13px; width: auto; min-width: 100%; }
th, td { padding: 5px 9px; border-bottom: 1px solid var(--line); vertical-align: top;
         text-align: left; }
th { background: var(--head); font-weight: 600; position: sticky; top: 0; }
tbody tr:nth-child(even) { background: var(--zebra); }
tbody tr:hover { background: #eaf1fb; }
td.num { text-align: right; font-variant-numeric: tabular-nums; white-space: nowrap; }
th { min-width: 4em; }
blockquote { margin: 10px 0; padding: 4px 14px; border-left: 4px solid var(--line);
             color: var(--muted); }
@media (max-width: 1180px) {
  .layout { display: block; }
  nav.toc { position: static; max-height: none; border-right: none; border-bottom: 1px solid
            var(--line); padding: 12px 0; columns: 2; }
  main { max-width: none; }
}
@media print { nav.toc { display: none; } .layout { display: block; } }
"""


class HtmlError(ValueError):
    """A figure the report references cannot be embedded."""


def data_uri(path):
    """The file as a base64 data: URI; HtmlError if it is missing or of an unknown type."""
    ext = os.path.splitext(path)[1].lower()
    if ext not in MIME:
        raise HtmlError(f"{path}: not an image type the HTML report embeds ({', '.join(MIME)})")
    try:
        with open(path, "rb") as fh:
            raw = fh.read()
    except OSError as e:
        raise HtmlError(f"figure {path} referenced by the report is missing: {e.strerror}")
    if not raw:
        raise HtmlError(f"figure {path} referenced by the report is empty")
    return f"data:{MIME[ext]};base64," + base64.b64encode(raw).decode("ascii")


def embed_images(body, base_dir):
    """Every <img src> replaced by its data: URI (paths relative to base_dir). Returns
    (html, number of images embedded)."""
    count = [0]

    def sub(m):
        src = html_mod.unescape(m.group(2))
        if src.startswith("data:"):
            return m.group(0)
        if re.match(r"^[a-z][a-z0-9+.-]*://", src, re.I) or os.path.isabs(src):
            raise HtmlError(f"image {src!r}: only figures relative to the report are embedded")
        count[0] += 1
        return m.group(1) + data_uri(os.path.join(base_dir, src)) + m.group(3)
    return IMG_SRC.sub(sub, body), count[0]


def style_tables(body):
    """Wrap tables for horizontal scrolling; right-align the cells that are numbers."""
    body = body.replace("<table>", '<div class="table-wrap"><table>')
    body = body.replace("</table>", "</table></div>")
    return TD_CELL.sub(lambda m: _td_open(m.group(1)) + m.group(1) + "</td>", body)


def _td_open(inner):
    """<td> with class num (a number: right-aligned) or long (long text: a minimum width)."""
    text = html_mod.unescape(re.sub(r"<[^>]+>", "", inner)).strip()
    if NUMERIC.match(text):
        return '<td class="num">'
    if len(text) < LONG_CELL_CHARS:
        return "<td>"
    lo, hi = LONG_CELL_EM
    width_em = min(max(len(text) / CHARS_PER_EM, lo), hi)
    return f'<td class="long" style="min-width: {width_em:.0f}em">'


def title_of(md_text, default="Report"):
    """The first level-1 heading, as plain text."""
    m = re.search(r"^#\s+(.+?)\s*#*\s*$", md_text, re.M)
    return re.sub(r"[`*_]", "", m.group(1)) if m else default


def to_html(md_text, base_dir):
    """The full HTML page of a Markdown report whose figure paths are relative to base_dir.
    Raises HtmlError for a figure that cannot be embedded."""
    conv = markdown.Markdown(extensions=["tables", "toc", "attr_list", "sane_lists"],
                             extension_configs={"toc": {"toc_depth": "2-3"}})
    body = conv.convert(md_text)
    body, _ = embed_images(body, base_dir)
    body = style_tables(body)
    title = html_mod.escape(title_of(md_text))
    toc = conv.toc if getattr(conv, "toc_tokens", None) else ""
    nav = (f'<nav class="toc"><p class="toc-title">Contents</p>{toc}</nav>' if toc else "")
    return ("<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
            "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
            f"<title>{title}</title>\n<style>{CSS}</style>\n</head>\n<body>\n"
            f"<div class=\"layout\">\n{nav}\n<main>\n{body}\n</main>\n</div>\n</body>\n</html>\n")


def write(md_path, html_path=None):
    """Convert md_path (figures relative to its directory) to html_path (default: the same
    name with .html); returns html_path."""
    with open(md_path, encoding="utf-8") as fh:
        text = fh.read()
    page = to_html(text, os.path.dirname(os.path.abspath(md_path)))
    html_path = html_path or os.path.splitext(md_path)[0] + ".html"
    with open(html_path, "w", encoding="utf-8") as fh:
        fh.write(page)
    return html_path
