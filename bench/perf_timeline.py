#!/usr/bin/env python3
"""Where a many-thread build waits: `perf script -F tid,time,ip,sym,dso --no-demangle` of a
`perf record -e cpu-clock -F HZ` run (gzipped or not), cut into slices of SLICE_MS.

Each line: the slice's start (s), threads sampled ("all"), threads in vgeo's own code rather than
oneTBB's or the kernel's ("work"), the main thread's top symbol and the slice's three top symbols.
"P>" marks the body of a parallel loop, named after the vgeo function that holds the loop. The last
line gives the CPU seconds sampled, the work among them, and the milliseconds in which one thread
alone ran (the serial stretches).

Usage: bench/perf_timeline.py PERF_SCRIPT[.gz] [SLICE_MS=5] [HZ=4000]
"""
import collections
import gzip
import re
import subprocess
import sys

LOOPS = {'parallelFor', 'parallelForRanges', 'parallelForInOrder', 'parallelNumber', 'parallelPrefix',
         'parallelFilled', 'parallelForRuns', 'parallelInvoke', 'withThreads', 'bucketSorted'}


def read(path):
    opener = gzip.open if path.endswith('.gz') else open
    rows = []
    with opener(path, 'rt') as f:
        for line in f:
            m = re.match(r'\s*(\d+)\s+([\d.]+):\s+[0-9a-f]+\s+(\S+)\s+\((.*)\)\s*$', line)
            if m:
                rows.append((int(m[1]), float(m[2]), m[3], m[4]))
    return rows


def namer(rows):
    mangled = sorted({r[2] for r in rows if r[2].startswith('_Z')})
    out = subprocess.run(['c++filt'], input='\n'.join(mangled), capture_output=True, text=True).stdout
    plain = dict(zip(mangled, out.split('\n')))

    def name(sym, dso):
        if 'libtbb' in dso:
            return '[tbb]'
        if 'kallsyms' in dso:
            return '[k]' + sym
        if 'libmetis' in dso:
            return 'metis:' + sym
        d = plain.get(sym, sym)
        loop = 'start_for' in d or 'parallel_invoke' in d or 'function_invoker' in d
        names = re.findall(r'vgeo::(?:\(anonymous namespace\)::)?([A-Za-z_][\w:]*)(?:<[^()]*?>)?\(', d)
        names = [n for n in names if n.split('::')[-1] not in LOOPS]
        if names:
            return ('P>' + names[-1]) if loop else names[0]
        return d[:30]
    return name


def main():
    path = sys.argv[1]
    slice_ms = float(sys.argv[2]) if len(sys.argv) > 2 else 5.0
    hz = float(sys.argv[3]) if len(sys.argv) > 3 else 4000.0
    rows = read(path)
    if not rows:
        sys.exit(f'{path}: no samples')
    name = namer(rows)
    main_thread = min(r[0] for r in rows)
    t0 = min(r[1] for r in rows)
    slices = collections.defaultdict(list)
    for tid, t, sym, dso in rows:
        slices[int((t - t0) * 1000 / slice_ms)].append((tid, name(sym, dso)))
    per_slice = slice_ms / 1000 * hz
    work_total = 0
    alone_ms = 0.0
    for k in range(max(slices) + 1):
        samples = slices.get(k, [])
        work = [s for s in samples if s[1] != '[tbb]' and not s[1].startswith('[k]')]
        work_total += len(work)
        threads = len(samples) / per_slice
        if 0.5 < threads < 1.5:
            alone_ms += slice_ms
        top_main = collections.Counter(s[1] for s in samples if s[0] == main_thread).most_common(1)
        top = collections.Counter(s[1] for s in samples).most_common(3)
        print('%6.3f all %4.1f work %4.1f main %-28s | %s' % (
            k * slice_ms / 1000, threads, len(work) / per_slice, (top_main[0][0] if top_main else '-')[:28],
            ', '.join('%s %d' % (a[:34], b) for a, b in top)))
    print('cpu %.3f s, work %.3f s, one thread alone %.0f ms' % (len(rows) / hz, work_total / hz, alone_ms))


if __name__ == '__main__':
    main()
