#!/usr/bin/env bash
# Command-line behaviour: --version, check, strict errors with exit code 2,
# output files, refusal to overwrite, and a clean interrupt.
# Usage: test_cli.sh PATH/TO/darcydem SOURCE_DIR
set -u
exe="$1"
src="$2"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
passed=0
failed=0
ok() { echo "ok: $1"; passed=$((passed + 1)); }
bad() { echo "FAILED: $1"; failed=$((failed + 1)); }

"$exe" --version | grep -q "^darcydem [0-9]" && ok "--version" || bad "--version"

scene="$src/examples/column_settling/column.toml"
"$exe" check "$scene" | grep -q "OK (2D, 50 particles" && ok "check accepts the example" || bad "check"

# The stages' 1 s in steps of the time step it gives (printed to 4
# digits, so to 1e-3).
"$exe" check "$scene" | awk '/OK \(2D/ { match($0, /time step [0-9.e+-]+ s, at most [0-9]+ steps/); split(substr($0, RSTART, RLENGTH), w, " ");
  dt = w[3]; n = w[7]; exit !(n > 0 && (n * dt - 1.0)^2 < 1e-6) }' \
  && ok "check gives the stages' length in steps" || bad "check: steps ($("$exe" check "$scene" | head -1))"

"$exe" check "$src/examples/fluid_cases/bed_with_inlet.toml" | grep -q "^  patch inlet on z_min: 9 faces, 3.6e-05 m^2, no_flow$" \
  && ok "check prints a boundary patch's faces and area" || bad "check: patch"
"$exe" check "$src/examples/fluid_cases/consolidation_sealed_piston.toml" | grep -q "^  wall piston displaces the fluid: a box$" \
  && ok "check names the walls that displace the fluid" || bad "check: walls that displace the fluid"
"$exe" check "$src/examples/fluid_cases/graded_upward_seepage.toml" \
  | grep -q "^  fluid grid: x 3 cells in \[0, 0.006\] m (0.002 m); .* z 4 cells in \[0, 0.008\] m (graded, 0.001368 to 0.002736 m)$" \
  && ok "check describes a graded fluid grid" || bad "check: graded grid"
# Kozeny-Carman's d by default: that of the example's equal 0.98 mm spheres.
"$exe" check "$src/examples/fluid_cases/upward_seepage_bed.toml" \
  | grep -q "^  permeability: Kozeny-Carman, d = 0.00098 m (the grains' specific-surface diameter); porosity taken in \[0.05, 0.9\]; drag darcy$" \
  && ok "check gives Kozeny-Carman's diameter and the drag law" || bad "check: permeability"
"$exe" check "$src/examples/fluid_cases/sheet_pile.toml" | grep -q "^  permeability: constant, k = 0.001 0.001 m/s;" \
  && ok "check gives a constant hydraulic conductivity per axis" || bad "check: constant permeability"
"$exe" check "$src/examples/fluid_cases/sheet_pile.toml" | grep -q "critical step none (no particle is free to move)$" \
  && ok "check says what an infinite critical step means (only fixed particles)" || bad "check: critical step"
"$exe" check "$src/examples/fluid_cases/sheet_pile_heave.toml" | grep -q "OK (2D, 508 particles, 4 walls" \
  && ok "check accepts a scene with a box wall" || bad "check: box wall"
"$exe" check "$src/examples/dem_cases/periodic_triaxial.toml" \
  | grep -q "^  stage shear: periodic cell x held at 100000 Pa, y held at 100000 Pa, z strained at -1 1/s (ln strains over the stage's 0.2 s if it runs to its end: z -0.2); servo gain 0.0002 1/(Pa s), at most 5 1/s, holding the contacts' stress$" \
  && ok "check gives a stage's periodic cell motion (-1 /s over 0.2 s: ln strain -0.2)" || bad "check: periodic cell"
"$exe" check "$src/examples/dem_cases/periodic_undrained.toml" \
  | grep -q "^  stage shear: periodic cell x strained at 0.5 1/s, y strained at 0.5 1/s, z strained at -1 1/s (ln strains over the stage's 0.2 s if it runs to its end: x 0.1, y 0.1, z -0.2, volumetric 0)$" \
  && ok "check gives the volume's strain of a cell strained along every axis (0: constant volume)" || bad "check: constant volume"
"$exe" check "$src/examples/fluid_cases/periodic_undrained_water.toml" \
  | grep -q "^  stage shear: periodic cell x held at 100000 Pa, y held at 100000 Pa, z strained at -1 1/s (ln strains over the stage's 0.2 s if it runs to its end: z -0.2); servo gain 0.0002 1/(Pa s), at most 5 1/s, holding the total stress (contacts + pore water)$" \
  && ok "check says a cell's servo holds the total stress" || bad "check: total stress servo"
"$exe" check "$src/examples/dem_cases/rotating_drum.toml" | grep -q "OK (3D, 450 particles, 1 wall, 2 stages" \
  && ok "check counts one wall in the singular" || bad "check: one wall"
"$exe" check "$src/examples/dem_cases/conical_hopper.toml" \
  | grep -q '^  note: \[\[wall\]\] #1: wall "hopper" is a mesh of 192 facets (144 vertices, from conical_hopper.stl), area 0.00' \
  && ok "check says what a mesh wall's file made" || bad "check: mesh wall ($("$exe" check "$src/examples/dem_cases/conical_hopper.toml" 2>&1 | grep mesh))"
"$exe" check "$scene" | grep -q "^  grains: all d = 1 mm$" \
  && ok "check gives the grains' sizes" || bad "check: grains ($("$exe" check "$scene" | sed -n 2p))"
"$exe" check "$src/examples/fluid_cases/graded_sand_seepage.toml" \
  | grep -q "^  grains: d 0.8[0-9]* to 2.[0-9]* mm; by mass D10 " \
  && ok "check gives a graded sand's D10 ... D60" || bad "check: graded sand"
sed 's/^drag = "darcy"/drag = "ergun"/' "$src/examples/fluid_cases/graded_sand_seepage.toml" > "$work/graded_ergun.toml"
"$exe" check "$work/graded_ergun.toml" \
  | grep -q "^  note: with Ergun's drag each grain takes its own d, which balances Kozeny-Carman for d = 0.0013" \
  && ok "check says how far Ergun's drag misses Kozeny-Carman on a graded sand" || bad "check: Ergun's note"

"$exe" check "$src/examples/fluid_cases/pumping_well.toml" \
  | grep -q "^  source well at (0.205, 0.205) m, into cell (20, 20): -2e-06 m^2/s$" \
  && ok "check names a well, its cell and inflow" || bad "check: source ($("$exe" check "$src/examples/fluid_cases/pumping_well.toml" | grep source))"
"$exe" check "$src/examples/fluid_cases/screened_well.toml" \
  | grep -q "^  source well at (0.155, 0.155) m, into cells (15, 15, 0 to 3; screened from z = 0 to 0.04 m): -4e-06 m^3/s; a well of radius 0.001 m, its cell's equivalent radius 0.00198506 m across it, well index 3.66554e-08 m^3/(s Pa) summed over its cells$" \
  && ok "check names a screened well's cells and its well index" || bad "check: screened well ($("$exe" check "$src/examples/fluid_cases/screened_well.toml" | grep source))"
# The screen's cells' inflows, a column each, add up to the well's at every
# output time: while it pumps 4e-6 m^3/s, and shut off, when the bore only
# passes water from cell to cell (bound 1e-9 of the pumping rate: the bore's
# pressure is found to the solver's tolerance, 1e-10).
cp "$src/examples/fluid_cases/screened_well.toml" "$work/screened.toml"
printf '\n[[probe]]\nname = "q"\nquantity = "screen_inflow_profile"\nside = "well"\n' >> "$work/screened.toml"
"$exe" run "$work/screened.toml" --out "$work/screened" > /dev/null 2>&1 \
  && head -1 "$work/screened/probes.csv" | grep -q ",q_0,q_1,q_2,q_3$" \
  && awk -F, 'NR > 1 { d = $7 + $8 + $9 + $10 - $2; if (d < 0) d = -d; if (d > 4e-15) bad = 1; if ($2 != 0) pumped = 1;
                       if ($10 < $8) ends = 1 }
              END { exit !(NR > 30 && !bad && pumped && ends) }' "$work/screened/probes.csv" \
  && ok "a screened well's cells' inflows add up to its own" || bad "screen_inflow_profile ($(sed -n 10p "$work/screened/probes.csv"))"
# A drain: the pumping test's well held at -5 Pa, taking water out only.
sed 's|^inflow = -2e-6 .*|pressure = -5.0\ndrain = true|' "$src/examples/fluid_cases/pumping_well.toml" > "$work/drain.toml"
"$exe" check "$work/drain.toml" \
  | grep -q "^  source well at (0.205, 0.205) m, into cell (20, 20): -5 Pa held; a drain: it takes water out only, while the water around it stands above that$" \
  && ok "check says a source is a drain" || bad "check: drain ($("$exe" check "$work/drain.toml" 2>&1 | grep source))"
"$exe" check "$src/examples/dem_cases/vibrated_bed.toml" \
  | grep -q "^  stage shake: wall floor oscillates, amplitude (0, 0.001242) m at 20 Hz, phase -90 deg: peak acceleration 19.62 m/s^2, Gamma = A omega^2 / g = 2 along gravity (above 1" \
  && ok "check gives a shaken wall's Gamma" || bad "check: Gamma ($("$exe" check "$src/examples/dem_cases/vibrated_bed.toml" | grep shake))"
sed 's/servo = { target_force = 0.51, gain/servo = { target_force = { times = [0.0, 0.2], values = [0.3, 0.51] }, cycle = { amplitude = 0.25, frequency = 1.5, phase = -90.0 }, gain/' \
  "$src/examples/fluid_cases/consolidation_sealed_piston.toml" > "$work/cyclic_piston.toml"
"$exe" check "$work/cyclic_piston.toml" \
  | grep -q "^  stage load: wall piston servo, target_force from 0.3 to 0.51 N over 0.2 s (2 points, between 0.3 and 0.51 N) + 0.25 N sin(2 pi 1.5 Hz t - 90 deg) (period 0.6667 s), on the load of the grains and the pore water$" \
  && ok "check gives a servo's schedule and cycle" || bad "check: servo schedule ($("$exe" check "$work/cyclic_piston.toml" | grep piston))"
sed 's/^density = 2650.0/densty = 2650.0/' "$scene" > "$work/bad.toml"
msg="$("$exe" check "$work/bad.toml" 2>&1)"; rc=$?
[ $rc -eq 2 ] && echo "$msg" | grep -q "bad.toml:[0-9]*:[0-9]*: error: .*'densty'.*Did you mean 'density'" \
  && ok "bad key: exit 2 with file:line and suggestion" || bad "bad key ($rc): $msg"

"$exe" run "$scene" --out "$work/out" > /dev/null 2>&1; rc=$?
[ $rc -eq 0 ] && [ -s "$work/out/probes.csv" ] && [ -s "$work/out/particles.pvd" ] && [ -s "$work/out/run.json" ] \
  && head -1 "$work/out/probes.csv" | grep -q "^time,top_y,floor_load,kinetic_energy$" \
  && grep -q '"status": "completed"' "$work/out/run.json" && ok "run writes probes, snapshots, run.json" || bad "run ($rc)"

"$exe" run "$scene" --out "$work/out" > /dev/null 2>"$work/err"; rc=$?
[ $rc -eq 2 ] && grep -q "not empty; use --force" "$work/err" && ok "refuses a non-empty output directory" || bad "overwrite ($rc)"
"$exe" run "$scene" --out "$work/out" --force > /dev/null 2>&1 && ok "--force overwrites" || bad "--force"

# A long run, interrupted: what was computed is kept and run.json says so.
sed -e 's/^duration = 1.0/duration = 1000.0/' -e '/stop_when/,/check_interval/d' "$scene" > "$work/long.toml"
timeout --preserve-status -s INT 2 "$exe" run "$work/long.toml" --out "$work/long" > /dev/null 2>&1; rc=$?
rows=$(wc -l < "$work/long/probes.csv" 2>/dev/null || echo 0)
[ $rc -eq 130 ] && grep -q '"status": "interrupted"' "$work/long/run.json" && [ "$rows" -gt 10 ] \
  && ok "interrupt keeps output ($rows probe rows)" || bad "interrupt (rc $rc, rows $rows)"

# ... and it goes on from its checkpoint with --resume: the probe rows written
# before the interruption stay as they were, new ones follow.
head -5 "$work/long/probes.csv" > "$work/long.head"
timeout --preserve-status -s INT 2 "$exe" run "$work/long.toml" --out "$work/long" --resume > /dev/null \
  2> "$work/resume.err"; rc=$?
rows2=$(wc -l < "$work/long/probes.csv" 2>/dev/null || echo 0)
[ $rc -eq 130 ] && grep -q '"resumes": 1' "$work/long/run.json" && [ "$rows2" -gt "$rows" ] \
  && [ "$(head -5 "$work/long/probes.csv")" = "$(cat "$work/long.head")" ] \
  && grep -q "^resumed from .*checkpoint.bin at t = " "$work/resume.err" \
  && grep -q "to go on from here: .* --resume$" "$work/resume.err" \
  && ok "--resume goes on from the checkpoint ($rows then $rows2 probe rows)" || bad "resume (rc $rc, rows $rows2)"
"$exe" run "$work/long.toml" --out "$work/long" --resume --force > /dev/null 2>"$work/err"; rc=$?
[ $rc -ne 0 ] && grep -q "excludes" "$work/err" && ok "--resume and --force exclude each other" || bad "--resume --force ($rc)"
"$exe" run "$scene" --out "$work/out" --resume > /dev/null 2>"$work/err"; rc=$?
[ $rc -eq 2 ] && grep -q "cannot resume: .*out/checkpoint.bin: no checkpoint to resume from" "$work/err" \
  && ok "--resume without a checkpoint: exit 2 with the file" || bad "--resume without checkpoint ($rc)"
"$exe" run "$scene" --out "$work/bad_every" --checkpoint-every -1 > /dev/null 2>"$work/err"; rc=$?
[ $rc -ne 0 ] && grep -q "^--checkpoint-every: '-1' is not allowed: a number of seconds >= 0" "$work/err" \
  && ok "a bad --checkpoint-every is refused with what is allowed" || bad "--checkpoint-every -1 ($rc)"
"$exe" run "$scene" --out "$work/bad_threads" --threads -2 > /dev/null 2>"$work/err"; rc=$?
[ $rc -ne 0 ] && grep -q "^--threads: '-2' is not allowed: a whole number of threads >= 0 (0: all cores)" "$work/err" \
  && ok "a bad --threads is refused with what is allowed" || bad "--threads -2 ($rc): $(cat "$work/err")"
touch "$work/a_file"
"$exe" run "$scene" --out "$work/a_file" > /dev/null 2>"$work/err"; rc=$?
[ $rc -eq 2 ] && grep -q "^error: --out '.*a_file' is a file; give a directory" "$work/err" \
  && ok "--out naming a file is refused as such" || bad "--out a file ($rc): $(cat "$work/err")"
"$exe" run "$scene" --out "$work/a_file/sub" > /dev/null 2>"$work/err"; rc=$?
[ $rc -eq 1 ] && grep -q "^error: cannot make the output directory '.*a_file/sub': " "$work/err" \
  && ok "an output directory that cannot be made is named" || bad "--out under a file ($rc): $(cat "$work/err")"
# Killed outright (no chance to write at the end): the checkpoint written
# every 0.3 s of wall time is there to resume from.
bash -c 'timeout -s KILL 2 "$0" run "$1" --out "$2" --checkpoint-every 0.3; true' \
  "$exe" "$work/long.toml" "$work/killed" > /dev/null 2>&1
timeout --preserve-status -s INT 2 "$exe" run "$work/long.toml" --out "$work/killed" --resume > /dev/null 2>&1; rc=$?
[ $rc -eq 130 ] && grep -q '"resumes": 1' "$work/killed/run.json" \
  && ok "a killed run resumes from its periodic checkpoint" || bad "resume after kill (rc $rc)"

# The same when the log's reader goes away (a closed pipe): the run stops
# as interrupted, its output kept, instead of being killed by SIGPIPE.
# The reader takes the log's two opening lines (the scene, its grains) and
# goes, so the run stops at its first progress line, having computed some.
"$exe" run "$work/long.toml" --out "$work/piped" 2>&1 | head -2 > /dev/null
rows=$(wc -l < "$work/piped/probes.csv" 2>/dev/null || echo 0)
grep -q '"status": "interrupted"' "$work/piped/run.json" 2>/dev/null && [ "$rows" -gt 10 ] \
  && ok "a closed log pipe stops the run with its output kept ($rows probe rows)" || bad "closed pipe (rows $rows)"

# A pore-fluid scene: fluid snapshots, the profile probe, the balance in run.json.
bed="$src/examples/fluid_cases/hydrostatic_bed.toml"
"$exe" run "$bed" --out "$work/bed" > "$work/bed.log" 2>&1; rc=$?
[ $rc -eq 0 ] && [ -s "$work/bed/fluid.pvd" ] && [ -s "$work/bed/fluid_00000.vti" ] \
  && grep -q 'Name="pressure"' "$work/bed/fluid_00000.vti" \
  && head -1 "$work/bed/probes.csv" | grep -q ",pressure_profile_0,.*,pressure_profile_4$" \
  && grep -q '"fluid": {"cells": 36' "$work/bed/run.json" && grep -q "fluid balance so far" "$work/bed.log" \
  && grep -q '"grains_outside_grid": 0, "grains_in_free_water": 0}' "$work/bed/run.json" \
  && ok "fluid run writes .vti snapshots, profile probes and the balance" || bad "fluid run ($rc)"
# The progress line at a stage's end: the time left is 0, not "-0" (the
# last step may end a hair past the stage's end).
grep -q "^stage settle: .* ETA 0 s$" "$work/bed.log" && ! grep -q "ETA -" "$work/bed.log" \
  && ok "progress ends a stage with ETA 0 s" || bad "progress: $(grep ETA "$work/bed.log" | tail -1)"

# A seepage-column run interrupted in its first stage still writes its
# analysis files, marked INCOMPLETE.
timeout --preserve-status -s INT 2 "$exe" run "$src/examples/seepage_column/kf_1e7.toml" --out "$work/seep" \
  > /dev/null 2>&1; rc=$?
[ $rc -eq 130 ] && grep -q '"verdict": "INCOMPLETE"' "$work/seep/seepage.json" && [ -s "$work/seep/report.md" ] \
  && ok "interrupted seepage run keeps its report" || bad "interrupted seepage run (rc $rc)"

# A run that blows up (absurd gravity): exit 1, a message with the time, and
# run.json written with status "failed" next to the probes so far.
sed -e 's/^gravity = \[0.0, -9.80665\]/gravity = [0.0, -1e308]/' "$scene" > "$work/blow.toml"
"$exe" run "$work/blow.toml" --out "$work/blow" > /dev/null 2>"$work/blow.err"; rc=$?
[ $rc -eq 1 ] && grep -q "^error: at t = .* (step [0-9]*): the position of particle [0-9]* is not finite: the simulation blew up" "$work/blow.err" && grep -q '"status": "failed"' "$work/blow/run.json" \
  && [ -s "$work/blow/probes.csv" ] && ok "a blown-up run fails cleanly and keeps its output" || bad "blow-up (rc $rc)"

# A new run with --force where an interrupted run left its checkpoint:
# the old checkpoint goes, even though this run fails before writing one.
[ -s "$work/long/checkpoint.bin" ] || bad "the interrupted run left no checkpoint"
"$exe" run "$work/blow.toml" --out "$work/long" --force > /dev/null 2>&1; rc=$?
[ $rc -eq 1 ] && [ ! -e "$work/long/checkpoint.bin" ] && ! grep -q '"checkpoint"' "$work/long/run.json" \
  && ok "--force removes an old run's checkpoint" || bad "stale checkpoint after --force (rc $rc)"

# --set: a scene changed on the command line runs as the file edited by
# hand, bit for bit, and says so in its log and run.json.
sed -e '0,/^restitution = 0.5/s//restitution = 0.3/' -e 's/^local_damping = 0.7/local_damping = 0.5/' "$scene" > "$work/edited.toml"
"$exe" run "$work/edited.toml" --out "$work/edited" > /dev/null 2>&1
"$exe" run "$scene" --out "$work/plain" > /dev/null 2>&1
"$exe" run "$scene" --out "$work/set" --set contact.1.restitution=0.3 --set 'stage.settle.local_damping=0.5' \
  > /dev/null 2>"$work/set.log"; rc=$?
[ $rc -eq 0 ] && ! cmp -s "$work/edited/probes.csv" "$work/plain/probes.csv" && cmp -s "$work/edited/probes.csv" "$work/set/probes.csv" \
  && grep -q "^set: contact.1.restitution=0.3$" "$work/set.log" \
  && grep -q '"overrides": \["contact.1.restitution=0.3", "stage.settle.local_damping=0.5"\],' "$work/set/run.json" \
  && ok "run --set is the scene edited by hand" || bad "run --set (rc $rc)"
"$exe" check "$src/examples/fluid_cases/undrained_triaxial_packing.toml" \
  | grep -q "^  note: \[fluid\]: one cell whose sides no stage drains: .* (3.015e-07 s with it)" \
  && ok "check notes a sealed cell's step without the water's stiffness" || bad "check: sealed cell's note"
"$exe" check "$src/examples/fluid_cases/undrained_biaxial.toml" --set fluid.bulk_modulus=1e5 \
  | grep -q "^  pore fluid: 1 cells, K_f = 1e+05 Pa" && ok "check --set changes K_f" || bad "check --set"
"$exe" check "$scene" --set stage.settle.duration=-1 > /dev/null 2>"$work/set.err"; rc=$?
[ $rc -eq 2 ] && grep -q "^--set stage.settle.duration=-1: error: \[\[stage\]\] #1 key 'duration': must be > 0" "$work/set.err" \
  && ok "a bad --set value is refused naming it" || bad "bad --set value (rc $rc): $(cat "$work/set.err")"
"$exe" check "$scene" --set stage.shear.duration=1 > /dev/null 2>"$work/set.err"; rc=$?
[ $rc -eq 2 ] && grep -q "has no \[\[stage\]\] named or numbered 'shear' (there are: 'settle'; number them from 1)" "$work/set.err" \
  && ok "a --set path the scene lacks is refused naming what there is" || bad "bad --set path (rc $rc): $(cat "$work/set.err")"

"$exe" check "$src/examples/fluid_cases/pumping_well.toml" --set fluid.source.well.radius=1e-3 \
  | grep -q "^  source well at (0.205, 0.205) m, into cell (20, 20): -2e-06 m^2/s; a well of radius 0.001 m, its cell's equivalent radius 0.00198506 m$" \
  && ok "check gives a well's radius and its cell's equivalent radius" || bad "check: well radius"

echo "$passed passed, $failed failed"
[ $failed -eq 0 ]
