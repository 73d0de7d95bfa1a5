# conformap developer recipes. The README's two commands are plain cargo; these are extras.

# format everything
fmt:
    cargo fmt --all

# lint, warnings are errors
clippy:
    cargo clippy --workspace --all-targets -- -D warnings

# the test suite (what CI runs)
test:
    cargo test --workspace

# docs, warnings are errors
doc:
    RUSTDOCFLAGS="-D warnings" cargo doc --workspace --no-deps

# everything CI and review expect
check: fmt clippy test doc

# benchmarks on ../shared/meshes and generated meshes (see docs/benchmarks.md)
bench *ARGS:
    cargo run --release -p conformap-bench -- {{ARGS}}

# regenerate golden reports on purpose
bless:
    CONFORMAP_BLESS=1 cargo test -p conformap-cli --test golden

# licences, advisories, bans and sources of the dependency tree (cargo install cargo-deny)
deny:
    cargo deny check
