#!/usr/bin/env bash
# The soak: the station's window sculpting for a long time, the demo session
# looped through a sim device at speed, resident memory sampled over time.
# Not part of the test suite (it takes as long as you give it).
#
#   bash scripts/soak.sh [MINUTES] [SPEED] [OUT.csv]
# Defaults: 60 minutes, speed 4, soak-rss.csv. Needs a build (build/bin/sculpt)
# and runs under xvfb-run when there is no display. Prints the RSS table and
# exits 1 when memory grew by more than 10% between the first quarter's end
# (the bounded caches are full by then) and the end.
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
     --hidden)
if [[ -z "${DISPLAY:-}" ]]; then run=(xvfb-run -a -s "-screen 0 1280x800x24" "${run[@]}"); fi
(cd "$work" && exec "${run[@]}") > soak.log 2>&1 &
launcher=$!
sleep 5
pid=$(pgrep -n -f "build/bin/sculpt run --device sim:$root/sim/sessions/demo.scs --loop" || true)
if [[ -z "$pid" ]]; then echo "soak: the station did not start (soak.log)"; cat soak.log; exit 1; fi
echo "minute,rss_mib" > "$out"
start=$(date +%s)
while (( $(date +%s) - start < seconds )); do
  if ! kill -0 "$pid" 2>/dev/null; then echo "soak: the station ended early (soak.log)"; exit 1; fi
  rss_kib=$(awk '/^VmRSS/ {print $2}' "/proc/$pid/status")
  elapsed=$(( $(date +%s) - start ))
  echo "$(awk -v s="$elapsed" 'BEGIN {printf "%.1f", s / 60}'),$(( rss_kib / 1024 ))" >> "$out"
  sleep 30
done
kill -TERM "$pid"
wait "$launcher" || true
rm -rf "$work"
cat "$out"
python3 - "$out" <<'PY'
import csv, sys
rows = [(float(m), int(r)) for m, r in list(csv.reader(open(sys.argv[1])))[1:]]
quarter = [r for m, r in rows if m >= rows[-1][0] / 4][0]
end = rows[-1][1]
print(f"soak: {rows[-1][0]:.0f} min, RSS {rows[0][1]} MiB at start, {quarter} MiB after a quarter, "
      f"{end} MiB at the end ({100.0 * (end - quarter) / quarter:+.1f}%)")
sys.exit(1 if end > 1.1 * quarter else 0)
PY
