#!/usr/bin/env python3
"""Builder benchmark: DAG build throughput, peak memory and DAG quality on closed meshes of 1-5 M
triangles (CGAL's armadillo and bunny00 after --subdiv 2), with 1 and 2 threads, plus the shipped cage.

Each configuration runs `vgeo build --stats` REPEAT times in a fresh process; the median build_seconds
is reported (2-core machines are noisy: compare ratios within one run). Writes
bench/results/build-<date>.json and prints a Markdown table.

Usage: python3 bench/build_bench.py [--repeat N] [--vgeo build/vgeo]
"""
import argparse
import datetime
import json
import os
import platform
import statistics
import subprocess
import tarfile
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))


def cgal_mesh(name, workdir):
    path = os.path.join(workdir, "data", "meshes", name)
    if not os.path.exists(path):
        with tarfile.open("/usr/share/doc/libcgal-dev/data.tar.gz") as tar:
            tar.extract("data/meshes/" + name, workdir)
    return path


def cpu_name():
    with open("/proc/cpuinfo") as f:
        for line in f:
            if line.startswith("model name"):
                return line.split(":", 1)[1].strip()
    return platform.processor()


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--repeat", type=int, default=3)
    parser.add_argument("--vgeo", default=os.path.join(ROOT, "build", "vgeo"))
    args = parser.parse_args()
    work = tempfile.mkdtemp(prefix="vgeo_bench_")
    cases = [
        ("armadillo.off", cgal_mesh("armadillo.off", work), 2),
        ("bunny00.off", cgal_mesh("bunny00.off", work), 2),
        ("horned_cube.obj", os.path.join(ROOT, "assets", "horned_cube.obj"), 5),
    ]
    records = []
    for name, path, subdiv in cases:
        for threads in (1, 2):
            runs = []
            for _ in range(args.repeat):
                stats = os.path.join(work, "stats.json")
                subprocess.run([args.vgeo, "build", path, "--subdiv", str(subdiv), "--threads", str(threads), "-q",
                                "-o", os.path.join(work, "out.vgeo"), "--stats", stats], check=True, stdout=subprocess.DEVNULL)
                with open(stats) as f:
                    runs.append(json.load(f))
            best = sorted(runs, key=lambda r: r["build_seconds"])[len(runs) // 2]
            t = best["level_triangles"]
            records.append({
                "mesh": name, "subdiv": subdiv, "threads": threads,
                "leaf_triangles": best["leaf_triangles"],
                "build_seconds_median": statistics.median(r["build_seconds"] for r in runs),
                "build_seconds_all": [r["build_seconds"] for r in runs],
                "mtri_per_second": best["leaf_triangles"] / 1e6 / statistics.median(r["build_seconds"] for r in runs),
                "total_seconds": best["total_seconds"],
                "peak_rss_bytes": max(r["peak_rss_bytes"] for r in runs),
                "bytes_per_triangle": max(r["peak_rss_bytes"] for r in runs) / best["leaf_triangles"],
                "levels": best["levels"], "root_clusters": best["root_clusters"],
                "avg_leaf_cluster_triangles": best["avg_leaf_cluster_triangles"],
                "avg_cluster_triangles": best["avg_cluster_triangles"],
                "max_level_ratio": max(t[i + 1] / t[i] for i in range(len(t) - 1)) if len(t) > 1 else 0,
                "relaxed_groups": best["relaxed_groups"], "stuck_groups": best["stuck_groups"],
            })
    commit = subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"], capture_output=True, text=True).stdout.strip()
    result = {"date": datetime.date.today().isoformat(), "cpu": cpu_name(), "cores": os.cpu_count(), "commit": commit,
              "repeat": args.repeat, "records": records}
    out = os.path.join(ROOT, "bench", "results", "build-%s.json" % result["date"])
    with open(out, "w") as f:
        json.dump(result, f, indent=2)
    print("%s, %d cores, commit %s, %s; median of %d runs\n" % (result["cpu"], result["cores"], commit, result["date"], args.repeat))
    print("| mesh | subdiv | threads | leaf tris | DAG s | M tri/s | peak B/tri | levels | roots | leaf tri/cluster | worst level ratio |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for r in records:
        print("| %s | %d | %d | %d | %.2f | %.2f | %.0f | %d | %d | %.1f | %.3f |" % (
            r["mesh"], r["subdiv"], r["threads"], r["leaf_triangles"], r["build_seconds_median"], r["mtri_per_second"],
            r["bytes_per_triangle"], r["levels"], r["root_clusters"], r["avg_leaf_cluster_triangles"], r["max_level_ratio"]))
    print("\nwritten to", os.path.relpath(out, ROOT))


if __name__ == "__main__":
    main()
