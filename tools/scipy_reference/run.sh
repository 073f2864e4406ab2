#!/usr/bin/env bash
# Create (once) the venv .tools/venv-scipy at the repository root, install the pinned
# requirements into it, and run evhi_scipy.py with the given arguments.
#   tools/scipy_reference/run.sh --scenario figure --n 128 --steps 128 --repeat 5 --check DIR
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
root="$(cd "$here/../.." && pwd)"
venv="$root/.tools/venv-scipy"
py="${PYTHON:-python3}"
if [ ! -x "$venv/bin/python" ]; then
    "$py" -m venv "$venv"
fi
# pip is quick when the pins are already satisfied; re-run it so a changed pin takes effect
if ! "$venv/bin/python" -c 'import sys, importlib.metadata as m
want = dict(l.strip().split("==") for l in open(sys.argv[1]) if "==" in l)
sys.exit(any(m.version(k) != v for k, v in want.items()))' "$here/requirements.txt" 2>/dev/null; then
    "$venv/bin/pip" install --quiet -r "$here/requirements.txt"
fi
exec "$venv/bin/python" "$here/evhi_scipy.py" "$@"
