#!/usr/bin/env bash
# Renders every Khronos glTF test model of ../shared/assets/models/khronos-tests (docs/gltf_conformance.md) with
# `glimmer render` (default framing camera, smooth shading, the default procedural sky, whose horizon the
# normal-map tests want; KHRONOS_ENV=file.hdr picks a map from ../shared/assets/hdri) into screenshots/khronos/<Model>.png and tiles them, labelled, into screenshots/khronos_contact_sheet.png.
# The models' reference screenshots (ref_*) stay in ../shared (third-party assets are never copied here).
# Run from the repository root after a build.
set -euo pipefail
glimmer=${GLIMMER:-./build/glimmer}
assets=${GLIMMER_ASSETS_DIR:-../shared/assets}
models=$assets/models/khronos-tests
envArgs=()
if [ -n "${KHRONOS_ENV:-}" ]; then envArgs=(--env "$assets/hdri/$KHRONOS_ENV"); fi
out=screenshots/khronos
size=${KHRONOS_SIZE:-256x256}
mkdir -p "$out"
logs=$(mktemp -d)
font=${KHRONOS_FONT:-/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf}   # labels need a font file (fonts-dejavu-core)
label() {   # label IMAGE TEXT OUT X Y SIZE
    if [ -f "$font" ]; then oiiotool "$1" --text:x=$4:y=$5:size=$6:color=1,1,0:font="$font" "$2" -o "$3"; else cp "$1" "$3"; fi
}
tiles=()
for dir in "$models"/*/; do
    name=$(basename "$dir")
    file=$(find "$dir" -maxdepth 1 \( -name '*.gltf' -o -name '*.glb' \) | sort | head -1)
    png=$out/$name.png
    if $glimmer render --scene "$file" --method smooth "${envArgs[@]}" --size "$size" --out "$png" 2> "$logs/$name.log"; then
        :
    else
        # A refused model (Box-draco: KHR_draco_mesh_compression) gets a tile with the one-line error.
        oiiotool --pattern constant:color=0.15,0.15,0.15,1 "$size" 4 -o "$png"
        label "$png" "$(tail -1 "$logs/$name.log" | sed 's/.*: requires/requires/' | cut -c1-40)" "$png" 6 60 12
    fi
    label "$png" "$name" "$out/.tile_$name.png" 6 20 16
    tiles+=("$out/.tile_$name.png")
done
oiiotool "${tiles[@]}" --mosaic:pad=4 4x3 -o screenshots/khronos_contact_sheet.png
rm -f "${tiles[@]}"
echo "screenshots/khronos_contact_sheet.png"
