#!/bin/bash
# obj2off.sh IN.obj OUT.off: the `v` and `f` records of an OBJ as an OFF file, one element a line.
awk 'BEGIN { v = 0; f = 0 } /^v / { v++ } /^f / { f++ } END { print "OFF"; print v, f, 0 }' "$1" > "$2"
awk '/^v / { print $2, $3, $4 }' "$1" >> "$2"
awk '/^f / { n = NF - 1; line = n; for (i = 2; i <= NF; i++) { split($i, c, "/"); line = line " " (c[1] - 1) } print line }' "$1" >> "$2"
