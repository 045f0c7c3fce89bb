#!/usr/bin/env python3
"""Medians of a runs.jsonl written by the bench/results run scripts: one line per (mesh, --subdiv,
threads, binary) with vgeo's whole run and DAG seconds, their ratio, the peak and the stages of the
cage path and the layout; peers' lines list their build milliseconds. Usage: summarize_runs.py RUNS."""
import collections
import json
import statistics as st
import sys

STAGES = [('load', 'load'), ('repair', 'repair'), ('subdivide', 'subdivide'), ('patches', 'patches'), ('limit', 'limit'), ('patch chord errors', 'chords'),
          ('patch points', 'patch_points'), ('layout', 'layout'), ('leaf clusters', 'leaves'), ('write', 'write')]

rows = [json.loads(line) for line in open(sys.argv[1])]
groups = collections.defaultdict(list)
for r in rows:
    groups[(r['mesh'], r.get('subdiv', 0), r['threads'], r['bin'])].append(r.get('stats') or r['peer'])
for key in sorted(groups):
    runs = groups[key]
    mesh, subdiv, threads, binary = key
    if 'total_seconds' not in runs[0]:
        ms = [x['build_ms'] for x in runs]
        print(f'{mesh:4} t{threads:<2} {binary:12} build ms {[round(m) for m in ms]} median {st.median(ms):.0f} '
              f'peak MB {max(x["peak_rss_mb"] for x in runs):.0f}')
        continue
    total = st.median(x['total_seconds'] for x in runs)
    dag = st.median(x['build_seconds'] for x in runs)
    stages = ' '.join(f'{short}={st.median(x["stage_seconds"].get(name, 0) for x in runs):.3f}' for name, short in STAGES)
    peak = max(x['peak_rss_bytes'] for x in runs) >> 20
    print(f'{mesh:4} s{subdiv} t{threads:<2} {binary:12} total {total:.3f} dag {dag:.3f} whole/dag {total / dag:.2f} '
          f'peak MB {peak:4} | {stages} | runs {len(runs)}')
