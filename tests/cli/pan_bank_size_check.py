#!/usr/bin/env python3
"""analysis/pan_bank_size.py (docs/pan.md "The subset"): its three estimates against closed forms.
On sizes that follow a power law, size = 0.2 B^-0.5 C^-1 MB, given at five proxies, the fit
recovers the exponents and the 66's sum of the law (the measured five at their own sizes), the
mean estimate is 66 times their mean, and the nearest estimate is the sum of each grid proxy's
nearest measured size, counted by hand, and the script writes its CSV and plot; on the demo bank
(two proxies) the per-entry sizes add up to the file's and the script refuses to fit two points
(exit 2), as it refuses a missing file.
Usage: pan_bank_size_check.py PYTHON SCRIPT CLATTER_BANK DEMO_BANK WORKDIR"""
import importlib.util, math, os, shutil, subprocess, sys

python, script, bank_tool, demo_bank, work = sys.argv[1:6]
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
failures = []


def check(ok, what):
    print(("ok:   " if ok else "FAIL: ") + what)
    if not ok:
        failures.append(what)


spec = importlib.util.spec_from_file_location("pan_bank_size", script)
m = importlib.util.module_from_spec(spec)
spec.loader.exec_module(m)
grid = m.proxy_grid(0.5, 0.025, 0.0475)
check(len(grid) == 66 and (0.025, 0.025) in grid and (0.5, 0.5) in grid and all(c <= b for b, c in grid),
      f"the grid: {len(grid)} proxies with C <= B, corners included")
law = lambda b, c: 0.2 * b ** -0.5 * c ** -1.0
measured = {k: law(*k) for k in [(0.5, 0.5), (0.025, 0.025), (0.5, 0.025), (0.2625, 0.12), (0.405, 0.0725)]}
fit, nearest, mean, coef, fitted = m.extrapolate(measured, grid)
check(abs(coef[1] + 0.5) < 1e-9 and abs(coef[2] + 1.0) < 1e-9, f"fit exponents {coef[1]:.6f}, {coef[2]:.6f} (law -0.5, -1)")
exact = sum(law(b, c) for b, c in grid)
check(abs(fit - exact) < 1e-9 * exact, f"fit total {fit:.6f} MB against the law's sum {exact:.6f} MB")
check(abs(mean - 66 * sum(measured.values()) / 5) < 1e-12, f"mean x 66 {mean:.4f} MB")
by_hand = 0.0
for b, c in grid:
    best = None
    for k in measured:
        d = math.log(k[0] / b) ** 2 + math.log(k[1] / c) ** 2
        if best is None or d < best[0]:
            best = (d, measured[k])
    by_hand += best[1]
check(abs(nearest - by_hand) < 1e-12, f"nearest {nearest:.4f} MB against {by_hand:.4f} by hand")

# The demo bank (two proxies): its entries add up to the file, and two are too few for the fit.
entries = m.entry_sizes(bank_tool, demo_bank)
info = subprocess.run([bank_tool, "info", demo_bank], capture_output=True, text=True).stdout
total = float(next(line.split()[1] for line in info.splitlines() if line.strip().startswith("size:")))
check(len(entries) == 2 and abs(sum(entries.values()) - total) <= 0.002,
      f"the demo bank's {len(entries)} entries add up to {sum(entries.values()):.3f} MB of its {total:.3f} MB")
run = subprocess.run([python, script, demo_bank, "--bank", bank_tool, "-o", work], capture_output=True, text=True)
check(run.returncode == 2 and "at least 3" in run.stderr, f"two entries: exit {run.returncode}, {run.stderr.strip()}")
# End to end on the five of the law (entry_sizes stood in for): the table, CSV and plot.
m.entry_sizes = lambda tool, path: measured
sys.argv = [script, "x.h5", "--bank", bank_tool, "-o", work]
check(m.main() == 0, "main on the law's five")
rows = open(os.path.join(work, "pan_bank_size.csv")).read().splitlines()
check(len(rows) == 6 and os.path.getsize(os.path.join(work, "pan_bank_size.png")) > 0, f"CSV ({len(rows)} lines) and plot written")
bad = subprocess.run([python, script, os.path.join(work, "none.h5"), "--bank", bank_tool, "-o", work], capture_output=True, text=True)
check(bad.returncode == 2 and "none.h5" in bad.stderr, f"a missing bank: exit {bad.returncode}, {bad.stderr.strip()}")
print("pan bank size checks: " + ("all passed" if not failures else f"{len(failures)} failed"))
sys.exit(1 if failures else 0)
