#!/usr/bin/env python3
"""regress.py: the headline numbers of one run against a baseline, for bench/gpu_regress.sh and
bench/lavapipe_regress.sh.

  regress.py merge DIR -o FILE.json    the records of DIR's *.json files (`bench cut`, `bench frame`, a
                                       `render --stats`) as one file: {"file name": [records], ...}
  regress.py minimum OUT.json RUN.json...  merged runs of one set, each time the minimum of the runs'
  regress.py compare BASE.json NEW.json [--limit 1.10] [--floor-ms 0.005]

compare matches records by what they measured (file, scene, instances, camera, viewport, tau, traversal,
occlusion, rasterizer, patches) and prints each number of NEW more than `limit` times its baseline (and
more than floor-ms slower: a 2 us difference is noise on any device), then one verdict line. Exit 1 when
something is slower, 2 when a baseline record has no match (the set changed: rebase).
"""
import argparse
import glob
import json
import os
import sys

# The fields that say what a record measured, and the times compared.
KEY_FIELDS = ["input", "layout", "instances", "camera", "width", "height", "tau", "mode", "traversal",
              "occlusion_setting", "raster", "triangle_cull", "patches"]
TIMES = ["traversal_ms", "instance_cull_ms", "frame_ms"]


def records(value):
    return value if isinstance(value, list) else [value]


def key(name, r):
    parts = [name]
    for f in KEY_FIELDS:
        if f in r:
            v = r[f]
            if f == "occlusion_setting" and v == "off":
                continue  # the cut alone: what records from before the setting measured on lavapipe
            if f == "input":
                v = os.path.basename(str(v))
            parts.append(f"{f}={v}")
    return " ".join(parts)


def merge(folder, out):
    merged = {}
    for path in sorted(glob.glob(os.path.join(folder, "*.json"))):
        with open(path) as f:
            merged[os.path.basename(path)] = records(json.load(f))
    with open(out, "w") as f:
        json.dump(merged, f, indent=1)
    print(f"{out}: {sum(len(v) for v in merged.values())} records from {len(merged)} files")


def minimum(out, paths):
    runs = []
    for p in paths:
        with open(p) as f:
            runs.append(json.load(f))
    best = runs[0]
    for run in runs[1:]:
        for name, rs in run.items():
            for a, b in zip(best.get(name, []), rs):  # the same set: the same records in the same order
                for t in TIMES:
                    if t in a and t in b:
                        a[t] = min(a[t], b[t])
    with open(out, "w") as f:
        json.dump(best, f, indent=1)


def index(merged):
    out = {}
    for name, rs in merged.items():
        for r in rs:
            out[key(name, r)] = r
    return out


def compare(base_path, new_path, limit, floor):
    with open(base_path) as f:
        base = index(json.load(f))
    with open(new_path) as f:
        new = index(json.load(f))
    slower, faster, compared, missing = [], 0, 0, []
    for k, b in base.items():
        n = new.get(k)
        if n is None:
            missing.append(k)
            continue
        for t in TIMES:
            if t not in b or t not in n or not b[t] or b[t] <= 0:
                continue
            compared += 1
            ratio = n[t] / b[t]
            if ratio > limit and n[t] - b[t] > floor:
                slower.append(f"SLOWER {ratio:5.2f}x  {t} {b[t]:.4f} -> {n[t]:.4f} ms  {k}")
            elif ratio < 1.0 / limit and b[t] - n[t] > floor:
                faster += 1
    for line in slower:
        print(line)
    for k in missing:
        print(f"MISSING {k}")
    verdict = "REGRESSION" if slower else ("SET CHANGED" if missing else "OK")
    print(f"verdict: {verdict}: {len(slower)} of {compared} numbers more than {limit:.2f}x their baseline, "
          f"{faster} faster by as much, {len(missing)} baseline records unmatched "
          f"({os.path.basename(new_path)} against {os.path.basename(base_path)})")
    return 1 if slower else (2 if missing else 0)


def main():
    p = argparse.ArgumentParser()
    sub = p.add_subparsers(dest="cmd", required=True)
    m = sub.add_parser("merge")
    m.add_argument("folder")
    m.add_argument("-o", "--output", required=True)
    n = sub.add_parser("minimum")
    n.add_argument("output")
    n.add_argument("runs", nargs="+")
    c = sub.add_parser("compare")
    c.add_argument("base")
    c.add_argument("new")
    c.add_argument("--limit", type=float, default=1.10)
    c.add_argument("--floor-ms", type=float, default=0.005)
    a = p.parse_args()
    if a.cmd == "merge":
        merge(a.folder, a.output)
        return 0
    if a.cmd == "minimum":
        minimum(a.output, a.runs)
        return 0
    return compare(a.base, a.new, a.limit, a.floor_ms)


if __name__ == "__main__":
    sys.exit(main())
