import json,sys,statistics as st,collections
rows=[json.loads(l) for l in open(sys.argv[1])]
g=collections.defaultdict(list)
for r in rows: g[(r['mesh'],r['threads'],r['bin'],r['thp'])].append(r['stats'])
for k in sorted(g):
    L=g[k]; med=lambda f: st.median(f(s) for s in L)
    ss=lambda n: med(lambda s: s['stage_seconds'].get(n,0))
    print(k, 'n=%d dag %.4f tot %.4f ratio %.3f load %.4f rep %.4f leaf %.4f simp %.4f peakB/t %.0f'%(len(L),med(lambda s:s['build_seconds']),med(lambda s:s['total_seconds']),med(lambda s:s['total_seconds']/s['build_seconds']),ss('load'),ss('repair'),ss('leaf clusters'),ss('simplify and split'),med(lambda s:s.get('peak_rss_bytes',0)/s['leaf_triangles'] if 'leaf_triangles' in s else 0)))
