#!/bin/bash
# Randomized check of the parallel Delaunay insertion, run by hand (not a test: it runs for minutes):
# generated samples of random shape and size (33k to 131k points, so that the insertion is split), each
# tetrahedralized on one thread and on 2, 3 and 8; the tetrahedra files must be byte for byte the same
# (dbrg_tetrahedralize lists them in a canonical order). Inputs that fail or differ are kept.
#
#     bash tests/bench/stress_threads.sh [build/src/cli/dbrg] [SECONDS]
set -u
dbrg=$(realpath "${1:-build/src/cli/dbrg}")
end=$(( $(date +%s) + ${2:-600} ))
work=$(mktemp -d)
shapes=(torus bumpy_sphere saddle sphere double_torus cube thin_plate capped_cylinder graded_sphere hemisphere)
runs=0 bad=0
while [ "$(date +%s)" -lt "$end" ]; do
    shape=${shapes[$((RANDOM % ${#shapes[@]}))]}
    points=$((33000 + RANDOM * 3))
    "$dbrg" reconstruct --demo --demo-shape "$shape" --demo-points "$points" -o "$work/in.ply" --quiet --threads 1
    "$dbrg" delaunay "$work/in.ply" --threads 1 --tets "$work/one.txt" --stats-json /dev/null
    for threads in 2 3 8; do
        if ! "$dbrg" delaunay "$work/in.ply" --threads "$threads" --tets "$work/many.txt" --stats-json /dev/null ||
            ! cmp -s "$work/one.txt" "$work/many.txt"; then
            bad=$((bad + 1))
            cp "$work/in.ply" "stress-$shape-$points-threads$threads.ply"
            echo "DIFFERENT: $shape, $points points, $threads threads (input kept as stress-$shape-$points-threads$threads.ply)"
        fi
    done
    runs=$((runs + 1))
done
rm -rf "$work"
echo "$runs inputs, $bad differing"
[ "$bad" -eq 0 ]
