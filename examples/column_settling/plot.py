"""Plots the column's top position against time with the closed-form
settled position, and prints the settlement error. Usage: plot.py OUT_DIR"""
import csv
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

out = sys.argv[1]
with open(f"{out}/probes.csv") as f:
    rows = list(csv.DictReader(f))
t = [float(r["time"]) for r in rows]
top = [float(r["top_y"]) for r in rows]
r = 0.0005
m = 2650.0 * math.pi * r * r * 1.0
expected = 1275.0 * m * 9.80665 / 1e5
top0 = r + 49 * 2 * r
settlement = top0 - top[-1]
err = abs(settlement - expected) / expected
plt.figure(figsize=(6, 4))
plt.plot(t, [(top0 - y) * 1e3 for y in top], label="darcydem")
plt.axhline(expected * 1e3, color="k", ls="--", label="closed form 1275 m g / k_n")
plt.xlabel("time (s)")
plt.ylabel("settlement of the top disc (mm)")
plt.title("50-disc column settling under gravity")
plt.legend()
plt.tight_layout()
plt.savefig(f"{out}/settlement.png", dpi=120)
print(f"settlement {settlement*1e3:.5f} mm, closed form {expected*1e3:.5f} mm, error {err*100:.3f}%")
print(f"plot: {out}/settlement.png")
