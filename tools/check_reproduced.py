"""After the main job (`cargo run --release -- reproduce`), `git status` must be clean.

The README's promise is that the main job rewrites data/ and figures/ with what is
committed: every table and figure is a deterministic function of the code. This script
is the check `.ci/run` makes between the README's two commands:

- a file the main job wrote that git does not know (and does not ignore) fails;
- a committed text file (CSV, Markdown, TXT, SVG) that changed fails, unless every
  number in it is within a relative 1e-9 of the committed one, token by token (a CPU
  whose floating-point kernels differ in the last bit; reported, not failed);
- a changed PNG is reported; it fails only when a text file failed, since every
  figure is drawn from a CSV.

Machine-dependent files are git-ignored (data/local/), so they never show here.
Exit status 0 when clean (or rounding-level only), 1 otherwise.
"""

import re
import subprocess
import sys

NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?|NaN|inf")
TEXT = (".csv", ".md", ".txt", ".svg", ".toml")
REL = 1e-9


def git(*args):
    return subprocess.run(["git", *args], check=True, capture_output=True).stdout


def numbers_close(old, new):
    """Whether two texts differ only in numbers, each within REL of the other."""
    split_old, split_new = NUMBER.split(old), NUMBER.split(new)
    if split_old != split_new:
        return False
    for a, b in zip(NUMBER.findall(old), NUMBER.findall(new)):
        if a == b:
            continue
        try:
            x, y = float(a), float(b)
        except ValueError:
            return False
        if abs(x - y) > REL * max(abs(x), abs(y)):
            return False
    return True


def main():
    status = git("status", "--porcelain", "--untracked-files=all").decode()
    failed, rounding, pictures = [], [], []
    for line in status.splitlines():
        code, path = line[:2], line[3:]
        if code == "??":
            failed.append(f"{path}: written by the main job but not committed (nor ignored)")
        elif path.endswith(TEXT):
            old = git("show", f"HEAD:{path}").decode("utf-8", "replace")
            try:
                new = open(path, encoding="utf-8", errors="replace").read()
            except FileNotFoundError:
                failed.append(f"{path}: deleted by the main job")
                continue
            if numbers_close(old, new):
                rounding.append(path)
            else:
                failed.append(f"{path}: differs from the committed file beyond a relative {REL:g}")
        else:
            pictures.append(path)
    for path in rounding:
        print(f"rounding only (within {REL:g}): {path}")
    for path in pictures:
        print(f"changed picture (drawn from the tables above): {path}")
    for msg in failed:
        print(f"FAIL {msg}")
    if failed:
        print("the main job does not reproduce the committed data/ and figures/: "
              "commit a full `cargo run --release -- reproduce` or find what is not deterministic")
        return 1
    print("after the main job: git status clean" if not status.strip()
          else "after the main job: only rounding-level changes")
    return 0


if __name__ == "__main__":
    sys.exit(main())
