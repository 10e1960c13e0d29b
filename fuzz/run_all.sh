#!/usr/bin/env bash
# Runs every fuzz target in turn for SECONDS_PER_TARGET seconds (default 300) on one core,
# with hangs (> 5 s) and memory over 2 GB counted as findings. Logs go to fuzz/logs/.
#   bash fuzz/run_all.sh [seconds] [target ...]
set -uo pipefail
cd "$(dirname "$0")"
secs="${1:-300}"
shift || true
targets=("$@")
[ ${#targets[@]} -eq 0 ] && targets=(msh22 msh41 vtk triangle obj off read_bytes)
export RUSTC_BOOTSTRAP=1
cargo +stable fuzz build -O -a -s none || exit 1
mkdir -p logs
for t in "${targets[@]}"; do
  mkdir -p "corpus/$t"
  start=$SECONDS
  cargo +stable fuzz run -O -a -s none "$t" "corpus/$t" "seeds/$t" -- \
    -jobs=1 -workers=1 -rss_limit_mb=2048 -timeout=5 -max_len=8192 -max_total_time="$secs" -print_final_stats=1 \
    > "logs/$t.log" 2>&1
  # With -jobs, libFuzzer writes the run's own output to fuzz-0.log.
  [ -f fuzz-0.log ] && cat fuzz-0.log >> "logs/$t.log" && rm -f fuzz-0.log
  runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "logs/$t.log" | tail -1 | grep -o '[0-9]*$')
  echo "$t: ${runs:-?} executions in $((SECONDS - start)) s; $(ls "artifacts/$t" 2>/dev/null | wc -l) artifact(s)"
done
