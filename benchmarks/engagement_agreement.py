"""Bench engagements against the Floquet exponents and the periodic orbit.

For each preset, a grid of dither settings across tongues 1-6 is run
through the bench FMU (``judder simulate``). Each run's verdict (the
dither-related oscillation above the NVH limit, or an instability
growing at 1/s or faster), mechanism and growth are compared with

* the Floquet exponent of the bench's linearisation (issue 18): above
  0.75 1/s the run should be parametric judder, growing within 30 % of
  the exponent where the dither's forced slip swing stays in the friction
  curve's linear range; between 0 and 0.75 1/s and below 0 the verdict
  is the amplitude's (forced judder where the forced oscillation exceeds
  the limit);
* the periodic orbit of the same bench at the same setting (``judder
  orbit``, issue 29): the same verdict and mechanism, and, where the
  orbit settles (not a combination tongue, whose motion is
  quasi-periodic), its amplitude against the run's.

Prints the tables docs/time-domain.md quotes.

    python benchmarks/engagement_agreement.py [--freq 10:230:56] [--pf 0.2,0.5,0.8]
"""

import argparse
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from sources import get_preset  # noqa: E402
from judder import api  # noqa: E402
from judder.commands._values import parse_grid, parse_list  # noqa: E402

PRESETS = ("paper-4dof", "paper-4dof-fitted")


def _run(preset, freq_hz, p_f_bar):
    s = api.simulate(freq_hz, p_f_bar,
                     parameters=get_preset(preset)).summaries[0]
    return {"preset": preset, "freq_hz": freq_hz, "p_f_bar": p_f_bar,
            "exponent": s["floquet_exponent_per_s"],
            "floquet_kind": s["floquet_kind"], "judder": s["judder"],
            "mechanism": s["mechanism"], "kind": s["judder_kind"],
            "growth": s["judder_growth_per_s"],
            "holds": s["linearisation_holds"],
            "rpm": s["oscillation_rpm"], "limit": s["judder_limit_rpm"],
            "orbit_rpm": s["orbit_settled_rpm"],
            "orbit_kind": s["orbit_kind"],
            "orbit_mechanism": s["orbit_mechanism"]}


def _by_exponent(rows, label):
    judder = [r for r in rows if r["exponent"] > 0.75]
    middle = [r for r in rows if 0 <= r["exponent"] <= 0.75]
    stable = [r for r in rows if r["exponent"] < 0]
    parametric = [r for r in judder if r["mechanism"] in ("parametric",
                                                          "both")]
    within = [r for r in parametric if r["growth"] is not None
              and abs(r["growth"] / r["exponent"] - 1) <= 0.3]
    print(f"| {label} | {len(judder)} | {len(parametric)} | {len(within)} | "
          f"{len(middle)} | {sum(r['judder'] for r in middle)} | "
          f"{len(stable)} | {sum(r['judder'] for r in stable)} | "
          f"{sum(r['mechanism'] == 'forced' for r in stable)} |")


def _against_orbit(rows, label):
    same = [r for r in rows if r["judder"] == (r["orbit_mechanism"]
                                               is not None)]
    mechanism = [r for r in rows if r["mechanism"] == r["orbit_mechanism"]]
    settled = [r for r in rows if r["orbit_kind"] != "combination"
               and r["rpm"] >= 3.0]
    within = [r for r in settled if abs(r["orbit_rpm"] / r["rpm"] - 1)
              <= 0.1]
    print(f"| {label} | {len(rows)} | {len(same)} | {len(mechanism)} | "
          f"{len(settled)} | {len(within)} |")


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
    print("| settings | exponent > 0.75 | parametric judder | growth "
          "within 30 % | 0 to 0.75 | judder | exponent < 0 | judder | "
          "of it forced |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    for preset in PRESETS:
        for holds, label in ((True, "forced swing within the linear range"),
                             (False, "forced swing beyond it")):
            _by_exponent([r for r in rows if r["preset"] == preset
                          and r["holds"] is holds], f"{preset}, {label}")
    print("\n| preset | runs | same verdict as the orbit | same mechanism | "
          "orbit settles, run >= 3 rpm | amplitude within 10 % |")
    print("| --- | --- | --- | --- | --- | --- |")
    for preset in PRESETS:
        _against_orbit([r for r in rows if r["preset"] == preset], preset)
    print("\njudder runs and the runs that differ from the orbit:")
    print("| preset | f (Hz) | p_f (bar) | Floquet | run | growth / "
          "exponent | run (rpm) | orbit (rpm) | orbit |")
    print("| --- | --- | --- | --- | --- | --- | --- | --- | --- |")
    for r in rows:
        if not (r["judder"] or r["orbit_mechanism"]):
            continue
        ratio = "-" if r["growth"] is None or r["exponent"] <= 0 else \
            f"{r['growth'] / r['exponent']:.2f}"
        run = (f"{r['mechanism']} ({r['kind']})" if r["judder"]
               else "no judder")
        print(f"| {r['preset']} | {r['freq_hz']:g} | {r['p_f_bar']:g} | "
              f"{r['floquet_kind']} {r['exponent']:+.2f} | {run} | {ratio} | "
              f"{r['rpm']:.3g} | {r['orbit_rpm']:.3g} | "
              f"{r['orbit_mechanism'] or 'no judder'} ({r['orbit_kind']}) |")


if __name__ == "__main__":
    main()
