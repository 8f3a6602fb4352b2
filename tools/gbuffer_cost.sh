#!/usr/bin/env bash
# G-buffer pass cost per view, two builds side by side in one run (before / after a geometry change):
#   tools/gbuffer_cost.sh BEFORE_EXE BEFORE_SHADER_DIR AFTER_EXE AFTER_SHADER_DIR [REPEATS]
# For every atrium camera at 640x360 and 64x36, and sphere / plane90 at 640x360: `render --stats --frames 5`
# (smooth, --env none: the environment does not touch the G-buffer pass), the builds alternating case by case,
# REPEATS times (default 3); prints a Markdown table of the minimum `gbuffer` wall ms per case (the least
# disturbed run on a shared machine) and the ratio. The load average is printed before and after.
set -euo pipefail
before=$1; beforeShaders=$2; after=$3; afterShaders=$4; repeats=${5:-3}
root=$(cd "$(dirname "$0")/.." && pwd)
cameras=$(python3 -c 'import json,sys; print(" ".join(c["name"] for c in json.load(open(sys.argv[1]))["cameras"]))' \
          "$root/content/atrium.json")
cases=()
for size in 640x360 64x36; do for c in $cameras; do cases+=("atrium:$c:$size"); done; done
cases+=("sphere::640x360" "plane90::640x360")
echo "load before: $(cut -d' ' -f1-3 /proc/loadavg)" >&2
gbuffer() {  # exe shaders scene camera size -> "gbuffer_ms triangles_drawn"
  local args=(render --scene "$3" --size "$5" --frames 5 --stats --env none --method smooth --shader-dir "$2"
              --out /tmp/gbuffer_cost_$$.png)
  [[ -n "$4" ]] && args+=(--camera "$4")
  "$1" "${args[@]}" 2>/dev/null | python3 -c 'import json,sys; s=json.load(sys.stdin);
print(next(p["wall_ms"] for p in s["passes"] if p["name"]=="gbuffer"), s.get("gbuffer_draw",{}).get("triangles_drawn", s["counts"]["triangles"]))'
}
declare -A best
for ((r = 0; r < repeats; ++r)); do
  for k in "${cases[@]}"; do
    IFS=: read -r scene camera size <<< "$k"
    for which in before after; do
      if [[ $which == before ]]; then out=$(gbuffer "$before" "$beforeShaders" "$scene" "$camera" "$size")
      else out=$(gbuffer "$after" "$afterShaders" "$scene" "$camera" "$size"); fi
      ms=${out% *}; tris=${out#* }
      key="$which|$k"
      if [[ -z "${best[$key]:-}" ]] || python3 -c "import sys; sys.exit(0 if $ms < ${best[$key]%% *} else 1)"; then
        best[$key]="$ms $tris"
      fi
    done
  done
done
echo "load after: $(cut -d' ' -f1-3 /proc/loadavg)" >&2
echo "| scene | camera | size | before ms | after ms | ratio | triangles before | triangles drawn after |"
echo "|---|---|---|---|---|---|---|---|"
for k in "${cases[@]}"; do
  IFS=: read -r scene camera size <<< "$k"
  read -r bms btris <<< "${best[before|$k]}"
  read -r ams atris <<< "${best[after|$k]}"
  printf '| %s | %s | %s | %.1f | %.1f | %.2fx | %s | %s |\n' "$scene" "${camera:--}" "$size" "$bms" "$ams" \
    "$(python3 -c "print($bms / $ams)")" "$btris" "$atris"
done
rm -f /tmp/gbuffer_cost_$$.png
