#!/bin/sh
# The README's environment screenshots: a white metal sphere (smooth method) at alpha 0.01, 0.05, 0.2 and 0.5 under
# the procedural sky (with its sun light), rooitou_park and studio_small_03 (map only) (../shared/assets/hdri), 256x256 tiles in a 2 x 2 mosaic.
# Usage: tools/env_sphere_screenshots.sh [build/glimmer]   (run from the repository root; needs oiiotool)
set -eu
glimmer=${1:-build/glimmer}
hdri=../shared/assets/hdri
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
for env in procedural rooitou_park studio_small_03; do
    # Under a map the scene's sun light is turned off: the map alone lights the sphere (the procedural sky's sun
    # is that light, so it stays on there).
    case $env in procedural) spec=procedural; lights=1 ;; *) spec=$hdri/${env}_1k.hdr; lights=0 ;; esac
    tiles=""
    for alpha in 0.01 0.05 0.2 0.5; do
        "$glimmer" render --scene sphere --method smooth --env "$spec" --size 256x256 \
            --set material.metallic=1 --set material.alpha=$alpha --set light.intensity=$lights --out "$tmp/$env-$alpha.png" >/dev/null 2>&1
        tiles="$tiles $tmp/$env-$alpha.png"
    done
    # shellcheck disable=SC2086
    oiiotool $tiles --mosaic 2x2 -o "screenshots/env_sphere_$env.png"
    echo "screenshots/env_sphere_$env.png"
done
