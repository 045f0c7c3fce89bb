# device_build_runs.sh: sourced by a results folder's run.sh, from the repository root on a device host
# with the binaries, their libraries, the peers and the inputs under .dev/. Writes the host to
# $OUT/host.txt (once: a second script sourcing it keeps the first's); run() builds once with --stats,
# appends a record to $OUT/runs.jsonl and compares the output with the first build of the same mesh
# and level (a DIFF line in host.txt when they differ); prepLoops makes the inputs, peer() runs a peer
# builder.
D=$(pwd)/.dev; W=/tmp/w; mkdir -p $W; export LD_LIBRARY_PATH=$D/lib
[ -f $OUT/host.txt ] || { nproc; lscpu | grep -E "Model name|Thread|Core|Socket|L2|L3"; uname -r; date -u; } > $OUT/host.txt 2>&1
run() { # bin input subdiv threads round tag
  rm -f $W/o.vgeo $W/s.json; sync
  $D/$1 build $2 -o $W/o.vgeo --subdiv $3 --threads $4 --stats $W/s.json > /dev/null 2>$W/err || { echo "FAIL $*"; cat $W/err; }
  echo "{\"bin\":\"$1\",\"mesh\":\"$6\",\"subdiv\":$3,\"threads\":$4,\"round\":$5,\"stats\":$(tr -d '\n' < $W/s.json)}" >> $OUT/runs.jsonl
  cmp -s $W/o.vgeo $W/ref_$6_$3.vgeo 2>/dev/null || { [ -f $W/ref_$6_$3.vgeo ] && echo "DIFF $*" >> $OUT/host.txt || cp $W/o.vgeo $W/ref_$6_$3.vgeo; }
}
# armadillo Loop x$l as $W/a$l.bin (for the peers) and $W/a$l.obj (for vgeo), for each level given.
prepLoops() { for l in "$@"; do $D/peers/prep $D/data/armadillo.off $W/a$l.bin $l loop >/dev/null && $D/peers/bin2obj $W/a$l.bin $W/a$l.obj >/dev/null; done; }
peer() { # driver mesh threads round: one build of a peer, its line appended to $OUT/runs.jsonl
  sync; echo "{\"bin\":\"$1\",\"mesh\":\"$2\",\"threads\":$3,\"round\":$4,\"peer\":$($D/peers/$1 $W/$2.bin $3 1 | tail -1)}" >> $OUT/runs.jsonl
}
