#!/usr/bin/env bash
# Runs every command of a `conformap` binary on the fixtures and on shared meshes and keeps
# what it writes, so two builds can be compared file by file (refactors must leave every
# output byte-identical):
#
#   tools/outputs-snapshot.sh target/release/conformap /tmp/before
#   ... change, rebuild ...
#   tools/outputs-snapshot.sh target/release/conformap /tmp/after
#   tools/outputs-snapshot.sh --compare /tmp/before /tmp/after
#
# Reports are compared with their run-dependent fields removed (timings, memory, paths of
# the run); every other file byte for byte. Needs jq. Shared meshes are read from
# ../shared/meshes (skipped when absent).
set -uo pipefail
cd "$(dirname "$0")/.."

normalize() { # JSON (one document or JSON lines) without the run-dependent fields: every
    # key ending in `_ms` (timings), the memory limit and peak, the version
    jq -cS 'walk(if type == "object" then with_entries(select(.key
        | test("_ms$|^limit_bytes$|^limit_source$|^peak_rss|^conformap_version$") | not))
        else . end)' "$1"
}

if [[ "${1:-}" == "--compare" ]]; then
    a=$2 b=$3 bad=0
    for f in $(cd "$a" && find . -type f | sort); do
        if [[ ! -f "$b/$f" ]]; then echo "missing in $b: $f"; bad=1; continue; fi
        case "$f" in
        *.json | *.jsonl)
            if ! diff -q <(normalize "$a/$f") <(normalize "$b/$f") >/dev/null; then
                echo "differs: $f"; bad=1
            fi ;;
        *.stderr) ;; # summary lines carry times
        *.stdout) # JSON (info --json, metrics --json, batch lines) or text
            if jq -e . "$a/$f" >/dev/null 2>&1; then
                diff -q <(normalize "$a/$f") <(normalize "$b/$f") >/dev/null \
                    || { echo "differs: $f"; bad=1; }
            elif ! cmp -s "$a/$f" "$b/$f"; then echo "differs: $f"; bad=1; fi ;;
        *)
            if ! cmp -s "$a/$f" "$b/$f"; then echo "differs: $f"; bad=1; fi ;;
        esac
    done
    for f in $(cd "$b" && find . -type f | sort); do
        [[ -f "$a/$f" ]] || { echo "new in $b: $f"; bad=1; }
    done
    [[ $bad == 0 ]] && echo "identical: $(cd "$a" && find . -type f | wc -l) files"
    exit $bad
fi

bin=$(realpath "$1") out=$2
rm -rf "$out" && mkdir -p "$out"
S=../shared/meshes
run() { # name, then the command's arguments; records the exit code and stdout
    local name=$1; shift
    (cd "$out" && "$bin" "$@" >"$name.stdout" 2>"$name.stderr"; echo $? >"$name.exit")
}
F=$PWD/fixtures
run disk_spothead disk "$F/spothead.obj" -o spothead_uv.obj --flat spothead_flat.obj \
    --report spothead.json --png spothead
run disk_woody_glb disk "$F/woody.obj" -o woody_uv.glb --report woody.json
run disk_woody_cem disk "$F/woody.obj" --method cem -o woody_cem.obj --report woody_cem.json
run disk_alligator disk "$F/alligator.obj" -o alligator_uv.obj --report alligator.json
run disk_holes disk "$F/halftunnel.obj" -o halftunnel_uv.obj --report halftunnel.json
run sphere_spot sphere "$F/spot.obj" -o spot_uv.obj --flat spot_sphere.obj --report spot.json \
    --png spot
run sphere_spot_uniform sphere "$F/spot.obj" --mobius uniform -o spot_u.gltf --report spot_u.json
run global_eightsim global "$F/eightsim.obj" -o eightsim_uv.obj --flat eightsim_flat.obj \
    --report eightsim.json -q
run global_ptorus global "$F/punctured_torus.obj" -o ptorus_uv.glb --report ptorus.json -q
run global_topo global "$F/spot.obj" --topology-opt -o spot_topo.obj --report spot_topo.json -q
run mobius_disk mobius "$F/spothead.obj" spothead_uv.obj --domain disk --objective uniform \
    -o spothead_mobius.obj --report spothead_mobius.json
run mobius_sphere mobius "$F/spot.obj" spot_sphere.obj --domain sphere --objective uniform \
    -o spot_mobius.obj --report spot_mobius.json
run metrics metrics "$F/spothead.obj" spothead_uv.obj --json
run info info "$F/halftunnel.obj" --json
run render_surface render "$F/spothead.obj" spothead_uv.obj -o r_surface.png --size 256
run render_map render "$F/spothead.obj" spothead_uv.obj -o r_map.png --view map --color angle \
    --size 256
run render_hist render "$F/spothead.obj" spothead_uv.obj -o r_hist.png --view histogram
run render_sphere render "$F/spot.obj" spot_sphere.obj -o r_sphere.png --size 256
run morph_glb morph "$F/morph/ict_neutral.obj" "$F/morph/ict_pout.obj" --landmarks \
    "$F/morph/ict_neutral.landmarks.txt" "$F/morph/ict_pout.landmarks.txt" --frames 4 \
    -o morph.glb --report morph.json
mkdir -p "$out/frames"
run morph_dir morph "$F/morph/ict_neutral.obj" "$F/morph/ict_pout.obj" --landmarks \
    "$F/morph/ict_neutral.landmarks.txt" "$F/morph/ict_pout.landmarks.txt" --frames 3 \
    -o frames/ --hard
mkdir -p "$out/batch"
run batch batch --command disk --out-dir batch --report batch.jsonl "$F/woody.obj" \
    "$F/alligator.obj" "$F/spot.obj"
if [[ -d $S ]]; then
    S=$(realpath $S)
    run s_disk_face disk "$S/human_face.obj" -o face_uv.obj --report face.json
    run s_disk_holes disk "$S/alex_3holes.obj" -o alex_uv.obj --report alex.json
    run s_sphere_david sphere "$S/david_head.obj" --mobius uniform -o david_uv.obj \
        --flat david_sphere.obj --report david.json
    run s_global_eight global "$S/eight.obj" -o eight_uv.obj --report eight.json -q
    run s_global_torus global "$S/torus.obj" -o torus_uv.glb --flat torus_flat.obj \
        --report torus.json -q
    run s_mobius_face mobius "$S/human_face.obj" face_uv.obj --domain disk \
        --objective uniform -o face_mobius.obj --report face_mobius.json
    run s_render_face render "$S/human_face.obj" face_uv.obj -o face.png --size 256
fi
echo "wrote $(find "$out" -type f | wc -l) files to $out"
