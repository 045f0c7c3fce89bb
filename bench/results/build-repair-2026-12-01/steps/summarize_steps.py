#!/usr/bin/env python3
"""Medians of steps.txt: the step timers of a temporary build ("TT name ms" lines on stderr, each the
time since the timer before), and the --stats stage seconds of each run, per "== mesh tN" block.
Usage: summarize_steps.py steps.txt."""
import sys, re, statistics as st, json, collections
runs=[]; cur=None
for line in open(sys.argv[1]):
    if line.startswith('=='):
        cur={'tag':line[3:].strip(),'tt':collections.OrderedDict(),'stats':None}; runs.append(cur)
    elif line.startswith('TT'):
        m=re.match(r'TT (.*?)\s+([\d.]+) ms',line); k=m.group(1).strip()
        cur['tt'][k]=cur['tt'].get(k,0)+float(m.group(2))
    elif line.startswith('{'):
        cur['stats']=json.loads(line)
tags=list(dict.fromkeys(r['tag'] for r in runs))
for tag in tags:
    rs=[r for r in runs if r['tag']==tag]
    print('###',tag,len(rs))
    for k in rs[0]['tt']:
        v=[r['tt'].get(k,0) for r in rs]; print(f'  {k:28s} {st.median(v):8.2f}')
    for k in rs[0]['stats']['stage_seconds']:
        v=[r['stats']['stage_seconds'].get(k,0)*1000 for r in rs]
        if st.median(v)>0.5: print(f'  [{k:26s}] {st.median(v):8.2f}')
    print('  build',st.median([r['stats']['build_seconds'] for r in rs]),'total',st.median([r['stats']['total_seconds'] for r in rs]))
