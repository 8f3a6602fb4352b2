#!/bin/sh
# Sparkle statistics (CV and p99.9 / mean of D / D_smooth over the highlight) of glint methods on plane25 and
# plane90 at their defaults: renders `--aov glint --env none` EXRs of each method and of smooth at 384x384 and runs
# the sparkle_stats tool (tools/sparkle_stats.cpp) on each pair. Prints one Markdown row per (method, scene).
# usage: tools/sparkle_stats.sh [GLIMMER [SPARKLE_STATS [METHODS [EXTRA --set ARGS...]]]]
set -e
GLIMMER=${1:-build/glimmer}
STATS=${2:-build/sparkle_stats}
METHODS=${3:-deliot2023 kemppinen2025 zirr2016 wang2020}
[ $# -gt 3 ] && shift 3 || set --
OUT=$(mktemp -d)
trap 'rm -rf "$OUT"' EXIT
echo "| method | scene | mean D/D_smooth | CV | p99.9 / mean | zero pixels |"
echo "|---|---|---|---|---|---|"
for scene in plane25 plane90; do
    "$GLIMMER" render --scene "$scene" --method smooth --env none --size 384x384 --aov glint --out "$OUT/smooth.exr" >/dev/null
    for method in $METHODS; do
        "$GLIMMER" render --scene "$scene" --method "$method" --env none --size 384x384 --aov glint "$@" \
            --out "$OUT/$method.exr" >/dev/null
        "$STATS" "$OUT/$method.exr" "$OUT/smooth.exr" | sed 's/[{}":,]/ /g' |
            awk -v m="$method" -v s="$scene" '{printf "| %s | %s | %s | %s | %s | %s |\n", m, s, $4, $6, $8, $10}'
    done
done
