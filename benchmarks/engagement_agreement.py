"""Bench engagements against the Floquet exponents of their linearisation.

For each preset, a grid of dither settings across tongues 1-6 is run
through the bench FMU (``judder simulate``), and each run's verdict and
growth rate are compared with the Floquet exponent of the bench's
linearisation (the acceptance of issue 18):

* exponent > 0.75 1/s: the run should have judder, growing within 30 %
  of the exponent;
* exponent < 0: no judder, and the upstream speed's swing after the
  pressure ramp below 100 rpm.

The settings are split by whether the dither's forced slip swing stays
within the friction curve's linear range (``linearisation_holds``).
Prints a table per class of setting; docs/time-domain.md quotes it.

    python benchmarks/engagement_agreement.py [--freq 10:230:56] [--pf 0.2,0.5,0.8]
"""

import argparse
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from drivelines import get_preset  # noqa: E402
from judder import api  # noqa: E402
from judder.commands._values import parse_grid, parse_list  # noqa: E402

PRESETS = ("paper-4dof", "paper-4dof-fitted")


def _run(preset, freq_hz, p_f_bar):
    result = api.simulate(freq_hz, p_f_bar, parameters=get_preset(preset))
    run, s = result.runs[0][1], result.summaries[0]
    after = run.time >= result.start
    swing = float(np.ptp(run["w_upstream"][after]) / 2 * 30 / np.pi)
    return {"preset": preset, "freq_hz": freq_hz, "p_f_bar": p_f_bar,
            "exponent": s["floquet_exponent_per_s"],
            "floquet_kind": s["floquet_kind"], "judder": s["judder"],
            "kind": s["judder_kind"], "growth": s["judder_growth_per_s"],
            "holds": s["linearisation_holds"], "swing_rpm": swing}


def _summary(rows, label):
    judder = [r for r in rows if r["exponent"] > 0.75]
    stable = [r for r in rows if r["exponent"] < 0]
    found = [r for r in judder if r["judder"]]
    within = [r for r in found if r["growth"] is not None
              and abs(r["growth"] / r["exponent"] - 1) <= 0.3]
    quiet = [r for r in stable if not r["judder"]]
    small = [r for r in stable if r["swing_rpm"] < 100]
    print(f"| {label} | {len(judder)} | {len(found)} | {len(within)} | "
          f"{len(stable)} | {len(quiet)} | {len(small)} |")
    return judder, stable


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--freq", default="10:230:56")
    parser.add_argument("--pf", default="0.2,0.5,0.8")
    args = parser.parse_args(argv)
    freqs = parse_grid(args.freq, "--freq", "Hz")
    amplitudes = [float(p) for p in parse_list(args.pf, "--pf")]
    rows = []
    total = len(PRESETS) * len(freqs) * len(amplitudes)
    for preset in PRESETS:
        for f in freqs:
            for p in amplitudes:
                rows.append(_run(preset, float(f), p))
                print(f"\r{len(rows)}/{total} runs", end="", file=sys.stderr)
    print(file=sys.stderr)
    print("| settings | exponent > 0.75 | judder | growth within 30 % | "
          "exponent < 0 | no judder | swing < 100 rpm |")
    print("| --- | --- | --- | --- | --- | --- | --- |")
    for preset in PRESETS:
        for holds, label in ((True, "forced swing within the linear range"),
                             (False, "forced swing beyond it")):
            _summary([r for r in rows if r["preset"] == preset
                      and r["holds"] is holds], f"{preset}, {label}")
    print("\njudder points (exponent > 0.75 1/s):")
    print("| preset | f (Hz) | p_f (bar) | Floquet | run | growth / "
          "exponent | swing (rpm) | linear |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- |")
    for r in rows:
        if r["exponent"] > 0.75:
            ratio = "-" if r["growth"] is None else \
                f"{r['growth'] / r['exponent']:.2f}"
            print(f"| {r['preset']} | {r['freq_hz']:g} | {r['p_f_bar']:g} | "
                  f"{r['floquet_kind']} {r['exponent']:+.2f} | "
                  f"{r['kind'] if r['judder'] else 'no judder'} | {ratio} | "
                  f"{r['swing_rpm']:.0f} | {'yes' if r['holds'] else 'no'} |")
    misses = [r for r in rows if r["exponent"] < 0
              and (r["judder"] or r["swing_rpm"] >= 100)]
    print(f"\nstable settings with judder or a swing >= 100 rpm: "
          f"{len(misses)}")
    for r in misses:
        print(f"  {r['preset']} {r['freq_hz']:g} Hz {r['p_f_bar']:g} bar: "
              f"{r['kind']}, swing {r['swing_rpm']:.0f} rpm")


if __name__ == "__main__":
    main()
