#!/usr/bin/env bash
# Seeds the cargo-fuzz corpus of one target from the fixtures (fuzz/corpus/TARGET, ignored
# by git). Idempotent: existing corpus files are kept.
#   tools/fuzz-corpus.sh obj|gltf|glb|disk
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
target="${1:?usage: tools/fuzz-corpus.sh obj|gltf|glb|disk}"
dir="$root/fuzz/corpus/$target"
mkdir -p "$dir"
fx="$root/fixtures"

# Small glTF/GLB seeds written by conformap itself (embedded buffers, with and without
# TEXCOORD_0), from the small bad fixtures after --repair.
make_gltf_seeds() {
    local ext="$1" tmp
    tmp="$(mktemp -d)"
    (cd "$root" && cargo build -q --release -p conformap-cli) || return 0
    local bin="$root/target/release/conformap"
    for m in two_components dirty_disk; do
        "$bin" disk "$fx/bad/$m.obj" --repair -o "$tmp/$m.$ext" --flat "$tmp/${m}_flat.$ext" \
            2>/dev/null || true
    done
    cp "$tmp"/*."$ext" "$dir/" 2>/dev/null || true
    rm -rf "$tmp"
}

case "$target" in
obj)
    cp "$fx"/bad/*.obj "$dir/"
    cp "$fx/woody.obj" "$dir/"
    ;;
gltf)
    cp "$fx/gltf/quad_external.gltf" "$dir/"
    make_gltf_seeds gltf
    ;;
glb)
    cp "$fx/gltf/woody.glb" "$fx/gltf/woody_soup.glb" "$dir/"
    make_gltf_seeds glb
    ;;
disk)
    # even first byte: an OBJ follows; odd: a perturbed grid (see fuzz/src/lib.rs)
    for f in "$fx"/bad/*.obj; do
        { printf '\000'; cat "$f"; } >"$dir/obj0_$(basename "$f")"
        { printf '\002'; cat "$f"; } >"$dir/obj2_$(basename "$f")"
    done
    for mode in 1 3 5 9 11 13 17 25 33 67 75; do
        printf "\\$(printf %03o "$mode")\\004hello-disk-seed-$mode" >"$dir/grid_$mode"
    done
    ;;
*)
    echo "unknown target: $target (expected obj, gltf, glb or disk)" >&2
    exit 2
    ;;
esac
echo "$dir: $(ls "$dir" | wc -l) files"
