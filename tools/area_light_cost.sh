#!/usr/bin/env bash
# Issue 37's performance ratios on this machine, measured side by side in one run (docs/area_lights.md):
#  - kk24: deliot2023 on plane90 under one rect light against one directional light of about the same irradiance
#    (content/bench/rect_plane.json, sun_plane.json);
#  - kk25: deliot2023 on plane25 and in the atrium court with environment glints (ibl.glint_levels=4, 8) against
#    without (off).
# Cases alternate A B A B ... for ROUNDS rounds, each a `render --stats --frames FRAMES`; per case the median over
# rounds of the median frame after the first (wall ms around glFinish and process CPU ms, all threads), and of the
# lighting pass. The load average is printed before and after.
#   tools/area_light_cost.sh [EXE] [SIZE] [ROUNDS] [FRAMES]     defaults: build/glimmer 640x360 3 4
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
exe=${1:-$root/build/glimmer}; size=${2:-640x360}; rounds=${3:-3}; frames=${4:-4}
out=$(mktemp --suffix=.png); log=$(mktemp)
trap 'rm -f "$out" "$log"' EXIT
run() {   # name, then render arguments
  local name=$1; shift
  GALLIUM_OVERRIDE_CPU_CAPS=${GALLIUM_OVERRIDE_CPU_CAPS:-avx} "$exe" render --method deliot2023 --size "$size" \
      --frames "$frames" --stats --out "$out" "$@" 2>/dev/null |
    python3 -c '
import json, statistics, sys
s = json.load(sys.stdin)
wall = s["frames_ms"][1:] or s["frames_ms"]
cpu = s["frames_cpu_ms"][1:] or s["frames_cpu_ms"]
light = [p["wall_ms"] for p in s["passes"] if p["name"] == "lighting"]
print(sys.argv[1], statistics.median(wall), statistics.median(cpu), light[0] if light else 0.0)' "$name" >> "$log"
}
echo "# $size, $rounds rounds x $frames frames; load before: $(cut -d' ' -f1-3 /proc/loadavg)"
for ((r = 0; r < rounds; ++r)); do
  run sun --scene "$root/content/bench/sun_plane.json"
  run rect --scene "$root/content/bench/rect_plane.json"
  for scene in plane25 atrium; do
    camera=(); [[ $scene == atrium ]] && camera=(--camera court)
    for levels in off 4 8; do run "$scene/env-$levels" --scene "$scene" "${camera[@]}" --set ibl.glint_levels=$levels; done
  done
done
echo "# load after: $(cut -d' ' -f1-3 /proc/loadavg)"
python3 - "$log" <<'PY'
import statistics, sys
rows = {}
for line in open(sys.argv[1]):
    name, wall, cpu, light = line.split()
    rows.setdefault(name, []).append((float(wall), float(cpu), float(light)))
med = {k: [statistics.median(v[i] for v in vs) for i in range(3)] for k, vs in rows.items()}
print("| case | frame wall ms | frame CPU ms | lighting wall ms |")
print("|---|---|---|---|")
for k, (w, c, l) in med.items():
    print(f"| {k} | {w:.1f} | {c:.1f} | {l:.1f} |")
def ratio(a, b):
    return " / ".join(f"{med[a][i] / med[b][i]:.2f}x" for i in range(3))
print()
print("rect / sun (frame wall / CPU / lighting):", ratio("rect", "sun"))
for scene in ("plane25", "atrium"):
    for levels in ("4", "8"):
        print(f"{scene} env glints {levels} / off:", ratio(f"{scene}/env-{levels}", f"{scene}/env-off"))
PY
