#!/bin/sh
# The README's animated comparison: the atrium's recorded camera path (content/atrium.path.json) rendered with
# four glint methods at 160x90, 5 frames per second, tiled 2x2 with labels and encoded as lossy WebP by ffmpeg.
# Usage: tools/walk_comparison.sh [build/glimmer] [screenshots/walk_methods.webp]
set -eu
glimmer=${1:-build/glimmer}
out=${2:-screenshots/walk_methods.webp}
command -v ffmpeg > /dev/null || { echo "walk_comparison.sh: needs the ffmpeg program (apt-get install ffmpeg)" >&2; exit 1; }
font=/usr/share/fonts/truetype/dejavu/DejaVuSansMono.ttf
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
inputs="" labels="" i=0
for method in smooth zirr2016 deliot2023 kemppinen2025; do
    mkdir -p "$work/$method"
    "$glimmer" render --scene atrium --method "$method" --size 160x90 --path content/atrium.path.json --fps 5 \
        --out "$work/$method/%03d.png" > /dev/null
    inputs="$inputs -framerate 5 -i $work/$method/%03d.png"
    labels="$labels[$i:v]drawtext=fontfile=$font:text=$method:x=3:y=3:fontsize=10:fontcolor=white:box=1:boxcolor=black@0.6:boxborderw=2[t$i];"
    i=$((i + 1))
done
# shellcheck disable=SC2086
ffmpeg -y -loglevel error $inputs -filter_complex "${labels}[t0][t1][t2][t3]xstack=inputs=4:layout=0_0|w0_0|0_h0|w0_h0" \
    -c:v libwebp -lossless 0 -q:v 55 -compression_level 6 -loop 0 "$out"
echo "$out"
