#!/bin/sh
# The README's atrium screenshots: every camera of the atrium with deliot2023 under the default sky, 640x360
# (shadows, ambient occlusion and reflection probes at their defaults), plus the window without its UI.
# Usage: tools/atrium_screenshots.sh [build/glimmer]   (run from the repository root)
set -eu
glimmer=${1:-build/glimmer}
for camera in entrance court objects grazing arcade gallery overview; do
    "$glimmer" render --scene atrium --camera "$camera" --method deliot2023 --size 640x360 \
        --out "screenshots/atrium_$camera.png"
done
