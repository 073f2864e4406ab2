# Recipes for evhi. `just` itself: ./tools/install.sh (installs just, mdbook, mdbook-katex
# into ./.tools with `cargo install --locked`, pinned versions).

export PATH := justfile_directory() + "/.tools/bin:" + env_var('PATH')

# Reproduce the paper's figures and tables into figures/ and data/
reproduce *ARGS:
    cargo run --release -- reproduce {{ARGS}}

# Run every test (numerical tests are compiled optimised)
test:
    cargo test --release

# Everything CI checks
ci:
    bash .ci/run

# One run of the solver, e.g. `just solve --scenario figure --n 128 --steps 128 --out runs/f128`
solve *ARGS:
    cargo run --release -- solve {{ARGS}}

# Build the book into book/book/ (installs just, mdbook and mdbook-katex on first use), then
# check every chapter at 1280 px in headless Chromium: it fails naming what is wider than
# the text column (tools/book_overflow.py; skipped where no chromium is installed)
book:
    bash tools/install.sh
    rm -rf book/src/figures && mkdir -p book/src/figures && cp figures/*.png book/src/figures/
    .tools/bin/mdbook build book
    @echo "book: book/book/index.html"
    @if command -v chromium >/dev/null; then python3 tools/book_overflow.py book/book; else echo "book: no chromium, the column check skipped"; fi

# Serve the book locally with live reload
serve-book:
    bash tools/install.sh
    rm -rf book/src/figures && mkdir -p book/src/figures && cp figures/*.png book/src/figures/
    .tools/bin/mdbook serve book

# Fuzz scenario parsing and law construction with libFuzzer (cargo-fuzz; the stable
# toolchain is told to accept the sanitizer flags), e.g. `just fuzz scenario 200000`
fuzz TARGET="scenario" RUNS="100000":
    test -x .tools/bin/cargo-fuzz || cargo install --locked cargo-fuzz --version 0.13.2 --root .tools
    cd fuzz && RUSTC_BOOTSTRAP=1 ../.tools/bin/cargo-fuzz run -O {{TARGET}} -- -runs={{RUNS}}
