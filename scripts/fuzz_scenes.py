#!/usr/bin/python3
"""Bad input, by mutation: every `key = value` line of the given scenes is
replaced by each of a list of bad values (or deleted), and `darcydem check`
must either accept the mutant or refuse it with exit code 2 and a message
that names the mutant's file. A crash (a signal, another exit code, an
uncaught exception, a sanitizer report) or a check that takes over a minute
is a failure. With --run, each mutant that `check` accepts is also run, its
stages cut to DURATION seconds, and any exit but 0 is listed with the last
lines of its log (an absurd but valid value may still blow a run up; the
list is for reading, not a verdict).

    scripts/fuzz_scenes.py build/darcydem examples/fluid_cases/*.toml
    scripts/fuzz_scenes.py --run 0.02 build/darcydem examples/seepage_column/kf_1e5.toml

Exits 1 if `check` failed on any mutant. Mutants are written next to their
scene (its relative paths must resolve) as _fuzz_mutant.toml and removed.
"""
import os
import re
import shutil
import subprocess
import sys
import tempfile

BAD_VALUES = ["-1", "0", "1e308", "nan", "inf", "-inf", '"x"', "[]", "[1]", "[1, 2, 3, 4]", "true", "{}",
              "1e-300", "2147483648", "-0", "[nan, nan]", "[0, 0]", '["a", "b"]', "0.5", "1e30", "[1e30, 0]"]
KEY_LINE = re.compile(r"^(\s*)([A-Za-z_.]+)\s*=\s*(.*)$")


def mutants(text):
    lines = text.split("\n")
    for i, line in enumerate(lines):
        m = KEY_LINE.match(line)
        if not m:
            continue
        for value in [None] + BAD_VALUES:
            new = list(lines)
            new[i] = "" if value is None else f"{m.group(1)}{m.group(2)} = {value}"
            yield i + 1, m.group(2), value, "\n".join(new)


def check(exe, path):
    """None if check behaved, else what went wrong."""
    try:
        r = subprocess.run([exe, "check", path], capture_output=True, text=True, timeout=60)
    except subprocess.TimeoutExpired:
        return "check took over 60 s", 1
    said = r.stdout + r.stderr
    if r.returncode not in (0, 2):
        return f"exit {r.returncode}: {said.strip()[:300]}", r.returncode
    for sign in ("terminate called", "runtime error", "AddressSanitizer", "Assertion"):
        if sign in said:
            return f"'{sign}': {said.strip()[:300]}", r.returncode
    if r.returncode == 2 and os.path.basename(path) not in said:
        return f"the message does not name the file: {said.strip()[:300]}", r.returncode
    return None, r.returncode


def main(argv):
    run_for = None
    if len(argv) > 2 and argv[1] == "--run":
        run_for = float(argv[2])
        argv = [argv[0]] + argv[3:]
    if len(argv) < 3:
        print(__doc__)
        return 2
    exe, scenes = os.path.abspath(argv[1]), argv[2:]
    failures = 0
    tried = 0
    for scene in scenes:
        text = open(scene).read()
        if run_for is not None:
            text = re.sub(r"(?m)^duration = .*$", f"duration = {run_for}", text)
        path = os.path.join(os.path.dirname(os.path.abspath(scene)), "_fuzz_mutant.toml")
        out = tempfile.mkdtemp(prefix="darcydem_fuzz_")
        try:
            for line, key, value, mutant in mutants(text):
                with open(path, "w") as f:
                    f.write(mutant)
                tried += 1
                problem, rc = check(exe, path)
                where = f"{scene}:{line} {key} = {value if value is not None else '(deleted)'}"
                if problem:
                    failures += 1
                    print(f"FAILED {where}: {problem}", flush=True)
                    continue
                if run_for is None or rc != 0 or key in ("duration", "name", "file"):
                    continue
                shutil.rmtree(os.path.join(out, "run"), ignore_errors=True)
                try:
                    r = subprocess.run([exe, "run", path, "--out", os.path.join(out, "run")],
                                       capture_output=True, text=True, timeout=60)
                    if r.returncode != 0:
                        last = [s for s in r.stderr.split("\n") if s.strip()][-1:]
                        print(f"run exit {r.returncode} {where}: {' '.join(last)[:300]}", flush=True)
                except subprocess.TimeoutExpired:
                    print(f"run over 60 s {where}", flush=True)
        finally:
            if os.path.exists(path):
                os.remove(path)
            shutil.rmtree(out, ignore_errors=True)
        print(f"{scene}: done", flush=True)
    print(f"{tried} mutants, {failures} check failures")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
