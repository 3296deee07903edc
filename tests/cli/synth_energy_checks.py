#!/usr/bin/env python3
"""The modal source's energy rule end to end (docs/synth.md "Energy account"), on the plate scene of
`make demo` (scenes/plate.toml pre-fractured into 40 pieces, simulated here) rendered with modal sound only:
- with the plate-shaped bank (configs/modal-plate.toml, the synth_plate_bank fixture) and with the
  near-sphere bank of make demo (configs/modal-demo.toml, glass, which serves ceramic's nu), the
  peaks at the listener are within a factor of 2 of each other: voicing the flat pieces by
  proxies that fit them badly no longer makes them several times louder (before the rule: 286
  and 69.6 Pa);
- every piece radiates less than its modes received (the summary's worst ratio is below 1) with
  either bank, and with the bank of the sphere alone (the synth_modal_bank fixture; its 33 modes
  per piece against the plate bank's 2 make its peak higher, which the rule does not touch);
- without the rule (--no-energy-rule) the near-sphere bank's pieces radiate more than they
  received, the defect the rule is for: this check fails on a synthesizer without the rule's effect.
Usage: synth_energy_checks.py CLATTER_SIM CLATTER_SYNTH SOURCE_DIR PLATE_BANK DEMO_BANK SPHERE_BANK SCRATCH"""
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from check_lib import check, finish, run, start  # noqa: E402

sim, synth, source_dir, plate_bank, demo_bank, sphere_bank, scratch = sys.argv[1:8]
start(scratch)

r = run(sim, "-c", os.path.join(source_dir, "scenes", "plate.toml"), "--set", "plate.pieces=40", "-o", "plate.json")
check(r.returncode == 0, f"clatter-sim makes the plate scene (exit {r.returncode}) {r.stderr.strip()[-300:]}")


def render(bank, *options):
    r = run(synth, "-i", "plate.json", "-m", bank, "-o", "plate.wav", *options)
    peak = re.search(r"modal +peak ([0-9.e+-]+) Pa", r.stdout)
    worst = re.search(r"worst object (\d+) radiates ([0-9.e+-]+) of its modes' energy", r.stdout)
    rule = re.search(r"energy rule (on|OFF): (\d+) objects' transfer bounded by their surface, (\d+) with radiation", r.stdout)
    line = next((l for l in r.stdout.splitlines() if "energy:" in l), "(no energy line)")
    print(f"  {os.path.basename(bank)} {' '.join(options)}: exit {r.returncode}; {line}")
    if r.returncode != 0 or not (peak and worst and rule):
        check(False, f"clatter-synth renders the plate with {bank} {options}: {r.stderr.strip()[-300:]}")
        return None
    return float(peak.group(1)), int(worst.group(1)), float(worst.group(2)), int(rule.group(2))


plate, demo, sphere = render(plate_bank), render(demo_bank), render(sphere_bank)
plate_off, demo_off = render(plate_bank, "--no-energy-rule"), render(demo_bank, "--no-energy-rule")
if plate and demo and sphere and plate_off and demo_off:
    ratio = demo[0] / plate[0]
    check(0.5 <= ratio <= 2, f"the plate's modal peak with the near-sphere bank {demo[0]:.4g} Pa is within a factor 2 of the "
          f"plate bank's {plate[0]:.4g} Pa (ratio {ratio:.3g}; without the rule {demo_off[0]:.4g} and {plate_off[0]:.4g} Pa; "
          f"the sphere bank's {sphere[0]:.4g} Pa)")
    for name, result in (("plate", plate), ("near-sphere", demo), ("sphere", sphere)):
        check(result[2] < 1, f"with the {name} bank every piece radiates less than its modes received (worst: object "
              f"{result[1]}, {result[2]:.3g}); {result[3]} objects' transfer bounded")
    check(demo_off[2] > 1, f"without the rule the near-sphere bank's worst piece radiates more than it received "
          f"(object {demo_off[1]}, {demo_off[2]:.3g}): the defect the rule removes")
finish("synth energy checks")
