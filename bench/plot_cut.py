#!/usr/bin/env python3
"""Plots `vgeo bench cut` records: traversal time against instances per mode (log-log), and visible
clusters against instances per camera (the cost following the screen, not the scene).

Usage: python3 bench/plot_cut.py RESULTS.json [OUT_PREFIX]   (writes OUT_PREFIX-time.png, -clusters.png)
Needs python3-matplotlib (Debian).
"""
import collections
import json
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main():
    path = sys.argv[1]
    prefix = sys.argv[2] if len(sys.argv) > 2 else path.rsplit(".", 1)[0]
    records = json.load(open(path))
    device = next((r["device"] for r in records if r["mode"] != "cpu"), "?")
    styles = {"grid": "-", "scatter": "--"}

    fig, axes = plt.subplots(1, 2, figsize=(12, 4.5), sharey=True)
    for ax, tau in zip(axes, sorted({r["tau"] for r in records})[:2]):
        series = collections.defaultdict(list)
        for r in records:
            if r["tau"] == tau and r["camera"] == "corner":
                series[(r["mode"], r["layout"])].append((r["instances"], max(r["traversal_ms"], 1e-4)))
        for (mode, layout), points in sorted(series.items()):
            points.sort()
            ax.plot([p[0] for p in points], [p[1] for p in points], styles.get(layout, "-"), marker="o", label=f"{mode} ({layout})")
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_xlabel("instances")
        ax.set_title(f"tau = {tau:g}: selection time, camera over the corner")
        ax.grid(True, which="both", alpha=0.3)
    axes[0].set_ylabel("traversal ms (median)")
    axes[1].legend(fontsize=8)
    fig.suptitle(device)
    fig.tight_layout()
    fig.savefig(prefix + "-time.png", dpi=110)

    fig, ax = plt.subplots(figsize=(7, 4.5))
    series = collections.defaultdict(list)
    for r in records:
        if r["tau"] == 1 and r["mode"] in ("levels", "persistent") and r["layout"] == "grid":
            series[r["camera"]].append((r["instances"], max(r.get("visible_clusters", 0), 0.5)))
    for camera, points in sorted(series.items()):
        points = sorted(set(points))
        ax.plot([p[0] for p in points], [p[1] for p in points], marker="o", label=camera)
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("instances (grid)")
    ax.set_ylabel("clusters drawn (tau = 1)")
    ax.set_title("Visible clusters follow the screen, not the scene")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    fig.suptitle(device)
    fig.tight_layout()
    fig.savefig(prefix + "-clusters.png", dpi=110)


if __name__ == "__main__":
    main()
