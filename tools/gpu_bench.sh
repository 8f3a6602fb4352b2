#!/usr/bin/env bash
# GPU numbers in one command: builds Release, runs the paper suites (DB23 Table 1, Kemppinen Table 3, Kneiphof & Klein
# 2024's area light against a directional light, Kneiphof & Klein 2025's environment glints) (`glimmer bench --suite ...`, docs/bench.md)
# and the atrium with deliot2023 at every camera of its walkthrough path (content/atrium.json "walkthrough"), all
# on the EGL device platform (engine/platform/egl_context.cpp picks an EGL device when the driver lists one) with
# per-pass GL timer queries (`gpu_timer_ms`, meaningful on real GPUs) beside the glFinish wall clock, and writes
# gpu_bench.json + gpu_bench.md (plus each suite's own JSON / Markdown) to OUTDIR.
#
#   tools/gpu_bench.sh [OUTDIR]          1920x1080, 20 frames per case, 3 warm-up; meant to finish in < 5 min on a GPU
#   GPU_BENCH_SMOKE=1 tools/gpu_bench.sh 320x180, 2 frames, no warm-up: a smoke test of the script on llvmpipe
#
# Environment: BUILD_DIR (default build-gpu-bench), JOBS (default nproc), GPU_BENCH_SIZE / GPU_BENCH_FRAMES to
# override. Exits non-zero on the first failing step, naming it.
set -euo pipefail
root=$(cd "$(dirname "$0")/.." && pwd)
out=${1:-$root/gpu_bench_out}
build=${BUILD_DIR:-$root/build-gpu-bench}
jobs=${JOBS:-$(nproc)}
if [[ "${GPU_BENCH_SMOKE:-0}" == 1 ]]; then
  size=${GPU_BENCH_SIZE:-320x180}; frames=${GPU_BENCH_FRAMES:-2}; warmup=0
else
  size=${GPU_BENCH_SIZE:-1920x1080}; frames=${GPU_BENCH_FRAMES:-20}; warmup=3
fi
mkdir -p "$out"
step() { echo "gpu_bench: $*" >&2; }
fail() { echo "gpu_bench: $1 failed (see $out/log.txt)" >&2; exit 1; }
start=$(date +%s)

step "building Release in $build"
# An existing build folder (BUILD_DIR=build) keeps its configuration; a new one is configured without tests.
{ if [[ ! -f "$build/CMakeCache.txt" ]]; then
    cmake -S "$root" -B "$build" -G Ninja -DCMAKE_BUILD_TYPE=Release -DGLIMMER_TESTS=OFF; fi &&
  cmake --build "$build" -j"$jobs" --target glimmer; } > "$out/log.txt" 2>&1 || fail "build"
glimmer="$build/glimmer"

for suite in deliot2023-table1 kemppinen2025-table3 kk24-area-lights kk25-environment; do
  step "suite $suite at $size, $frames frames"
  "$glimmer" bench --suite "$suite" --backend egl --size "$size" --frames "$frames" --warmup "$warmup" \
      --json "$out/$suite.json" --markdown "$out/$suite.md" > /dev/null 2>> "$out/log.txt" || fail "suite $suite"
done

cameras=$(python3 -c 'import json,sys; print(" ".join(json.load(open(sys.argv[1]))["walkthrough"]))' \
          "$root/content/atrium.json")
for camera in $cameras; do
  step "atrium $camera at $size (deliot2023)"
  "$glimmer" render --scene atrium --camera "$camera" --method deliot2023 --backend egl --size "$size" \
      --frames "$frames" --stats --out "$out/atrium_$camera.png" > "$out/atrium_$camera.json" 2>> "$out/log.txt" \
      || fail "atrium camera $camera"
done

python3 - "$out" "$size" "$frames" $cameras <<'PY' || fail "summary"
import json, sys, os
out, size, frames, cameras = sys.argv[1], sys.argv[2], int(sys.argv[3]), sys.argv[4:]
atrium = []
for c in cameras:
    s = json.load(open(os.path.join(out, f"atrium_{c}.json")))
    atrium.append({"camera": c, "frame_ms": s["frame_ms"], "passes": s["passes"],
                   "triangles_drawn": s.get("gbuffer_draw", {}).get("triangles_drawn")})
suites = {}
for name in ("deliot2023-table1", "kemppinen2025-table3", "kk24-area-lights", "kk25-environment"):
    suites[name] = json.load(open(os.path.join(out, name + ".json")))
first = json.load(open(os.path.join(out, f"atrium_{cameras[0]}.json")))
meta = {"gl_renderer": first["gl_renderer"], "gl_version": first["gl_version"],
        "gpu_timers_meaningful": first["gpu_timers_meaningful"], "size": size, "frames": frames,
        "smoke": os.environ.get("GPU_BENCH_SMOKE") == "1"}
json.dump({"schema": "glimmer-gpu-bench/1", "meta": meta, "atrium_walkthrough": atrium,
           "suites": {k: v.get("derived", {}) for k, v in suites.items()}},
          open(os.path.join(out, "gpu_bench.json"), "w"), indent=1)
names = [p["name"] for p in atrium[0]["passes"]]
md = [f"# gpu_bench: {meta['gl_renderer']} ({meta['gl_version']}), {size}, {frames} frames",
      "", "GL timer queries are " + ("meaningful here." if meta["gpu_timers_meaningful"] else
      "NOT meaningful on this renderer (software: they time the submit); read the wall clock."), "",
      "## Atrium along the walkthrough path (deliot2023), ms of the last frame", "",
      "| camera | frame (wall) | " + " | ".join(f"{n} GPU / wall" for n in names) + " | triangles drawn |",
      "|---|---|" + "---|" * len(names) + "---|"]
for a in atrium:
    cells = [f"{p['gpu_timer_ms']:.2f} / {p['wall_ms']:.2f}" for p in a["passes"]]
    md.append(f"| {a['camera']} | {a['frame_ms']:.2f} | " + " | ".join(cells) + f" | {a['triangles_drawn']} |")
for name in suites:
    md += ["", f"## Suite {name}", "", open(os.path.join(out, name + ".md")).read()]
open(os.path.join(out, "gpu_bench.md"), "w").write("\n".join(md) + "\n")
PY
step "done in $(( $(date +%s) - start )) s: $out/gpu_bench.json, $out/gpu_bench.md"
