#!/usr/bin/env bash
# The main job: builds darcydem and runs the paper's column of 50 discs
# settling under gravity, then plots the settlement against the closed form.
# Output in out/column_settling/ (probes.csv, snapshots, run.json, settlement.png).
set -euo pipefail
root="$(cd "$(dirname "$0")/.." && pwd)"
"$root/scripts/build.sh" "$root/build"
out="$root/out/column_settling"
"$root/build/darcydem" run "$root/examples/column_settling/column.toml" --out "$out" --force
/usr/bin/python3 "$root/examples/column_settling/plot.py" "$out"
