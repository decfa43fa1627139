#!/usr/bin/env bash
# spacetree-dem main job: set up + build (scripts/build.sh), then run the demo deck
# inputs/demo/in.polydisperse_settle (about 23 000 spheres, bidisperse d = 1 mm / 10 mm, settling
# under gravity between walls, 300 steps, lists rebuilt every 10 steps) once with
# `neighbor ... spacetree` and once with stock `neighbor ... bin`, and print them side by side.
#
#   bash scripts/demo.sh            # 1 MPI rank per run
#   NP=2 bash scripts/demo.sh       # 2 MPI ranks per run
#   SKIP_BUILD=1 bash scripts/demo.sh   # reuse an existing build/liggghts-spacetree
#
# Results: build/demo/summary.txt (+ logs build/demo/log.<style>, data build/demo/polydisperse.data).
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$ROOT"
NP="${NP:-1}"
STEPS="${STEPS:-300}"

if [[ "${SKIP_BUILD:-0}" != "1" ]]; then
  bash scripts/build.sh
fi

EXE="$ROOT/build/liggghts-spacetree"
[[ -x "$EXE" ]] || { echo "demo: $EXE not found (build failed?)" >&2; exit 1; }
PY=/usr/bin/python3
[[ -x "$PY" ]] || PY="$(command -v python3)"
TIME=/usr/bin/time
[[ -x "$TIME" ]] || { echo "demo: /usr/bin/time is missing (apt-get install time)" >&2; exit 1; }

OUT="$ROOT/build/demo"
mkdir -p "$OUT"
DATA="$OUT/polydisperse.data"

echo "== demo: generating the pack"
"$PY" scripts/gen_pack.py bidisperse --d 1e-3 --R 10 --n 30 --K 8 --boundary f --vel 0.1 \
      --seed 4242 --out "$DATA"

# screen output goes line-buffered to build/demo/screen.<style>: an error raised on one rank
# (e.g. a neighbour-list overflow) is printed only there before MPI_Abort
launch=("$EXE")
command -v stdbuf >/dev/null && launch=(stdbuf -oL -eL "$EXE")
if [[ "$NP" != "1" ]]; then
  MPIRUN="$(command -v mpirun || command -v mpiexec)"
  launch=("$MPIRUN" --allow-run-as-root --oversubscribe -np "$NP" "${launch[@]}")
fi

for style in spacetree bin; do
  echo "== demo: running with 'neighbor 1e-4 $style' on $NP rank(s) ($STEPS steps)"
  start=$(date +%s.%N)
  if ! "$TIME" -v -o "$OUT/time.$style" "${launch[@]}" -in inputs/demo/in.polydisperse_settle \
        -var nstyle "$style" -var data "$DATA" -var nsteps "$STEPS" \
        -log "$OUT/log.$style" -echo none > "$OUT/screen.$style" 2>&1; then
    echo "demo: the $style run failed; see $OUT/screen.$style and $OUT/log.$style:" >&2
    grep -h ERROR "$OUT/screen.$style" "$OUT/log.$style" >&2 || tail -20 "$OUT/screen.$style" >&2 || true
    exit 1
  fi
  end=$(date +%s.%N)
  echo "$start $end" > "$OUT/wall.$style"
done

"$PY" - "$OUT" "$NP" <<'EOF'
import os, re, sys
out, np = sys.argv[1], sys.argv[2]

def grab(style):
    log = open(os.path.join(out, "log." + style)).read()
    tim = open(os.path.join(out, "time." + style)).read()
    t0, t1 = map(float, open(os.path.join(out, "wall." + style)).read().split())
    r = {}
    m = re.search(r"Loop time of (\S+) on \d+ procs for (\d+) steps with (\d+) atoms", log)
    r["atoms"] = int(m.group(3)); r["steps"] = int(m.group(2)); r["loop"] = float(m.group(1))
    r["neigh"] = float(re.search(r"Neigh time \(%\) = (\S+)", log).group(1))
    r["pair"] = float(re.search(r"Pair  time \(%\) = (\S+)", log).group(1))
    r["nb"] = int(float(re.search(r"Total # of neighbors = (\S+)", log).group(1)))
    r["builds"] = int(re.search(r"Neighbor list builds = (\d+)", log).group(1))
    r["rss"] = int(re.search(r"Maximum resident set size \(kbytes\): (\d+)", tim).group(1)) / 1024.0
    r["wall"] = t1 - t0
    r["ms"] = 1e3 * r["neigh"] / r["builds"] if r["builds"] else float("nan")
    # last thermo line (step atoms ke rke)
    lines = log.splitlines()
    i = max(k for k, l in enumerate(lines) if l.startswith("Loop time"))
    r["last"] = lines[i - 1].split()
    return r

s, b = grab("spacetree"), grab("bin")
rows = [
    ("atoms", "%d" % s["atoms"], "%d" % b["atoms"], ""),
    ("steps", "%d" % s["steps"], "%d" % b["steps"], ""),
    ("total # of neighbours", "%d" % s["nb"], "%d" % b["nb"], "equal" if s["nb"] == b["nb"] else "DIFFER"),
    ("neighbour list builds", "%d" % s["builds"], "%d" % b["builds"], ""),
    ("ms per rebuild", "%.2f" % s["ms"], "%.2f" % b["ms"], "%.1fx" % (b["ms"] / s["ms"])),
    ("neighbour time (s)", "%.3f" % s["neigh"], "%.3f" % b["neigh"], "%.1fx" % (b["neigh"] / s["neigh"])),
    ("pair time (s)", "%.3f" % s["pair"], "%.3f" % b["pair"], ""),
    ("loop time (s)", "%.2f" % s["loop"], "%.2f" % b["loop"], "%.1fx" % (b["loop"] / s["loop"])),
    ("total wall time (s)", "%.2f" % s["wall"], "%.2f" % b["wall"], "%.1fx" % (b["wall"] / s["wall"])),
    ("peak memory (MB%s)" % ("" if np == "1" else ", largest rank"), "%.1f" % s["rss"], "%.1f" % b["rss"], ""),
    ("final kinetic energy", s["last"][2], b["last"][2], ""),
]
w0 = max(len(r[0]) for r in rows)
txt = ["spacetree-dem demo: inputs/demo/in.polydisperse_settle, %s MPI rank(s)" % np,
       "bidisperse pack (d = 1 mm lattice + 8 spheres of d = 10 mm), gravity, walls, hertz + tangential history,",
       "neigh_modify every 10 check no; the runs differ only in the neighbor line.", "",
       "%-*s  %14s  %14s  %s" % (w0, "", "spacetree", "bin", "speed-up (bin/spacetree)"),
       "%-*s  %14s  %14s  %s" % (w0, "-" * w0, "-" * 14, "-" * 14, "-" * 24)]
for r in rows:
    txt.append("%-*s  %14s  %14s  %s" % (w0, r[0], r[1], r[2], r[3]))
txt.append("")
txt.append("logs: %s/log.spacetree, %s/log.bin" % (out, out))
open(os.path.join(out, "summary.txt"), "w").write("\n".join(txt) + "\n")
print("\n".join(txt))
EOF
echo "(written to build/demo/summary.txt)"
