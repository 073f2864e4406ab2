#!/usr/bin/env python3
"""Every number in the book's prose must come from data/ or from the paper.

Prototype of tests/book_numbers.rs, which implements the same rule, exactly:

Chapters: every `(file.md)` link target in book/src/SUMMARY.md.

Skipped text: fenced code blocks (``` ... ```), lines containing `{{#include`,
HTML comments <!-- ... --> (also across lines), inline code spans `...`, link
targets ](...) and URLs (http://, https://, www.).

Checked numbers (the sign, ASCII '-' or Unicode minus, is irrelevant):
  (a) a decimal with a fractional part: 18.9, 0.63, −0.1;
  (b) scientific notation: 1e-11, 1.4e-14, 10^{-14}, 10^-14, 10⁻¹⁴,
      1.4·10^{-14}, 1.4 × 10⁻¹⁴, 1.4 \\cdot 10^{-14}, 1.4 \\times 10^{-14};
  (c) any number directly followed by '%' or ' %' (also '\\%' and a
      no-break or thin space before it), integers included: 19 %.
  Plain integers without % are not checked. Numbers inside $...$ and
  $$...$$ math are checked like any other.

Exempt (references, not quantities):
  - a number d.d or d.dd (one digit, a dot, one or two digits) that stands
    alone inside parentheses: (3.15), (4.16)–(4.24);
  - a number d.d or d.dd one of whose two previous whitespace-separated words
    is Proposition, Corollary, Theorem, Lemma, Remark, Section, §, Fig.,
    Figure, Table, Problem, equation, eq., Step, Assumption, Hypothesis,
    chapter, version or v (case-insensitive, a plural 's' allowed, surrounding
    punctuation such as * ( [ , ; : ignored; '§' and 'v' may also be glued to
    the number: §3.1, v0.5);
  - version strings with two dots or more (0.5.4), anywhere;
  - anything inside \\tag{...}.

Matching: collect every numeric token of the files under data/
(recursively), leaving out what would match almost any short decimal (mesh
coordinates, times, counts, mesh sizes): files named *_nodes.csv are skipped
whole, and in every CSV the columns headed exactly x, y, t, n, steps, step,
node, i, j, level, h_plus_k or n_ref are skipped. A CSV's '#' comment lines
are mined whole, its header line (the first other line) not at all, and its
fields are split at the commas outside double quotes; .md, .txt and .toml
files are mined whole. A checked number x written with d decimals (d = 0 for an
integer with %) matches if some value v satisfies round(|v|, d) == |x| or
round(100·|v|, d) == |x|. A scientific number with s significant digits in
its mantissa matches if |v| (or 100·|v| when followed by %) rounded to s
significant digits equals |x|. Either kind also matches a value listed in
tests/paper_numbers.txt (one value per line, then '#' and where the paper
prints it), compared the same way. A number listed for its chapter, exactly as
written (spaces aside), in tests/unstored_numbers.txt (a measurement data/ does
not keep, with its source after '#') passes too; each listed number must occur
exactly once in its chapter.

Output: every unmatched number as chapter:line, the number and the line's
text; exit status 1 if there is any.
"""
import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
BOOK = os.path.join(ROOT, "book", "src")
DATA = os.path.join(ROOT, "data")
PAPER = os.path.join(ROOT, "tests", "paper_numbers.txt")
UNSTORED = os.path.join(ROOT, "tests", "unstored_numbers.txt")


def unstored():
    """(chapter, number as written, whitespace removed) pairs of
    tests/unstored_numbers.txt: the chapter, the number, then '#' and its
    source; lines starting with '#' are comments."""
    pairs = []
    for line in open(UNSTORED, encoding="utf-8"):
        if not line.strip() or line.lstrip().startswith("#"):
            continue
        entry = line.split("#", 1)[0].strip()
        chapter, token = (entry.split(None, 1) + [""])[:2]
        token = "".join(token.split())
        if not token:
            raise SystemExit(f"no number on the line: {line.rstrip()}")
        pairs.append((chapter, token))
    return pairs


SUP = {"⁰": "0", "¹": "1", "²": "2", "³": "3", "⁴": "4", "⁵": "5",
       "⁶": "6", "⁷": "7", "⁸": "8", "⁹": "9", "⁻": "-", "⁺": "+"}
SUP_CLASS = "⁰¹²³⁴⁵⁶⁷⁸⁹"
MINUS = "-−"

KEYWORDS = {"proposition", "corollary", "theorem", "lemma", "remark",
            "section", "§", "fig.", "figure", "table", "problem",
            "equation", "eq.", "step", "assumption", "hypothesis",
            "chapter", "version", "v"}

# Scientific first (it contains decimals), then plain decimals and % integers.
MANT = r"(?P<mant>\d+(?:\.\d+)?)"
TIMES = r"\s*(?:·|×|⋅|\\cdot|\\times)\s*"
EXP10 = (r"10(?:\^\{\s*(?P<e1>[+" + MINUS + r"]?\s*\d+)\s*\}"
         r"|\^(?P<e2>[+" + MINUS + r"]?\d+)"
         r"|(?P<e3>[⁻⁺]?[" + SUP_CLASS + r"]+))")
SCI = re.compile(
    r"(?<![\w.])(?:"
    r"(?P<emant>\d+(?:\.\d+)?)[eE](?P<eexp>[+" + MINUS + r"]?\d+)(?!\w)"
    r"|(?:" + MANT + TIMES + r")?" + EXP10 +
    r")(?P<pct>(?:\s|\u00a0|\u202f)?\\?%)?")
NUM = re.compile(r"(?<![\w.])(?P<num>\d+(?:\.\d+)+)"
                 r"|(?<![\w.])(?P<int>\d+)(?=(?:\s|\u00a0|\u202f)?\\?%)")
PCT_AFTER = re.compile(r"^(?:\s|\u00a0|\u202f)?\\?%")
REF = re.compile(r"^\d\.\d{1,2}$")


def chapters():
    text = open(os.path.join(BOOK, "SUMMARY.md"), encoding="utf-8").read()
    seen = []
    for target in re.findall(r"\]\(([^)]+\.md)\)", text):
        if target not in seen:
            seen.append(target)
    return seen


SKIPPED_COLUMNS = {"x", "y", "t", "n", "steps", "step", "node", "i", "j",
                   "level", "h_plus_k", "n_ref"}


def csv_fields(line):
    """A CSV line's fields: split at the commas outside double quotes."""
    fields, quoted, start = [], False, 0
    for k, c in enumerate(line):
        if c == '"':
            quoted = not quoted
        elif c == "," and not quoted:
            fields.append(line[start:k])
            start = k + 1
    fields.append(line[start:])
    return fields


def data_values(origin=None):
    tok = re.compile(r"\d+(?:\.\d+)?(?:[eE][-+]?\d+)?")
    values = set()

    def mine(text, path):
        for t in tok.findall(text):
            try:
                v = float(t)
            except ValueError:
                continue
            if v == v and v not in (float("inf"),):
                values.add(v)
                if origin is not None:
                    origin.setdefault(v, os.path.relpath(path, ROOT))

    for dirpath, _, files in os.walk(DATA):
        if os.path.relpath(dirpath, DATA).split(os.sep)[0] == "local":
            continue  # this machine's own timings, git-ignored: never a source
        for name in files:
            if name.endswith("_nodes.csv"):
                continue
            path = os.path.join(dirpath, name)
            with open(path, encoding="utf-8", errors="replace") as fh:
                text = fh.read()
            if not name.endswith(".csv"):
                mine(text, path)
                continue
            skip = None
            for line in text.split("\n"):
                if line.startswith("#"):
                    mine(line, path)
                elif skip is None:
                    skip = [h.strip() in SKIPPED_COLUMNS
                            for h in csv_fields(line)]
                else:
                    for k, field in enumerate(csv_fields(line)):
                        if not (k < len(skip) and skip[k]):
                            mine(field, path)
    return values


def paper_values():
    values = []
    if not os.path.exists(PAPER):
        return values
    for line in open(PAPER, encoding="utf-8"):
        head = line.split("#", 1)[0].strip()
        if head:
            values.append(float(head.replace("−", "-")))
    return values


class Matcher:
    def __init__(self, values, paper):
        self.values = [abs(v) for v in values]
        self.paper = [abs(v) for v in paper]
        self.dec = {}
        self.sig = {}

    def _dec_set(self, d):
        if d not in self.dec:
            s = set()
            for v in self.values:
                s.add(round(v, d))
                s.add(round(100 * v, d))
            self.dec[d] = s
        return self.dec[d]

    def _sig_set(self, s, pct):
        key = (s, pct)
        if key not in self.sig:
            out = set()
            for v in self.values:
                out.add(f"{v:.{s - 1}e}")
                if pct:
                    out.add(f"{100 * v:.{s - 1}e}")
            self.sig[key] = out
        return self.sig[key]

    def decimal(self, x, d):
        x = abs(x)
        if round(x, d) in self._dec_set(d):
            return True
        return any(round(v, d) == x or round(100 * v, d) == x
                   for v in self.paper)

    def scientific(self, x, s, pct):
        want = f"{abs(x):.{s - 1}e}"
        if want in self._sig_set(s, pct):
            return True
        return any(f"{v:.{s - 1}e}" == want or
                   (pct and f"{100 * v:.{s - 1}e}" == want)
                   for v in self.paper)


def blank(s):
    """Same length, all spaces: positions stay aligned with the source."""
    if not isinstance(s, str):
        s = s.group(0)
    return re.sub(r"[^\n]", " ", s)


def prose_lines(text):
    """Yield (line number, original line, masked line) for every prose line.

    Masking replaces skipped text by spaces, so columns stay aligned.
    """
    original = text.split("\n")
    # Fenced code blocks and {{#include lines go first, so that their
    # backticks cannot pair with those of the prose.
    lines, in_fence, skip = [], False, set()
    for i, line in enumerate(original):
        if line.lstrip().startswith("```"):
            in_fence = not in_fence
            skip.add(i)
            lines.append(blank(line))
        elif in_fence or "{{#include" in line:
            skip.add(i)
            lines.append(blank(line))
        else:
            lines.append(line)
    text = "\n".join(lines)
    # HTML comments, possibly spanning lines.
    text = re.sub(r"<!--.*?-->", blank, text, flags=re.S)
    # Inline code spans; one may run over a line break but not a blank line.
    text = re.sub(r"`(?:[^`\n]|\n(?![ \t]*\n))*`", blank, text)
    for i, masked in enumerate(text.split("\n")):
        if i in skip:
            continue
        masked = re.sub(r"\]\([^)]*\)", blank, masked)
        masked = re.sub(r"(?:https?://|www\.)\S+", blank, masked)
        masked = re.sub(r"\\tag\{[^}]*\}", blank, masked)
        # LaTeX control words (\pm, \approx, ...) would hide the number glued
        # to them from the word-boundary test; \cdot and \times belong to
        # scientific notation and stay.
        masked = re.sub(r"\\(?!cdot(?![A-Za-z])|times(?![A-Za-z]))[A-Za-z]+",
                        blank, masked)
        # Version strings with two dots or more.
        masked = re.sub(r"(?<![\w.])v?\d+(?:\.\d+){2,}", blank, masked)
        yield i + 1, original[i], masked


def previous_words(masked, start, n=2):
    words = masked[:start].split()
    return words[-n:]


def norm_word(w):
    w = w.strip("*_()[]{},;:\"'“”‘’").lower()
    return w


def is_keyword(w):
    w = norm_word(w)
    if w in KEYWORDS:
        return True
    if w.endswith("s") and w[:-1] in KEYWORDS:
        return True
    if w.endswith("s.") and w[:-2] + "." in KEYWORDS:  # Figs.
        return True
    return False


def exempt_reference(masked, start, end, token):
    if not REF.match(token):
        return False
    # Alone inside parentheses.
    if start > 0 and masked[start - 1] == "(" and masked[end:end + 1] == ")":
        return True
    # Glued prefix: §3.1, v0.5 (the prefix is the preceding character(s)).
    j = start
    while j > 0 and not masked[j - 1].isspace():
        j -= 1
    glued = norm_word(masked[j:start])
    if glued in ("§", "v"):
        return True
    return any(is_keyword(w) for w in previous_words(masked, j))


def check_line(masked, matcher):
    """Return the list of unmatched number strings of one masked line."""
    bad = []
    taken = [False] * len(masked)
    for m in SCI.finditer(masked):
        if m.group("emant") is not None:
            mant, exp = m.group("emant"), m.group("eexp")
        else:
            mant = m.group("mant") or "1"
            exp = m.group("e1") or m.group("e2")
            if exp is None:
                exp = "".join(SUP[c] for c in m.group("e3"))
        exp = exp.replace("−", "-").replace(" ", "")
        digits = mant.replace(".", "").lstrip("0") or "0"
        s = max(1, len(digits))
        x = float(mant) * 10.0 ** int(exp)
        pct = m.group("pct") is not None
        for k in range(m.start(), m.end()):
            taken[k] = True
        if not matcher.scientific(x, s, pct):
            bad.append(m.group(0).strip())
    for m in NUM.finditer(masked):
        if any(taken[m.start():m.end()]):
            continue
        token = m.group("num") or m.group("int")
        if token.count(".") > 1:
            continue  # version string
        if m.group("num") and exempt_reference(masked, m.start(), m.end(),
                                               token):
            continue
        d = len(token.split(".")[1]) if "." in token else 0
        if not matcher.decimal(float(token), d):
            pct = PCT_AFTER.match(masked[m.end():]) is not None
            bad.append(token + (" %" if pct else ""))
    return bad


def explain(matcher, origin, paper_lines):
    """--explain: list every checked number with a source it matched."""
    for chapter in chapters():
        text = open(os.path.join(BOOK, chapter), encoding="utf-8").read()
        for i, line, masked in prose_lines(text):
            for m in re.finditer(r"(?<![\w.])\d+\.\d+|(?<![\w.])\d+(?=\s?\\?%)",
                                 masked):
                token = m.group(0)
                if token.count(".") > 1 or exempt_reference(
                        masked, m.start(), m.end(), token):
                    continue
                d = len(token.split(".")[1]) if "." in token else 0
                x = float(token)
                src = [f"paper: {l.strip()}" for v, l in paper_lines
                       if round(abs(v), d) == x or round(100 * abs(v), d) == x]
                if not src:
                    src = [f"{f} ({v!r})" for v, f in origin.items()
                           if round(abs(v), d) == x
                           or round(100 * abs(v), d) == x][:1]
                print(f"{chapter}:{i}: {token} <- {src[0] if src else 'NONE'}")


def main():
    if "--explain" in sys.argv:
        origin = {}
        values = data_values(origin)
        lines = []
        if os.path.exists(PAPER):
            for line in open(PAPER, encoding="utf-8"):
                head = line.split("#", 1)[0].strip()
                if head:
                    lines.append((float(head.replace("−", "-")), line))
        explain(Matcher(values, [v for v, _ in lines]), origin, lines)
        return 0
    matcher = Matcher(data_values(), paper_values())
    listed = unstored()
    failures = 0
    # Each listed number must occur exactly once in its chapter, among all its
    # checked numbers (a matcher that matches nothing lists them all).
    nothing = Matcher([], [])
    for chapter, token in listed:
        text = open(os.path.join(BOOK, chapter), encoding="utf-8").read()
        count = sum("".join(n.split()) == token
                    for _, _, masked in prose_lines(text)
                    for n in check_line(masked, nothing))
        if count != 1:
            failures += 1
            print(f"{chapter}: tests/unstored_numbers.txt lists {token}, "
                  f"quoted {count} time(s)")
    for chapter in chapters():
        path = os.path.join(BOOK, chapter)
        text = open(path, encoding="utf-8").read()
        for i, line, masked in prose_lines(text):
            for number in check_line(masked, matcher):
                if (chapter, "".join(number.split())) in listed:
                    continue
                failures += 1
                print(f"{chapter}:{i}: {number}\n    {line.strip()}")
    if failures:
        print(f"\n{failures} number(s) in the book match neither data/ "
              f"nor tests/paper_numbers.txt")
        return 1
    print("every checked number in the book matches data/ or the paper")
    return 0


if __name__ == "__main__":
    sys.exit(main())
