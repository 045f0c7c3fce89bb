#!/usr/bin/env python3
"""Per round and median ratios of the goals run (runs.jsonl): vgeo on one thread against clusterlod,
on 16 against nv_cluster_lod_builder, one thread against 16, whole / DAG. Usage: summarize.py runs.jsonl"""
import json,statistics as st,collections,sys
rows=[json.loads(l) for l in open(sys.argv[1])]
d=collections.defaultdict(lambda: collections.defaultdict(dict))
for r in rows:
    if 'peer' in r: d[r['mesh']][r['round']][r['bin']]=r['peer']['build_ms']/1e3
    else: d[r['mesh']][r['round']][f"vgeo{r['threads']}"]=r['stats']['build_seconds']; d[r['mesh']][r['round']][f"whole{r['threads']}"]=r['stats']['total_seconds']/r['stats']['build_seconds']
for m in d:
    R=d[m]; med=lambda k: st.median([R[r][k] for r in R])
    print(m, 'rounds',len(R))
    for r in sorted(R): x=R[r]; print('  round',r,'clod %.3f vgeo1 %.3f vgeo16 %.3f nv %.3f  | 1t/clod %.2f 16t/nv %.2f 1->16 %.1f' % (x['clod_driver'],x['vgeo1'],x['vgeo16'],x['nvlod_driver'],x['vgeo1']/x['clod_driver'],x['vgeo16']/x['nvlod_driver'],x['vgeo1']/x['vgeo16']))
    print('  medians: clod %.3f vgeo1 %.3f vgeo16 %.3f nv %.3f | 1t/clod %.2f 16t/nv %.2f 1->16 %.1f whole/dag16 %.2f whole/dag1 %.2f' % (med('clod_driver'),med('vgeo1'),med('vgeo16'),med('nvlod_driver'),med('vgeo1')/med('clod_driver'),med('vgeo16')/med('nvlod_driver'),med('vgeo1')/med('vgeo16'),med('whole16'),med('whole1')))
    print('  by round medians: 1t/clod %.2f 1->16 %.1f' % (st.median([R[r]['vgeo1']/R[r]['clod_driver'] for r in R]), st.median([R[r]['vgeo1']/R[r]['vgeo16'] for r in R])))
