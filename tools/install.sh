#!/usr/bin/env bash
# Installs the pinned tools this project uses into ./.tools/bin (no root, no global state):
# just (task runner), mdbook and mdbook-katex (the book, math rendered at build time).
# Takes about 6 minutes on a 2-core machine the first time; later runs are instant.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)/.tools"
need() {
    local crate=$1 version=$2 bin=$3
    if [ -x "$root/bin/$bin" ] && grep -qx "$crate $version" "$root/.versions" 2>/dev/null; then
        return
    fi
    cargo install --locked --quiet --root "$root" "$crate" --version "$version"
    mkdir -p "$root"
    { grep -vx "$crate .*" "$root/.versions" 2>/dev/null || true; echo "$crate $version"; } > "$root/.versions.tmp"
    mv "$root/.versions.tmp" "$root/.versions"
}
need just 1.59.0 just
need mdbook 0.5.4 mdbook
need mdbook-katex 0.10.0 mdbook-katex
echo "tools in $root/bin: $(ls "$root/bin" | tr '\n' ' ')"
