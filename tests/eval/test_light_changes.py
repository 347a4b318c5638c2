#!/usr/bin/env python3
"""scripts/eval/run_eval.py's light_changes, which labels the lag table's rows (docs/results.md, "After a light
change: the lag"), on light curves written out here as the scene files define them (demo/scenes/*.json):
  light-off  a key light's one step at frame 30: one change, its window the 30 frames after it
  flicker    bursts of 2 frames at 8, 20, 23 and 41 (peak 12): every on and off is a step, including frame 23's,
             where a burst begins one frame after the one before ended; 20-25 is one change (steps closer than
             MERGE_STEPS frames), windows end at the next change
  sinusoid   a light that moves every frame by less than a step: no step, the first change at frame 1
Run: /usr/bin/python3 tests/eval/test_light_changes.py"""
import math
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
sys.path.insert(0, os.path.join(ROOT, "scripts", "eval"))
import run_eval  # noqa: E402

FAILED = []


def check(ok, what):
    print(("ok   " if ok else "FAIL ") + what)
    if not ok:
        FAILED.append(what)


def lights(curve, frames=60):
    return {f: {"key": curve(f)} for f in range(frames)}


def main():
    first, changes = run_eval.light_changes(lights(lambda f: 1.5 if f < 30 else 0.0))
    check(first == 30 and changes == [(30, 60, "30: key 1.5->0")], f"light-off: {first}, {changes}")

    bursts = [8, 20, 23, 41]
    first, changes = run_eval.light_changes(lights(lambda f: 12.0 if any(b <= f < b + 2 for b in bursts) else 0.0, 72))
    check(first == 8, f"flicker: first change at 8 (got {first})")
    check([c[:2] for c in changes] == [(8, 20), (20, 41), (41, 71)], f"flicker: windows {[c[:2] for c in changes]}")
    check(len(changes) == 3 and changes[1][2] == "20: key 0->12; 22: key 12->0; 23: key 0->12; 25: key 12->0",
          f"flicker: the second change lists frame 23's burst ({changes[1][2] if len(changes) > 1 else changes})")

    first, changes = run_eval.light_changes(lights(lambda f: 1.0 + 0.5 * math.sin(2.0 * math.pi * f / 60.0)))
    check(first == 1 and changes == [], f"sinusoid: no step ({first}, {changes})")
    if FAILED:
        print(f"{len(FAILED)} check(s) failed")
        return 1
    print("light changes: OK")
    return 0


if __name__ == "__main__":
    sys.exit(main())
