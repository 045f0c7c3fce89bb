# Counts the switch-outs of `perf script` (sched:sched_switch with stacks) by state and what they waited in.
# Usage: blocked_by_stack.py sw.txt.gz
import gzip,re,collections
ev=[]; cur=None
for line in gzip.open(__import__('sys').argv[1] if len(__import__('sys').argv) > 1 else 'sw.txt.gz','rt'):
    m=re.match(r'\s*(\d+)\s+([\d.]+): sched:sched_switch: prev_comm=(\S+) prev_pid=(\d+) prev_prio=\d+ prev_state=(\S+) ==> ',line)
    if m: cur=dict(t=float(m[2]),tid=int(m[4]),state=m[5],stack=[]); ev.append(cur); continue
    s=line.strip()
    if cur is not None and s:
        p=s.split(None,1)
        if len(p)==2: cur['stack'].append(p[1])
t0=min(e['t'] for e in ev); print(len(ev),'switch-outs over',round((max(e['t'] for e in ev)-t0)*1e3),'ms')
# time to next switch-out of the same thread ~ (off + on) duration: sum per category as an upper bound of off-CPU time
bytid=collections.defaultdict(list)
for e in ev: bytid[e['tid']].append(e)
agg=collections.Counter(); n=collections.Counter(); win=collections.Counter()
def cat(st):
    ks=[f.split('+')[0] for f in st]
    for key in ('rwsem_down_write_slowpath','rwsem_down_read_slowpath','futex_wait','do_sched_yield','folio_wait','io_schedule','__cond_resched','schedule_timeout','do_nanosleep','jbd2','ext4_sync'):
        for f in ks:
            if f.startswith(key): 
                u=[x for x in st if 'vgeo::' in x or 'tbb::' in x]
                return key, (re.sub(r'\(.*','',u[0])[:60] if u else '?')
    return ks[3] if len(ks)>3 else '?', '?'
for e in ev:
    c=cat(e['stack']); n[(e['state'],)+c]+=1; win[(int((e['t']-t0)*100),e['state'],c[0])]+=1
for k,v in n.most_common(22): print(v,k)
print()
for k in sorted(win):
    if k[1]=='D': print('%3d-%3d ms'%(k[0]*10,k[0]*10+10), k[2], win[k])
