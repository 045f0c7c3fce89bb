#!/bin/bash
# armadillo Loop x5 and CGAL's bear Loop x6 built on the project's 2-core machine with 2 threads under
# /usr/bin/time -v. Usage: run.sh PEERS_BIN CGAL_MESHES VGEO (the peer builders' prep and bin2obj,
# CGAL's demo meshes, the vgeo binary); run in an empty folder with 10 GB of disk free.
P=$1; M=$2; V=$3
[ -f a5.obj ] || { $P/prep $M/armadillo.off a5.bin 5 loop && $P/bin2obj a5.bin a5.obj && rm a5.bin; }
rm -f a5.vgeo; /usr/bin/time -v $V build a5.obj -o a5.vgeo --threads 2 -q --stats a5.json > a5.out 2> a5.time
[ -f bear6.obj ] || { $P/prep $M/bear.off bear6.bin 6 loop && $P/bin2obj bear6.bin bear6.obj && rm bear6.bin; }
rm -f bear6.vgeo; /usr/bin/time -v $V build bear6.obj -o bear6.vgeo --threads 2 -q --stats bear6.json > bear6.out 2> bear6.time
$V check bear6.vgeo --cuts 4 > check.log 2>&1
