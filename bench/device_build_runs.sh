# device_build_runs.sh: sourced by a results folder's run.sh, from the repository root on a device host
# with the binaries, their libraries, the peers and the inputs under .dev/. Writes the host to
# $OUT/host.txt; run() builds once with --stats, appends a record to $OUT/runs.jsonl and compares the
# output with the first build of the same mesh and level (a DIFF line in host.txt when they differ).
D=$(pwd)/.dev; W=/tmp/w; mkdir -p $W; export LD_LIBRARY_PATH=$D/lib
{ nproc; lscpu | grep -E "Model name|Thread|Core|Socket|L2|L3"; uname -r; date -u; } > $OUT/host.txt 2>&1
run() { # bin input subdiv threads round tag
  rm -f $W/o.vgeo $W/s.json; sync
  $D/$1 build $2 -o $W/o.vgeo --subdiv $3 --threads $4 --stats $W/s.json > /dev/null 2>$W/err || { echo "FAIL $*"; cat $W/err; }
  echo "{\"bin\":\"$1\",\"mesh\":\"$6\",\"subdiv\":$3,\"threads\":$4,\"round\":$5,\"stats\":$(tr -d '\n' < $W/s.json)}" >> $OUT/runs.jsonl
  cmp -s $W/o.vgeo $W/ref_$6_$3.vgeo 2>/dev/null || { [ -f $W/ref_$6_$3.vgeo ] && echo "DIFF $*" >> $OUT/host.txt || cp $W/o.vgeo $W/ref_$6_$3.vgeo; }
}
