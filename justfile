# Recipes for evhi. `just` itself: ./tools/install.sh (installs just, mdbook, mdbook-katex
# into ./.tools with `cargo install --locked`, pinned versions).

export PATH := justfile_directory() + "/.tools/bin:" + env_var('PATH')

# Reproduce the paper's figures and tables into figures/ and data/
reproduce *ARGS:
    cargo run --release -- reproduce {{ARGS}}

# Run every test (numerical tests are compiled optimised)
test:
    cargo test

# Everything CI checks
ci:
    bash .ci/run

# One run of the solver, e.g. `just solve --scenario figure --n 128 --steps 128 --out runs/f128`
solve *ARGS:
    cargo run --release -- solve {{ARGS}}
