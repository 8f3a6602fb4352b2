#!/usr/bin/env python3
"""Plot a `glimmer bench --json` file: frame time per method and scene as grouped bars.

usage: plot_bench.py BENCH.json OUT.png [--title TEXT]

Each bar is the median frame time of one method in one scene (and suite variant); with a density sweep the bar
shows the sweep's median and the whisker its min..max, like Deliot & Belcour's Table 1 ranges. A second panel
shows process CPU time per frame (steadier than wall time on a shared machine with a software renderer).
Needs python3 and matplotlib (Debian: python3-matplotlib).
"""
import argparse
import json
import statistics
import sys

import matplotlib

matplotlib.use("Agg")  # no display needed
import matplotlib.pyplot as plt  # noqa: E402


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("bench_json")
    parser.add_argument("out_png")
    parser.add_argument("--title", default=None)
    args = parser.parse_args()
    try:
        with open(args.bench_json) as f:
            bench = json.load(f)
    except (OSError, ValueError) as e:
        sys.exit(f"plot_bench: {args.bench_json}: {e}")
    if bench.get("schema") != "glimmer-bench/1":
        sys.exit(f"plot_bench: {args.bench_json}: not a glimmer bench JSON (schema {bench.get('schema')!r})")

    methods, groups = [], []
    wall, cpu = {}, {}  # (group, method) -> medians over the sweep
    for r in bench["results"]:
        group = r["scene"] + ("\n" + r["variant"] if r["variant"] else "")
        if r["method"] not in methods:
            methods.append(r["method"])
        if group not in groups:
            groups.append(group)
        wall.setdefault((group, r["method"]), []).append(r["median_ms"])
        if "cpu_median_ms" in r:
            cpu.setdefault((group, r["method"]), []).append(r["cpu_median_ms"])

    panels = [(wall, "wall ms per frame (median, glFinish)")]
    if cpu:
        panels.append((cpu, "process CPU ms per frame (median)"))
    fig, axes = plt.subplots(len(panels), 1, figsize=(max(6.0, 1.4 * len(groups) + 2.0), 3.6 * len(panels)),
                             squeeze=False)
    width = 0.8 / max(1, len(methods))
    for ax, (times, label) in zip(axes[:, 0], panels):
        for m, method in enumerate(methods):
            xs, heights, low, high = [], [], [], []
            for g, group in enumerate(groups):
                values = times.get((group, method))
                if not values:
                    continue
                mid = statistics.median(values)
                xs.append(g + (m - (len(methods) - 1) / 2) * width)
                heights.append(mid)
                low.append(mid - min(values))
                high.append(max(values) - mid)
            ax.bar(xs, heights, width, label=method, yerr=[low, high], capsize=2)
        ax.set_xticks(range(len(groups)))
        ax.set_xticklabels(groups, fontsize=8)
        ax.set_ylabel(label, fontsize=8)
        ax.grid(axis="y", alpha=0.3)
    axes[0, 0].legend(fontsize=8)
    meta = bench.get("meta", {})
    size = meta.get("resolution", ["?", "?"])
    title = args.title or f"glimmer bench {meta.get('suite', '')}, {size[0]}x{size[1]}, {meta.get('gl_renderer', '')}"
    axes[0, 0].set_title(title, fontsize=9)
    fig.tight_layout()
    fig.savefig(args.out_png, dpi=110)


if __name__ == "__main__":
    main()
