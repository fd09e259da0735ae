# SPDX-License-Identifier: Apache-2.0
"""The report's HTML page (tools/uvms_tools/report/html.py) in a real browser, Debian's headless
Chromium: a small synthetic report (a Markdown text with a table, a relative link and two PNG
figures drawn here with matplotlib) is converted; the page must be one self-contained file
(every figure a data: URI whose bytes are the figure file's, no network reference), its
screenshot must have the window size and not be blank, and Chromium's own decoding must find
every image with a natural width (none broken). A negative control (one data: URI corrupted)
proves the broken-image probe can fail; a missing figure must be an error, not a broken image.

With UVMS_REPORT_HTML=PATH (a full report.html, e.g. from tools/report.py), that page gets the
same browser checks too.

Usage: test_report_html.py REPO_ROOT
"""
import base64
import os
import re
import subprocess
import sys

import numpy as np

REPO = sys.argv[1]
sys.path.insert(0, os.path.join(REPO, "tools"))
import matplotlib  # noqa: E402

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from PIL import Image  # noqa: E402

from uvms_tools.report import html  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import checklist  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, "support"))
from scratch import scratch_dir  # noqa: E402  (tests/support/scratch.py)

CHROMIUM = "/usr/bin/chromium"
WINDOW_PX = (1280, 2000)
FLAGS = ["--headless=new", "--no-sandbox", "--disable-gpu", "--hide-scrollbars",
         "--virtual-time-budget=5000"]
MIN_NONWHITE = 0.02   # fraction of pixels that are not (near) white on a page with 2 figures
MIN_STD = 10.0        # grey-level standard deviation of a non-blank page [0–255]
# Written into the DOM on load: the number of <img> and of those Chromium could not decode.
PROBE = ("<script>window.addEventListener('load', function () {"
         "var im = document.images, bad = 0;"
         "for (var i = 0; i < im.length; i++)"
         " if (!im[i].complete || im[i].naturalWidth === 0) bad++;"
         "var p = document.createElement('pre'); p.id = 'uvms-probe';"
         "p.textContent = 'imgs=' + im.length + ' broken=' + bad;"
         "document.body.appendChild(p); });</script>")
TMP = scratch_dir("uvms-report-html-")  # removed at exit (tests/support/scratch.py)
FIGS = ["figures/curve.png", "figures/bars.png"]
MD = f"""# Synthetic report for the HTML test

Intro paragraph with a [recording](recordings/exp1_cases-IV_stagnant.rrd) link.

## A table

| case | energy E_el [J] | verdict |
|---|---|---|
| IV | 581.6 | reference |
| VII | 422.9 | cheaper |

## Figures

![A curve]({FIGS[0]})

*A curve.*

![Some bars]({FIGS[1]})

*Some bars.*
"""


def draw_figures():
    os.makedirs(os.path.join(TMP, "figures"))
    t_s = np.linspace(0.0, 10.0, 200)
    fig, ax = plt.subplots(figsize=(8, 4))
    ax.plot(t_s, np.sin(t_s), lw=2)
    ax.set_xlabel("time t [s]")
    ax.set_ylabel("y [m]")
    fig.savefig(os.path.join(TMP, FIGS[0]), dpi=100)
    plt.close(fig)
    fig, ax = plt.subplots(figsize=(8, 4))
    ax.bar(["IV", "VII"], [581.6, 422.9], color=["#1f77b4", "#d62728"])
    ax.set_ylabel("E_el [J]")
    fig.savefig(os.path.join(TMP, FIGS[1]), dpi=100)
    plt.close(fig)


def chromium(args, timeout_s=60):
    return subprocess.run([CHROMIUM, *FLAGS, *args], capture_output=True, text=True,
                          timeout=timeout_s)


def screenshot(page, png, window=WINDOW_PX):
    chromium([f"--window-size={window[0]},{window[1]}", f"--screenshot={png}",
              "file://" + os.path.abspath(page)])
    return png


def probe(page):
    """(imgs, broken) as Chromium decodes the page (a copy with the probe script)."""
    with open(page, encoding="utf-8") as fh:
        text = fh.read()
    copy = os.path.join(TMP, "probe-" + os.path.basename(page))
    with open(copy, "w", encoding="utf-8") as fh:
        fh.write(text.replace("</body>", PROBE + "</body>", 1))
    p = chromium([f"--window-size={WINDOW_PX[0]},{WINDOW_PX[1]}", "--dump-dom",
                  "file://" + copy])
    m = re.search(r'id="uvms-probe">imgs=(\d+) broken=(\d+)<', p.stdout)
    assert m, f"probe output not found in the DOM Chromium dumped (rc {p.returncode}): " \
              f"{p.stderr.strip()[-300:]}"
    return int(m.group(1)), int(m.group(2))


def not_blank(png, window=WINDOW_PX):
    assert os.path.isfile(png) and os.path.getsize(png) > 0, f"no screenshot {png}"
    im = Image.open(png)
    assert im.size == window, f"screenshot size {im.size} != window {window}"
    grey = np.asarray(im.convert("L"), float)
    nonwhite = float((grey < 240).mean())
    assert grey.std() > MIN_STD, f"screenshot looks blank: grey std {grey.std():.1f}"
    assert nonwhite > MIN_NONWHITE, f"screenshot looks blank: {nonwhite:.3f} non-white"
    return nonwhite


# -- checks on the synthetic page
def page_path():
    return os.path.join(TMP, "report.html")


def check_self_contained():
    page = open(page_path(), encoding="utf-8").read()
    assert "<title>Synthetic report for the HTML test</title>" in page, "title from the # heading"
    srcs = re.findall(r'<img\b[^>]*\bsrc="([^"]*)"', page)
    assert len(srcs) == len(FIGS), f"{len(srcs)} <img> for {len(FIGS)} figures"
    for src, fig in zip(srcs, FIGS):
        assert src.startswith("data:image/png;base64,"), f"{fig} not embedded: {src[:40]}"
        raw = open(os.path.join(TMP, fig), "rb").read()
        assert base64.b64decode(src.split(",", 1)[1]) == raw, f"{fig}: embedded bytes differ"
    assert not re.search(r"src=\"(https?:)?//|url\(|@import|<link\b|<script\b", page), \
        "the page references something outside itself (network, stylesheet or script)"
    assert 'href="recordings/exp1_cases-IV_stagnant.rrd"' in page, "relative link kept"
    assert page.count("<table") == 1 and page.count('<td class="num">') == 2, \
        "one table, its two energies right-aligned"


def check_missing_figure_is_an_error():
    try:
        html.to_html(MD.replace(FIGS[1], "figures/absent.png"), TMP)
    except html.HtmlError as e:
        assert "absent.png" in str(e), f"error names the figure: {e}"
        return
    raise AssertionError("a missing figure gave no HtmlError")


def check_screenshot():
    not_blank(screenshot(page_path(), os.path.join(TMP, "shot.png")))


def check_images_decode():
    imgs, broken = probe(page_path())
    assert (imgs, broken) == (len(FIGS), 0), f"imgs={imgs} broken={broken}, want {len(FIGS)}, 0"


def check_negative_control():
    page = open(page_path(), encoding="utf-8").read()
    i = page.index("data:image/png;base64,") + len("data:image/png;base64,")
    bad = os.path.join(TMP, "corrupt.html")
    with open(bad, "w", encoding="utf-8") as fh:
        fh.write(page[:i] + "AAAAAAAAAAAAAAAA" + page[i + 16:])
    imgs, broken = probe(bad)
    assert (imgs, broken) == (len(FIGS), 1), f"corrupted copy: imgs={imgs} broken={broken}"


def check_full_report():
    full = os.environ.get("UVMS_REPORT_HTML")
    if not full:
        print("     (UVMS_REPORT_HTML not set: no full report checked)")
        return
    n_img = len(re.findall(r"<img\b", open(full, encoding="utf-8").read()))
    imgs, broken = probe(full)
    assert imgs == n_img and n_img > 0 and broken == 0, \
        f"{full}: {imgs} images in the DOM ({n_img} in the file), {broken} broken"
    not_blank(screenshot(full, os.path.join(TMP, "full.png")))


CHECKS = [check_self_contained, check_missing_figure_is_an_error, check_screenshot,
          check_images_decode, check_negative_control, check_full_report]


def main():
    if not os.access(CHROMIUM, os.X_OK):
        print(f"FAIL {CHROMIUM} not found: install it with tools/bootstrap (Debian package "
              f"chromium)")
        return 1
    return checklist.run(CHECKS, TMP, write_page,
                         errors=(AssertionError, subprocess.TimeoutExpired))


def write_page():
    """The synthetic page: two matplotlib figures and a table, converted by html.py."""
    draw_figures()
    with open(page_path(), "w", encoding="utf-8") as fh:
        fh.write(html.to_html(MD, TMP))


if __name__ == "__main__":
    sys.exit(main())
