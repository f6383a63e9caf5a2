"""One verdict in every view: check, map, orbit, simulate and a campaign
chart at the same dither settings (issue 41).

For each preset a grid of dither settings (irregular frequencies over
60-220 Hz, the bench's f1 region and tongue 3, by eight amplitudes over
0.05-0.8 bar, drawn from ``--seed`` so the settings are not the ones the
tests pin) is judged by

* ``judder check`` (the bench, its default for a preset): verdict and
  mechanism from the bench's orbit, or its settled quasi-periodic motion;
* ``judder map`` (the bench): growth of the linearisation and its linear
  forced response; where the dither's forced slip swing leaves the
  friction curve's linear range the map says so, and such points are
  counted apart (the linear view cannot judge them);
* ``judder orbit``: the periodic orbit's verdict (the settled motion in
  combination tongues);
* ``judder simulate``: the 4 s held-slip bench run (FMU), judged as a
  bench run;
* ``judder campaign`` + ``judder chart``: the same runs recorded as bench
  acquisitions (tooth-sampled speeds, noise) and charted.

Prints the agreement of verdict and mechanism, and the settled amplitudes
of orbit and simulate side by side (within 10 %), then the settings that
disagree. ``--json FILE`` writes every row.

    python benchmarks/one_verdict.py [--seed 7] [--json rows.json]
"""

import argparse
import json
import sys
import tempfile
import time
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))

from infra.criteria import MECHANISMS  # noqa: E402
from judder import api  # noqa: E402
from sources import get_preset  # noqa: E402

PRESETS = ("paper-4dof", "paper-4dof-fitted")
#: Views compared; ``map`` only where it is within its linear range.
VIEWS = ("check", "map", "orbit", "simulate", "chart")


def settings(seed):
    """Frequencies (Hz) and amplitudes (bar) of the grid, per preset."""
    rng = np.random.default_rng(seed)
    freqs = np.concatenate([
        rng.uniform(60, 220, 12), rng.uniform(14.0, 19.0, 4),
        rng.uniform(31.0, 36.0, 4)])
    amplitudes = np.sort(rng.uniform(0.05, 0.8, 8))
    return np.round(np.sort(freqs), 2), np.round(amplitudes, 3)


def _word(judder, mechanism):
    return "no judder" if not judder else f"judder ({mechanism})"


def judge(preset, freqs, amplitudes, folder):
    """Rows of every view at every setting of the grid."""
    params = get_preset(preset)
    pairs = [(f, p) for f in freqs for p in amplitudes]
    rows = {pair: {"preset": preset, "freq_hz": pair[0],
                   "p_f_bar": pair[1]} for pair in pairs}
    started = time.perf_counter()
    checked = api.check([f for f, _ in pairs], [p for _, p in pairs],
                        params, sensitivity=())
    for pair, record in zip(pairs, checked.records()):
        rows[pair]["check"] = _word(record["verdict"] == "JUDDER",
                                    record["mechanism"])
        rows[pair]["check_settled_rpm"] = record["settled_amplitude_rpm"]
    shown = api.stability_map(freqs, amplitudes, params)
    judder, mechanism = shown.verdicts()
    beyond = shown.beyond_linear_range()
    for i, f in enumerate(freqs):
        for j, p in enumerate(amplitudes):
            rows[f, p]["map"] = _word(judder[i, j],
                                      MECHANISMS[mechanism[i, j]])
            rows[f, p]["map_beyond_linear_range"] = bool(beyond[i, j])
    for f in freqs:
        result = api.orbit([f], list(amplitudes), params)
        for row in result.rows():
            pair = (f, min(amplitudes, key=lambda p: abs(p - row["p_f_bar"])))
            rows[pair]["orbit"] = _word(row["judder"], row["mechanism"])
            rows[pair]["orbit_settled_rpm"] = row["settled_rpm"]
    for pair in pairs:
        run = api.simulate(pair[0], pair[1], parameters=params).summaries[0]
        rows[pair]["simulate"] = _word(run["judder"], run["mechanism"])
        rows[pair]["simulate_rpm"] = run["oscillation_rpm"]
    api.campaign(folder, list(freqs), list(amplitudes), duration=4.0,
                 formats=("csv",), parameters=params)
    chart = api.chart([folder])
    for run in chart.chart.read:
        a = run.analysis
        pair = (min(freqs, key=lambda f: abs(f - a.freq_hz)),
                min(amplitudes, key=lambda p: abs(p - a.p_f_bar)))
        rows[pair]["chart"] = _word(a.judder, a.mechanism)
    print(f"{preset}: {len(pairs)} settings in "
          f"{time.perf_counter() - started:.0f} s", file=sys.stderr)
    return list(rows.values())


def agreement(rows):
    """Counts of agreement, printed."""
    linear = [r for r in rows if not r["map_beyond_linear_range"]]
    agree = [r for r in rows
             if len({r[v] for v in VIEWS if v != "map"
                     or not r["map_beyond_linear_range"]}) == 1]
    verdict_agree = [r for r in rows
                     if len({r[v].startswith("judder") for v in VIEWS
                             if v != "map"
                             or not r["map_beyond_linear_range"]}) == 1]
    sized = [r for r in rows if max(r["orbit_settled_rpm"],
                                    r["simulate_rpm"]) >= 5.0]
    close = [r for r in sized if abs(r["orbit_settled_rpm"]
                                     - r["simulate_rpm"])
             <= 0.1 * r["simulate_rpm"]]
    print(f"settings: {len(rows)}; the map within its linear range at "
          f"{len(linear)} (beyond it the map says so and is left out)")
    print(f"verdict agrees in every view: {len(verdict_agree)} of "
          f"{len(rows)} ({100 * len(verdict_agree) / len(rows):.1f} %)")
    print(f"verdict and mechanism agree in every view: {len(agree)} of "
          f"{len(rows)} ({100 * len(agree) / len(rows):.1f} %)")
    for view in VIEWS:
        pairs = [r for r in rows if view != "map"
                 or not r["map_beyond_linear_range"]]
        same = sum(r[view] == r["simulate"] for r in pairs)
        print(f"  {view:9s} = simulate: {same} of {len(pairs)}")
    print(f"settled amplitude, orbit against simulate within 10 %: "
          f"{len(close)} of {len(sized)} settings with 5 rpm or more "
          f"({100 * len(close) / max(len(sized), 1):.1f} %)")
    print("disagreements:")
    for r in rows:
        if r not in agree:
            print(f"  {r['preset']} {r['freq_hz']:g} Hz {r['p_f_bar']:g} "
                  "bar: " + "; ".join(
                      f"{v} {r[v]}" for v in VIEWS)
                  + f"; orbit {r['orbit_settled_rpm']:.1f} rpm, run "
                    f"{r['simulate_rpm']:.1f} rpm"
                  + (" (map beyond its linear range)"
                     if r["map_beyond_linear_range"] else ""))


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--seed", type=int, default=7,
                        help="seed of the settings (default 7)")
    parser.add_argument("--json", metavar="FILE",
                        help="write every row as JSON")
    args = parser.parse_args(argv)
    freqs, amplitudes = settings(args.seed)
    rows = []
    with tempfile.TemporaryDirectory() as folder:
        for preset in PRESETS:
            rows += judge(preset, freqs, amplitudes,
                          Path(folder) / preset)
    agreement(rows)
    if args.json:
        Path(args.json).write_text(json.dumps(rows, indent=1))


if __name__ == "__main__":
    main()
