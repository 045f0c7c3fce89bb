#!/usr/bin/env python3
"""Prints the worker profiles of a `vgeo bench cut --profile-workers` JSON, a line a persistent record:
time, span, first item, last item end, tail (device-clock ticks: ns on NVIDIA and lavapipe), median
claim / take / rounds of the iterations with items, items an iteration, polls.
Usage: python3 bench/print_worker_profile.py RESULTS.json"""
import json
import sys

for r in json.load(open(sys.argv[1])):
    if "worker_profile" not in r:
        continue
    p = r["worker_profile"]
    print("%-7s %6d %-8s tau %g  %.3f ms  span %s first %s last %s tail %s  claim %s take %s rounds %s  items/it %.1f polls %s%s" % (
        r["layout"], r["instances"], r["camera"], r["tau"], r["traversal_ms"], p.get("span_ticks"), p.get("first_item_ticks"),
        p.get("last_item_end_ticks"), p.get("tail_ticks"), p.get("claim_ticks_median"), p.get("take_ticks_median"),
        p.get("rounds_ticks_median"), p.get("items_per_iteration", 0.0), p.get("polls"), " TRUNCATED" if p.get("truncated") else ""))
    if "items_taken" in p:
        step = p["timeline_step_ticks"]
        print("   workers started a %d ticks:" % step, p["workers_started"])
        print("   items taken a %d ticks:    " % step, p["items_taken"])
    elif "items_taken_per_1000_ticks" in p:  # the older record form (steps of 1,000 ticks)
        print("   workers started a 1000 ticks:", p["workers_started_per_1000_ticks"])
        print("   items taken a 1000 ticks:    ", p["items_taken_per_1000_ticks"])
