#!/usr/bin/env bash
# Runs one cargo-fuzz target for SECONDS seconds and prints its run count.
#   tools/fuzz.sh obj|gltf|glb|disk|param|ply|stl|off|gifti|freesurfer SECONDS [more libFuzzer flags...]
# Needs the nightly toolchain (`cargo +nightly fuzz`); installs cargo-fuzz if missing.
# FUZZ_SANITIZER=none|address (default address); FUZZ_JOBS=N runs N jobs in parallel (the
# run count is then in fuzz/fuzz-*.log).
# The corpus (fuzz/corpus/TARGET) is seeded from the fixtures on first use; crashes land
# in fuzz/artifacts/TARGET (both ignored by git): turn each into a regression test in the
# crate that owns the bug, then delete it.
set -euo pipefail
usage="usage: tools/fuzz.sh obj|gltf|glb|disk|param|ply|stl|off|gifti|freesurfer SECONDS [libFuzzer flags...]"
root="$(cd "$(dirname "$0")/.." && pwd)"
target="${1:?$usage}"
secs="${2:?$usage}"
shift 2
case "$target" in
obj | disk | param) dict=obj.dict; max_len=16384 ;;
gltf | glb) dict=gltf.dict; max_len=131072 ;;
ply | stl | off | gifti | freesurfer) dict=formats.dict; max_len=131072 ;;
*)
    echo "$usage" >&2
    exit 2
    ;;
esac
command -v cargo-fuzz >/dev/null 2>&1 || cargo install cargo-fuzz --locked
"$root/tools/fuzz-corpus.sh" "$target" >/dev/null
cd "$root/fuzz"
log="$(mktemp)"
set +e
cargo +nightly fuzz run --sanitizer "${FUZZ_SANITIZER:-address}" "$target" "corpus/$target" -- \
    -max_total_time="$secs" -max_len="$max_len" -timeout=30 -rss_limit_mb=3072 \
    -dict="dicts/$dict" -print_final_stats=1 ${FUZZ_JOBS:+-jobs=$FUZZ_JOBS -workers=$FUZZ_JOBS} "$@" \
    2>&1 | tee "$log"
status=${PIPESTATUS[0]}
set -e
runs="$(grep -Eo 'Done [0-9]+ runs in [0-9]+ second' "$log" | tail -1 || true)"
echo "fuzz $target: ${runs:-no run count (see the log above)}; exit $status"
rm -f "$log"
exit "$status"
