#!/bin/sh
# README's hero image, comparison grids and TAA crop grid, rendered through the image pipeline (docs/image.md):
# 16 jittered frames of a still camera resolved by TAA, bloom 0.04; the hero is also auto-exposed, the comparison
# grids keep manual exposure 0 so that every method's tile has the same exposure.
# Usage: tools/readme_images.sh [build/glimmer] [all|hero|grids|crops|taau]   (run from the repository root)
set -eu
glimmer=${1:-build/glimmer}
what=${2:-all}
TAA="--frames 16 --set aa=taa --set bloom.strength=0.04"
if [ "$what" = all ] || [ "$what" = hero ]; then
    # shellcheck disable=SC2086
    "$glimmer" render --scene atrium --camera court --method deliot2023 --size 1280x720 $TAA --set exposure=auto \
        --out screenshots/hero_atrium_deliot2023.png
fi
if [ "$what" = all ] || [ "$what" = grids ]; then
    # Every method and the discrete-facet reference (issue 36): the material as it is, counted facet by facet.
    M=deliot2023,zirr2016,kemppinen2025,wang2020,chermain2020,reference
    E="--env none --set material.alpha=0.15"
    # shellcheck disable=SC2086
    "$glimmer" render --scene plane90 --size 256x256 $E $TAA --compare $M --crop 200,96,32,24 --crop 30,170,32,24 \
        --out screenshots/compare_plane90.png
    # shellcheck disable=SC2086
    "$glimmer" render --scene plane25 --size 256x256 $E $TAA --compare $M --crop 200,96,32,24 --crop 30,170,32,24 \
        --out screenshots/compare_plane25.png
    # shellcheck disable=SC2086
    "$glimmer" render --scene atrium --camera overview --size 480x270 $E $TAA --compare $M --crop 218,165,36,27 \
        --crop 261,208,36,27 --out screenshots/compare_atrium.png
fi
if [ "$what" = all ] || [ "$what" = crops ]; then
    # No AA (left) vs TAA (right), same exposure, no bloom: the atrium's columns (edges) and snow (glints),
    # 160x120 crops of a 640x360 render enlarged 3x (nearest neighbour), 2x2.
    command -v oiiotool > /dev/null || { echo "readme_images.sh: needs oiiotool (apt-get install openimageio-tools)" >&2; exit 1; }
    work=$(mktemp -d)
    trap 'rm -rf "$work"' EXIT
    view="--scene atrium --camera court --method deliot2023 --size 640x360"
    # shellcheck disable=SC2086
    "$glimmer" render $view --out "$work/off.png" > /dev/null
    # shellcheck disable=SC2086
    "$glimmer" render $view --frames 16 --set aa=taa --out "$work/taa.png" > /dev/null
    for name in off taa; do
        oiiotool "$work/$name.png" --cut 160x120+60+120 --resize:filter=box 480x360 -o "$work/$name-edges.png"
        oiiotool "$work/$name.png" --cut 160x120+220+240 --resize:filter=box 480x360 -o "$work/$name-glints.png"
    done
    oiiotool "$work/off-edges.png" "$work/taa-edges.png" "$work/off-glints.png" "$work/taa-glints.png" \
        --mosaic:pad=4 2x2 -o screenshots/image_taa_crops.png
fi
if [ "$what" = all ] || [ "$what" = taau ]; then
    # TAA upsampling at render_scale 0.5 (docs/image.md): no AA + the Catmull-Rom upscale (left), TAAU after 32
    # frames (middle), the 4x4 supersampled reference at the output size (right); 160x120 crops of 640x360
    # (columns and snow), enlarged 2x (nearest neighbour).
    command -v oiiotool > /dev/null || { echo "readme_images.sh: needs oiiotool (apt-get install openimageio-tools)" >&2; exit 1; }
    work=$(mktemp -d)
    trap 'rm -rf "$work"' EXIT
    view="--scene atrium --camera court --method deliot2023 --size 640x360"
    # shellcheck disable=SC2086
    "$glimmer" render $view --render-scale 0.5 --out "$work/off.png" > /dev/null
    # shellcheck disable=SC2086
    "$glimmer" render $view --render-scale 0.5 --frames 32 --set aa=taa --out "$work/taau.png" > /dev/null
    # shellcheck disable=SC2086
    "$glimmer" render $view --set aa=ssaa --out "$work/ssaa.png" > /dev/null
    for name in off taau ssaa; do
        oiiotool "$work/$name.png" --cut 160x120+60+120 --resize:filter=box 320x240 -o "$work/$name-crop.png"
    done
    oiiotool "$work/off-crop.png" "$work/taau-crop.png" "$work/ssaa-crop.png" --mosaic:pad=4 3x1 \
        -o screenshots/image_taau_crops.png
fi
