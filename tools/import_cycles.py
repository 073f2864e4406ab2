#!/usr/bin/env python3
"""Lists the import cycles among the top-level modules of src/ (code only, not comments).

A module names another as `crate::x`, or, in the binary's modules (cli, bench,
experiments), as `evhi::x` (the library)."""
import glob
import re
import sys

mods = {}
for f in glob.glob("src/**/*.rs", recursive=True):
    if f in ("src/main.rs", "src/lib.rs"):
        continue
    top = f[4:-3].replace("/mod", "").split("/")[0]
    # Code only: no comments, no string literals.
    code = "\n".join(re.sub(r'"(?:[^"\\]|\\.)*"', '""', l).split("//")[0] for l in open(f))
    deps = set(re.findall(r"\b(?:crate|evhi)::(\w+)", code))
    mods.setdefault(top, set()).update(d for d in deps if d != top)


def reach(a):
    seen, stack = set(), [a]
    while stack:
        for y in mods.get(stack.pop(), ()):
            if y not in seen:
                seen.add(y)
                stack.append(y)
    return seen


cycles = sorted({tuple(sorted((a, b))) for a in mods for b in mods[a] if a in reach(b)})
for a, b in cycles:
    print(f"cycle: {a} <-> {b}")
sys.exit(1 if cycles else 0)
