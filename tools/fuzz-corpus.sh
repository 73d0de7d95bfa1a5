#!/usr/bin/env bash
# Seeds the cargo-fuzz corpus of one target from the fixtures (fuzz/corpus/TARGET, ignored
# by git). Idempotent: existing corpus files are kept.
#   tools/fuzz-corpus.sh obj|gltf|glb|disk|param|ply|stl|off|gifti|freesurfer
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
target="${1:?usage: tools/fuzz-corpus.sh obj|gltf|glb|disk|param|ply|stl|off|gifti|freesurfer}"
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

# Small PLY, STL, OFF, GIfTI and FreeSurfer seeds: small fixtures converted by
# conformap-io's formats_speed example (binary and ASCII where the format has both).
make_format_seeds() {
    local tmp
    tmp="$(mktemp -d)"
    (cd "$root" && cargo build -q --release -p conformap-io --example formats_speed) || return 0
    for m in "$fx/eightsim.obj" "$fx/bad/two_components.obj"; do
        "$root/target/release/examples/formats_speed" "$m" "$tmp" >/dev/null 2>&1 || true
    done
    case "$target" in
    ply) cp "$tmp"/*.ply "$dir/" ;;
    stl) cp "$tmp"/*.stl "$dir/" ;;
    off) cp "$tmp"/*.off "$dir/" ;;
    gifti) cp "$tmp"/*.gii "$dir/" ;;
    freesurfer) cp "$tmp"/*.white "$dir/" ;;
    esac
    rm -rf "$tmp"
}

case "$target" in
ply | stl | off | gifti | freesurfer)
    make_format_seeds
    ;;
obj)
    cp "$fx"/bad/*.obj "$dir/"
    cp "$fx/woody.obj" "$dir/"
    ;;
gltf)
    cp "$fx/gltf/quad_external.gltf" "$fx/gltf/triangle_data_uri.gltf" "$fx"/bad/*.gltf "$dir/"
    make_gltf_seeds gltf
    ;;
glb)
    cp "$fx"/gltf/*.glb "$fx"/bad/*.glb "$dir/"
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
param)
    # maps of the target's fixed hexagon (centre + 6 corners, 6 faces): flat and with vt
    v='v 0 0 0\nv 1 0 0\nv 0.5 0.8660254037844386 0\nv -0.5 0.8660254037844387 0\nv -1 0 0\nv -0.5 -0.8660254037844384 0\nv 0.5 -0.8660254037844386 0\n'
    printf "${v}f 1 2 3\nf 1 3 4\nf 1 4 5\nf 1 5 6\nf 1 6 7\nf 1 7 2\n" >"$dir/flat.obj"
    printf "${v}vt 0.5 0.5\nvt 1 0.5\nvt 0.75 0.93\nvt 0.25 0.93\nvt 0 0.5\nvt 0.25 0.07\nvt 0.75 0.07\n" >"$dir/uv.obj"
    printf "f 1/1 2/2 3/3\nf 1/1 3/3 4/4\nf 1/1 4/4 5/5\nf 1/1 5/5 6/6\nf 1/1 6/6 7/7\nf 1/1 7/7 2/2\n" >>"$dir/uv.obj"
    cp "$fx/bad/uv_seam.obj" "$dir/"
    ;;
*)
    echo "unknown target: $target (expected obj, gltf, glb, disk, param, ply, stl, off, gifti or freesurfer)" >&2
    exit 2
    ;;
esac
echo "$dir: $(ls "$dir" | wc -l) files"
