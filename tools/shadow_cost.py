#!/usr/bin/env python3
"""Cost of shadows, side by side in one run (docs/shadows.md):

    tools/shadow_cost.py EXE [--today EXE_WITHOUT_SHADOWS] [--repeats N] [--sizes 640x360,1280x720]
                         [--cameras court,arcade] [--method deliot2023] [--frames 4]

For each atrium camera and size, `render --stats --frames F` with shadows off (`--set shadow.enabled=0`), with
shadows on, and (with --today) the given executable of the main branch, alternating case by case, REPEATS times.
Reports the minimum over repeats (the least disturbed run on a shared machine) of: the first frame (every shadow
map rendered, plus the first use of each program), the last frame (cached maps: nothing moved), their process CPU
times, and the first and last frame's pass times. Wall clock around glFinish; GL timer queries are meaningless on
llvmpipe. The load average is printed before and after: numbers from a loaded machine are ratios, not absolutes.
"""
import argparse
import json
import os
import subprocess
import sys
import tempfile


def run(exe, camera, size, method, frames, extra):
    out = os.path.join(tempfile.gettempdir(), "shadow_cost_%d.png" % os.getpid())
    args = [exe, "render", "--scene", "atrium", "--camera", camera, "--size", size, "--method", method,
            "--frames", str(frames), "--stats", "--out", out] + extra
    stats = json.loads(subprocess.run(args, check=True, capture_output=True, text=True).stdout)
    passes = lambda key: {p["name"]: p["wall_ms"] for p in stats.get(key, [])}
    frames_ms = stats.get("frames_ms", [stats["frame_ms"]])
    frames_cpu = stats.get("frames_cpu_ms", [stats["frame_cpu_ms"]])
    return {"first": frames_ms[0], "last": frames_ms[-1], "first_cpu": frames_cpu[0], "last_cpu": frames_cpu[-1],
            "first_passes": passes("first_frame_passes"), "last_passes": passes("passes"),
            "shadows": stats.get("shadows", {})}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("exe")
    ap.add_argument("--today")
    ap.add_argument("--repeats", type=int, default=2)
    ap.add_argument("--sizes", default="640x360,1280x720")
    ap.add_argument("--cameras", default="court,arcade")
    ap.add_argument("--method", default="deliot2023")
    ap.add_argument("--frames", type=int, default=4)
    a = ap.parse_args()
    configs = [("off", a.exe, ["--set", "shadow.enabled=0"]), ("on", a.exe, [])]
    if a.today:
        configs.insert(0, ("today", a.today, []))
    cases = [(c, s) for s in a.sizes.split(",") for c in a.cameras.split(",")]
    best = {}
    print("load before: " + open("/proc/loadavg").read().strip(), file=sys.stderr)
    for _ in range(a.repeats):
        for camera, size in cases:
            for name, exe, extra in configs:
                r = run(exe, camera, size, a.method, a.frames, extra)
                key = (camera, size, name)
                old = best.get(key)
                best[key] = r if old is None else {
                    k: (min(old[k], r[k]) if isinstance(r[k], float) else
                        ({p: min(old[k].get(p, 1e30), v) for p, v in r[k].items()} if k.endswith("passes") else r[k]))
                    for k in r}
                print(camera, size, name, round(r["first"]), round(r["last"]), file=sys.stderr)
    print("load after: " + open("/proc/loadavg").read().strip(), file=sys.stderr)

    print("| camera | size | config | first frame ms | cached frame ms | first / cached CPU ms | "
          "shadow passes, first frame ms | shadow passes, cached frame ms | lighting ms (cached) |")
    print("|---|---|---|---|---|---|---|---|---|")
    for camera, size in cases:
        for name, _, _ in configs:
            r = best[(camera, size, name)]
            shadow = lambda passes: sum(v for p, v in passes.items() if p.startswith("shadow_"))
            print("| %s | %s | %s | %.0f | %.0f | %.0f / %.0f | %s | %s | %.0f |" % (
                camera, size, name, r["first"], r["last"], r["first_cpu"], r["last_cpu"],
                "%.0f" % shadow(r["first_passes"]) if name == "on" else "-",
                "%.1f" % shadow(r["last_passes"]) if name == "on" else "-",
                r["last_passes"].get("lighting", float("nan"))))
    print()
    print("| camera | size | cached frame on / off | cached frame on / today | first frame on / off |")
    print("|---|---|---|---|---|")
    for camera, size in cases:
        on, off = best[(camera, size, "on")], best[(camera, size, "off")]
        today = best.get((camera, size, "today"))
        print("| %s | %s | %.2fx | %s | %.2fx |" % (camera, size, on["last"] / off["last"],
              "%.2fx" % (on["last"] / today["last"]) if today else "-", on["first"] / off["first"]))


if __name__ == "__main__":
    main()
