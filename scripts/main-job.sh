#!/usr/bin/env bash
# The main job: builds darcydem and runs the paper's 1D upward seepage column
# (examples/seepage_column/) for K_f = 1e7, 1e5 and 1e4 Pa. Each run settles
# the column, imposes the inflow, compares uplift and pore pressure with the
# analytical solution and writes, in out/seepage_column/kf_<K_f>/:
#   uplift.csv, pressure.csv, uplift.png, pressure.png, report.md, ...
# and out/seepage_column/uplift_all.png shows the three runs together (the
# paper's Fig. 3). Exits non-zero if a run misses its tolerances.
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
"$root/scripts/build.sh" "$root/build"
out="$root/out/seepage_column"
mkdir -p "$out"
status=0
run() {
  "$root/build/darcydem" run "$root/examples/seepage_column/kf_$1.toml" --out "$out/kf_$1" --force \
    > "$out/kf_$1.log" 2>&1 || return 1
}
# Two at a time (the machine has 2 cores; each run is single-threaded work).
run 1e7 & pid=$!
run 1e5 || status=1
run 1e4 || status=1
wait "$pid" || status=1
for k in 1e7 1e5 1e4; do
  grep -h "seepage column" "$out/kf_$k.log" | sed "s/^/K_f = $k Pa: /" || status=1
done
/usr/bin/python3 "$root/scripts/plot_seepage.py" --compare "$out/uplift_all.png" \
  "$out/kf_1e7" "$out/kf_1e5" "$out/kf_1e4"
echo "reports: $out/kf_*/report.md; plots: $out/kf_*/uplift.png, pressure.png, $out/uplift_all.png"
if grep -q "FAIL\|INCOMPLETE" "$out"/kf_*.log; then status=1; fi
exit "$status"
