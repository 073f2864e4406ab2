#!/usr/bin/env python3
"""Fails where a chapter of the built book has an element wider than its text column.

For every chapter page of book/book/ (the output of `just book`), a copy of the page
with a measuring script injected is opened in headless Chromium at a 1280 px window;
the script compares each element of the page's <main> (the column) with the column's
box and writes what sticks out into the DOM, which Chromium dumps. An element inside
a box that scrolls or clips on its own (the tables and display formulas of
book/theme/tables.css) stays in the column and is not reported; the scrolling box
itself is, if it is wider than the column. Only the outermost overflowing element
of a subtree is named.

Usage: python3 tools/book_overflow.py [BOOK_DIR] [--chromium PATH] [--width PX]
Exit status: 0 when nothing overflows, 1 when something does (each named by chapter,
element and widths), 2 when the book or Chromium is missing. Standard library only.
"""

import argparse
import html
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

# The measuring script: runs once the page (and its fonts) have loaded, writes the
# findings as JSON into <pre id="overflow-report">.
MEASURE = r"""
<script>
(function () {
  function describe(e) {
    var d = e.tagName.toLowerCase();
    if (e.id) d += '#' + e.id;
    var cls = (typeof e.className === 'string' ? e.className : '').trim();
    if (cls) d += '.' + cls.split(/\s+/).slice(0, 2).join('.');
    var text = (e.textContent || '').replace(/\s+/g, ' ').trim();
    if (text.length > 60) text = text.slice(0, 57) + '...';
    // Where it is: the paragraph, item, cell or heading that holds it.
    var home = e.parentElement && e.parentElement.closest('p, li, td, th, h1, h2, h3, h4, dd');
    var where = home ? (home.textContent || '').replace(/\s+/g, ' ').trim().slice(0, 60) : '';
    return {element: d, text: text, where: where};
  }
  function scrolls(e) {
    var s = getComputedStyle(e);
    return ['auto', 'scroll', 'hidden', 'clip'].indexOf(s.overflowX) >= 0;
  }
  function measure() {
    var main = document.querySelector('main');
    var out = {column: null, overflow: []};
    if (!main) { write(out); return; }
    var col = main.getBoundingClientRect();
    out.column = Math.round(col.width);
    var walk = function (e) {
      for (var i = 0; i < e.children.length; i++) {
        var c = e.children[i];
        var r = c.getBoundingClientRect();
        if (r.width > 0 && (r.right > col.right + 1 || r.left < col.left - 1)) {
          var d = describe(c);
          d.width = Math.round(r.width);
          d.left = Math.round(r.left - col.left);
          d.right = Math.round(r.right - col.right);
          out.overflow.push(d);
          continue; // its descendants overflow with it
        }
        if (!scrolls(c)) walk(c);
      }
    };
    walk(main);
    write(out);
  }
  function write(out) {
    var pre = document.createElement('pre');
    pre.id = 'overflow-report';
    pre.textContent = JSON.stringify(out);
    document.body.appendChild(pre);
  }
  window.addEventListener('load', function () {
    var ready = document.fonts ? document.fonts.ready : Promise.resolve();
    ready.then(function () { setTimeout(measure, 200); });
  });
})();
</script>
"""

REPORT = re.compile(r'<pre id="overflow-report">(.*?)</pre>', re.S)

# Pages of the book that are not chapters.
NOT_CHAPTERS = {"print.html", "404.html", "toc.html"}


def chromium_path(given):
    if given:
        return given
    for name in ("chromium", "chromium-browser", "google-chrome"):
        p = shutil.which(name)
        if p:
            return p
    return None


def chapters(book):
    return sorted(
        f for f in os.listdir(book)
        if f.endswith(".html") and f not in NOT_CHAPTERS and not f.startswith(".")
    )


def measure(chromium, book, page, width, profile):
    with open(os.path.join(book, page), encoding="utf-8") as f:
        text = f.read()
    if "</body>" not in text:
        return None, "no </body> in the page"
    # The copy sits beside the page, so that its relative links (CSS, fonts,
    # figures) resolve as the page's own.
    fd, copy = tempfile.mkstemp(prefix=".overflow-", suffix=".html", dir=book)
    try:
        with os.fdopen(fd, "w", encoding="utf-8") as f:
            f.write(text.replace("</body>", MEASURE + "</body>", 1))
        run = subprocess.run(
            [
                chromium, "--headless", "--no-sandbox", "--disable-gpu",
                "--user-data-dir=" + profile,
                "--window-size=%d,2000" % width,
                "--virtual-time-budget=5000", "--dump-dom",
                "file://" + os.path.abspath(copy),
            ],
            capture_output=True, text=True, timeout=120,
        )
    finally:
        os.remove(copy)
    found = REPORT.search(run.stdout)
    if not found:
        return None, "Chromium returned no measurement (exit %d): %s" % (
            run.returncode, run.stderr.strip()[-300:])
    return json.loads(html.unescape(found.group(1))), None


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("book", nargs="?", default="book/book",
                    help="the built book (default: book/book)")
    ap.add_argument("--chromium", help="the browser (default: chromium on the PATH)")
    ap.add_argument("--width", type=int, default=1280, help="window width, px (1280)")
    args = ap.parse_args()
    if not os.path.isfile(os.path.join(args.book, "index.html")):
        print("book_overflow: no built book at %s (run `just book`)" % args.book,
              file=sys.stderr)
        return 2
    chromium = chromium_path(args.chromium)
    if not chromium:
        print("book_overflow: no chromium on the PATH (apt-get install chromium)",
              file=sys.stderr)
        return 2
    bad, broken = 0, 0
    profile = tempfile.mkdtemp(prefix="book-overflow-")
    try:
        for page in chapters(args.book):
            result, error = measure(chromium, args.book, page, args.width, profile)
            if error:
                print("%s: %s" % (page, error))
                broken += 1
                continue
            for o in result["overflow"]:
                bad += 1
                side = "right by %d px" % o["right"] if o["right"] > 1 else \
                    "left by %d px" % -o["left"]
                where = " in %r" % o["where"] if o.get("where") else ""
                print("%s: <%s> %d px wide in a %d px column, out %s: %r%s" % (
                    page, o["element"], o["width"], result["column"], side, o["text"],
                    where))
    finally:
        shutil.rmtree(profile, ignore_errors=True)
    pages = len(chapters(args.book))
    if bad or broken:
        print("book_overflow: %d element(s) wider than the column, %d page(s) not "
              "measured, of %d chapters at %d px" % (bad, broken, pages, args.width))
        return 1
    print("book_overflow: nothing wider than the column in %d chapters at %d px"
          % (pages, args.width))
    return 0


if __name__ == "__main__":
    sys.exit(main())
