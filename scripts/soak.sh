#!/usr/bin/env bash
# The soak: the station's window sculpting for a long time, the demo session
# looped through a sim device at speed, resident memory sampled over time.
# Not part of the test suite (it takes as long as you give it).
#
#   bash scripts/soak.sh [MINUTES] [SPEED] [OUT.csv]
# Defaults: 60 minutes, speed 4, soak-rss.csv. Needs a build (build/bin/sculpt)
# and runs under xvfb-run when there is no display. Besides the resident
# memory, the station's own --stats (rewritten every 30 s) give the heap the
# program holds and what the allocator keeps free, so a growth of RSS can be
# told apart: held memory (a leak) or allocator fragmentation. Prints the
# table and exits 1 when the median memory held in the last quarter is more
# than 10% above the second quarter's (the bounded caches are full by then).
set -euo pipefail
cd "$(dirname "$0")/.."
minutes=${1:-60}
speed=${2:-4}
out=${3:-soak-rss.csv}
seconds=$(( minutes * 60 ))
root=$PWD
# The station autosaves its project into the folder it runs in: a scratch one.
work=$(mktemp -d)
run=("$root/build/bin/sculpt" run --device "sim:$root/sim/sessions/demo.scs" --loop --speed "$speed"
     --hidden --stats "$work/stats.json" --stats-every 30)
if [[ -z "${DISPLAY:-}" ]]; then run=(xvfb-run -a -s "-screen 0 1280x800x24" "${run[@]}"); fi
(cd "$work" && exec "${run[@]}") > soak.log 2>&1 &
launcher=$!
sleep 5
pid=$(pgrep -n -f "build/bin/sculpt run --device sim:$root/sim/sessions/demo.scs --loop" || true)
if [[ -z "$pid" ]]; then echo "soak: the station did not start (soak.log)"; cat soak.log; exit 1; fi
echo "minute,rss_mib,heap_held_mib,heap_free_mib" > "$out"
start=$(date +%s)
while (( $(date +%s) - start < seconds )); do
  if ! kill -0 "$pid" 2>/dev/null; then echo "soak: the station ended early (soak.log)"; exit 1; fi
  rss_kib=$(awk '/^VmRSS/ {print $2}' "/proc/$pid/status")
  elapsed=$(( $(date +%s) - start ))
  heap=$(python3 - "$work/stats.json" <<'PY'
import json, sys
try:
    h = json.load(open(sys.argv[1]))["heap"]
    print("%.1f,%.1f" % (h["in_use_mib"], h["free_mib"]))
except (OSError, ValueError, KeyError):
    print(",")
PY
)
  echo "$(awk -v s="$elapsed" 'BEGIN {printf "%.1f", s / 60}'),$(( rss_kib / 1024 )),$heap" >> "$out"
  sleep 30
done
kill -TERM "$pid"
wait "$launcher" || true
rm -rf "$work"
cat "$out"
python3 - "$out" <<'PY'
import csv, statistics, sys
rows = [(float(m), int(r), float(h)) for m, r, h, _ in list(csv.reader(open(sys.argv[1])))[1:] if h]
last = rows[-1][0]
# Medians over the second quarter (the caches full) and the last quarter:
# one sample can catch a transient, such as the copy of the volume the
# mesher takes when each round of the demo starts a new block.
def median(lo, hi, column):
    return statistics.median(row[column] for row in rows if lo * last <= row[0] <= hi * last)
rss_q, rss_end = median(0.25, 0.5, 1), median(0.75, 1.0, 1)
held_q, held_end = median(0.25, 0.5, 2), median(0.75, 1.0, 2)
print(f"soak: {last:.0f} min; RSS {rows[0][1]} MiB near the start, median {rss_q:.0f} in the second "
      f"quarter and {rss_end:.0f} in the last ({100.0 * (rss_end - rss_q) / rss_q:+.1f}%); heap held "
      f"{held_q:.1f} and {held_end:.1f} MiB ({100.0 * (held_end - held_q) / held_q:+.1f}%)")
sys.exit(1 if held_end > 1.1 * held_q else 0)
PY
