#!/usr/bin/env bash
# The pictures of docs/area_lights.md (run from the repository root after a build; needs oiiotool):
#  - the atrium's arcade and its big snow patch in shade (every light off, the sky alone), deliot2023 with
#    Kneiphof & Klein 2025's environment glints (ibl.glint_levels=4) and without (off): the snow sparkles from the sky;
#  - car paint under a rect light (content/area_lights.json);
#  - a comparison grid, one column per method (smooth, deliot2023, zirr2016, kemppinen2025, wang2020): the car paint
#    under the area lights (top row) and plane25 under the sky alone (bottom row; wang2020 with its own IBL mode).
# Usage: tools/area_light_screenshots.sh [build/glimmer]
set -euo pipefail
glimmer=${1:-build/glimmer}
out=screenshots
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for camera in arcade grazing; do
    for levels in 4 off; do
        name=$([[ $levels == off ]] && echo smooth || echo glints)
        "$glimmer" render --scene atrium --camera "$camera" --method deliot2023 --size 640x360 \
            --set light.intensity=0 --set ibl.glint_levels=$levels --out "$out/area_lights_${camera}_sky_$name.png"
    done
done
"$glimmer" render --scene area_lights --camera front --method deliot2023 --size 640x360 \
    --out "$out/area_lights_car_paint.png"
row1=() row2=()
for method in smooth deliot2023 zirr2016 kemppinen2025 wang2020; do
    "$glimmer" render --scene area_lights --camera side --method "$method" --size 256x256 --out "$tmp/lights_$method.png"
    "$glimmer" render --scene plane25 --method "$method" --size 256x256 --set light.intensity=0 \
        --set material.glinty=1 --set material.alpha=0.25 --out "$tmp/sky_$method.png"
    row1+=("$tmp/lights_$method.png")
    row2+=("$tmp/sky_$method.png")
done
oiiotool "${row1[@]}" "${row2[@]}" --mosaic:pad=4 5x2 -o "$out/area_lights_grid.png"
