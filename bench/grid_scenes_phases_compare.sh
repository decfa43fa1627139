#!/usr/bin/env bash
# Two builds of bench_grid_scenes_phases side by side on the scenes of bench/grid_scenes.py:
# alternating rounds (the order swapped every round), all rows to a CSV, medians printed.
#   bench/grid_scenes_phases_compare.sh BEFORE_EXE AFTER_EXE OUT.csv [rounds] [steps]
# The scene files come from bench/grid_scenes.py (build/bench_<name>/<scene>.data); set
# SCENES_DIR to their folder (default build/bench_grid_scenes).
set -euo pipefail
before=$1 after=$2 out=$3 rounds=${4:-6} steps=${5:-60}
dir=${SCENES_DIR:-build/bench_grid_scenes}
echo "scene,version,round,grid,atoms,steps,update_ms,build_ms,sweep_ms,refine_for_pairs_ms,total_ms,pairs,comparisons,cells,rehosted" > "$out"
for r in $(seq 1 "$rounds"); do
  if [ $((r % 2)) = 1 ]; then order="before after"; else order="after before"; fi
  for sc in sparse clustered; do
    for ver in $order; do
      if [ "$ver" = before ]; then exe=$before; else exe=$after; fi
      "$exe" "$dir/$sc.data" "$steps" | tail -n +2 | sed "s/^/$sc,$ver,$r,/" >> "$out"
    done
  done
done
/usr/bin/python3 - "$out" <<'PY'
import csv, statistics as st, sys
rows = list(csv.DictReader(open(sys.argv[1])))
print("scene     grid      version update  build  sweep refine  total  comparisons")
for sc in ("sparse", "clustered"):
    for g in ("regular", "adaptive", "reluctant"):
        for v in ("before", "after"):
            rs = [r for r in rows if r["scene"] == sc and r["grid"] == g and r["version"] == v]
            m = lambda k: st.median(float(r[k]) for r in rs)
            print("%-9s %-9s %-7s %6.2f %6.2f %6.2f %6.2f %6.2f %12s" % (sc, g, v, m("update_ms"), m("build_ms"),
                  m("sweep_ms"), m("refine_for_pairs_ms"), m("total_ms"), rs[0]["comparisons"]))
PY
