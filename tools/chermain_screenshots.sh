#!/bin/sh
# The images of docs/chermain2020.md (run from the repository root; the car paint needs ../shared/assets).
# Usage: tools/chermain_screenshots.sh [build/glimmer]
set -eu
glimmer=${1:-build/glimmer}
TAA="--frames 16 --set aa=taa --set bloom.strength=0.04"
# shellcheck disable=SC2086
"$glimmer" render --scene sphere --method chermain2020 --size 384x384 $TAA --out screenshots/chermain2020_sphere.png
# Density sweep, Beckmann (the papers' base NDF) then GGX (our warp): log density 14, 20, 26, 32 and smooth, one row
# each (oiiotool --mosaic).
tmp=$(mktemp -d)
for ndf in beckmann ggx; do
    tiles=""
    for d in 14 20 26 32; do
        "$glimmer" render --scene sphere --size 160x160 --env none --set material.ndf=$ndf --method chermain2020 \
            --set chermain2020.log_density=$d --out "$tmp/$ndf$d.png"
        tiles="$tiles $tmp/$ndf$d.png"
    done
    "$glimmer" render --scene sphere --size 160x160 --env none --set material.ndf=$ndf --method smooth \
        --out "$tmp/${ndf}smooth.png"
    # shellcheck disable=SC2086
    oiiotool $tiles "$tmp/${ndf}smooth.png" --mosaic 5x1 -o "$tmp/row_$ndf.png"
done
oiiotool "$tmp/row_beckmann.png" "$tmp/row_ggx.png" --mosaic 1x2 -o screenshots/chermain2020_density_sweep.png
rm -r "$tmp"
car=../shared/assets/models/ClearCoatCarPaint/glTF/ClearCoatCarPaint.gltf
if [ -f "$car" ]; then
    # chermain2020 against chermain2021 (GGAA + LEAN) on the car paint's per-texel noise normal map.
    # shellcheck disable=SC2086
    "$glimmer" render --scene "$car" --size 256x256 --set material.glinty=1 $TAA --compare chermain2020,chermain2021 \
        --crop 120,70,40,30 --out screenshots/chermain2021_carpaint.png
fi
