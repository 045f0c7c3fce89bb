#!/bin/bash
# glibc's malloc arenas at 16 threads: vgeo_new with glibc.malloc.arena_max 1, 2, 4 and 8 against the
# default (8 a core), armadillo Loop x2 (four rounds), x3 and the cage at --subdiv 2 (three), the
# settings' order turning by round; output bytes compared. Setup as run.sh.
set -u
. bench/device_build_runs.sh  # D, W, host.txt and run()
A=$D/data/armadillo.off
for l in 2 3; do $D/peers/prep $A $W/a$l.bin $l loop >/dev/null && $D/peers/bin2obj $W/a$l.bin $W/a$l.obj >/dev/null; done
for a in 1 2 4 8 0; do
  if [ $a = 0 ]; then ln -sf vgeo_new $D/vgeo_arenas_default; else printf '#!/bin/sh\nGLIBC_TUNABLES=glibc.malloc.hugetlb=1:glibc.malloc.arena_max=%s exec %s "$@"\n' $a $D/vgeo_new > $D/vgeo_arenas_$a; chmod +x $D/vgeo_arenas_$a; fi
done
for r in 1 2 3 4; do
  set -- 1 2 4 8 default; shift $((r % 5)); list="$* 1 2 4 8 default"; list=$(echo $list | cut -d' ' -f1-5)
  for a in $list; do
    run vgeo_arenas_$a $W/a2.obj 0 16 $r a2
    [ $r -le 3 ] && run vgeo_arenas_$a $W/a3.obj 0 16 $r a3 && run vgeo_arenas_$a $A 2 16 $r cage
  done
done
grep -c . $OUT/runs.jsonl; date -u >> $OUT/host.txt
