#!/usr/bin/env python3
"""Start-up and split-screen times of `glimmer view` under xvfb (issue 39; docs/window.md, "The first minute").

For each binary given (e.g. main's build and this one, to compare side by side), runs in turn, interleaved:
  cold: fresh, empty cache folders (GLIMMER_CACHE_DIR and Mesa's MESA_SHADER_CACHE_DIR), then
  warm: the same folders again, then
  glimmer-cold: Glimmer's cache emptied, Mesa's shader cache kept (a new scene or environment, or a cleared
  Glimmer cache, on a machine that ran this build before),
each with an input script that prints once the first picture is on screen, presses B (the split screen) at 0.5 s
and quits at 12 s (after the refinements a cold start runs after its first picture, so that the warm runs
find everything cached). Reports, per run: the time from the process's start (just before exec) to the first line of the
window's log, to the loading frame (the binary's own log, where it has one) and to the first picture, and the
longest frame after it from `--stats` (warm: B's freeze, the split screen's first frame; cold or glimmer-cold:
the refinements after the first picture, the environment's prefilter or the probes' capture, are longer). Start with the load you report: `uptime`.

    tools/startup_times.py [--scene atrium] [--size 1280x720] [--repeat 1] BINARY [BINARY ...]
"""
import argparse
import json
import os
import re
import subprocess
import sys
import tempfile
import time

SCRIPT = "0 print\n0.5 press b\n11.5 print\n12.0 quit\n"


def run(binary, cache, scene, size, workdir):
    script = os.path.join(workdir, "script.txt")
    with open(script, "w") as f:
        f.write(SCRIPT)
    env = dict(os.environ, GLIMMER_CACHE_DIR=cache, MESA_SHADER_CACHE_DIR=os.path.join(cache, "mesa"))
    inner = (f"date +%s.%N; exec stdbuf -oL {binary} view --scene {scene} --size {size} --no-vsync "
             f"--input-script {script} --stats")
    proc = subprocess.Popen(["xvfb-run", "-a", "-s", f"-screen 0 {size}x24", "sh", "-c", inner], env=env,
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True, bufsize=1, cwd=workdir)
    start, lines = None, []
    for line in proc.stdout:
        now = time.time()
        if start is None:
            try:
                start = float(line.strip())
                continue
            except ValueError:
                start = now
        lines.append((now - start, line.rstrip("\n")))
    proc.wait()
    result = {"exit": proc.returncode}
    glimmer_lines = [(t, l) for t, l in lines if l.startswith("glimmer:")]
    if glimmer_lines:
        result["first_log_s"] = round(glimmer_lines[0][0], 2)
    prints = [(t, l) for t, l in lines if l.startswith("time ")]
    if prints:
        result["first_picture_s"] = round(prints[0][0], 2)
    for t, l in lines:
        m = re.search(r"view: loading frame at ([\d.]+) s after process start \(([\d.]+) s after the window opened", l)
        if m:
            result["loading_frame_s"] = float(m.group(1))
            result["loading_frame_after_window_s"] = float(m.group(2))
        m = re.search(r"view: first picture at ([\d.]+) s after process start \(([\d.]+) s after the window", l)
        if m:
            result["first_picture_own_log_s"] = float(m.group(1))
            result["first_picture_after_window_s"] = float(m.group(2))
        if l.startswith("{") and "frame_times_ms" in l:
            stats = json.loads(l)
            times = stats["frame_times_ms"]
            if times:
                result["longest_frame_ms"] = round(max(times), 1)
                result["median_frame_ms"] = round(sorted(times)[len(times) // 2], 1)
    result["log_tail"] = [l for _, l in lines if "loading" in l or "cache" in l or "captured" in l][-12:]
    return result


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("binaries", nargs="+")
    parser.add_argument("--scene", default="atrium")
    parser.add_argument("--size", default="1280x720")
    parser.add_argument("--repeat", type=int, default=1)
    args = parser.parse_args()
    print("load:", os.getloadavg())
    with tempfile.TemporaryDirectory(prefix="glimmer-startup-") as work:
        for r in range(args.repeat):
            caches = {b: tempfile.mkdtemp(dir=work) for b in args.binaries}
            for kind in ("cold", "warm", "glimmer-cold"):
                for binary in args.binaries:
                    if kind == "glimmer-cold":   # Glimmer's cache emptied, Mesa's shader cache kept
                        for entry in os.listdir(caches[binary]):
                            if entry != "mesa":
                                os.remove(os.path.join(caches[binary], entry))
                    result = run(os.path.abspath(binary), caches[binary], args.scene, args.size, work)
                    print(json.dumps({"binary": binary, "run": kind, "repeat": r, **result}), flush=True)
    print("load:", os.getloadavg())


if __name__ == "__main__":
    sys.exit(main())
