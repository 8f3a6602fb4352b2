#!/usr/bin/env bash
# Where the frame time goes, per pass and per render size, for one atrium camera (issue 19):
#   tools/frame_cost.sh [EXE] [SHADER_DIR] [CAMERA] [METHOD] [FRAMES] [SIZES...]
# defaults: build/glimmer shaders court deliot2023 4  64x36 320x180 1280x720
# (320x180 is 1280x720 at the minimum render scale 0.25). For each size: `render --stats --frames FRAMES` and one
# line per pass of the last frame (wall ms around glFinish), then the frame's wall ms and its process CPU ms (all
# threads, CLOCK_PROCESS_CPUTIME_ID: the work itself, far less sensitive to other processes than the wall clock on
# a shared machine), both the median of the frames after the first (the first captures probes, bakes shadows
# and builds programs). The load average is printed before and after each size.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
exe=${1:-$root/build/glimmer}; shaders=${2:-$root/shaders}; camera=${3:-court}; method=${4:-deliot2023}
frames=${5:-4}; shift $(( $# < 5 ? $# : 5 )) || true
sizes=("$@"); [[ ${#sizes[@]} -gt 0 ]] || sizes=(64x36 320x180 1280x720)
out=$(mktemp --suffix=.png)
trap 'rm -f "$out"' EXIT
for size in "${sizes[@]}"; do
  echo "# $camera $method $size  load before: $(cut -d' ' -f1-3 /proc/loadavg)"
  GALLIUM_OVERRIDE_CPU_CAPS=${GALLIUM_OVERRIDE_CPU_CAPS:-avx} "$exe" render --scene atrium --camera "$camera" \
      --method "$method" --size "$size" --frames "$frames" --stats --shader-dir "$shaders" --out "$out" 2>/dev/null |
    python3 -c '
import json, statistics, sys
s = json.load(sys.stdin)
for p in s["passes"]:
    print("  %-14s %10.1f ms wall" % (p["name"], p["wall_ms"]))
wall = s["frames_ms"][1:] or s["frames_ms"]
cpu = s["frames_cpu_ms"][1:] or s["frames_cpu_ms"]
tris = s.get("gbuffer_draw", {}).get("triangles_drawn", "?")
print("  %-14s %10.1f ms wall   %8.1f ms process CPU   (%s G-buffer triangles)"
      % ("frame", statistics.median(wall), statistics.median(cpu), tris))'
  echo "# load after: $(cut -d' ' -f1-3 /proc/loadavg)"
done
