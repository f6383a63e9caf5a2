"""Coverage of the fit's 95 % intervals on noisy boundaries (section 4.2).

Each boundary is made independently from its own truth: the fitted set
of section 4.2 (preset ``paper-4dof-fitted``) with each fitted parameter
scaled by a factor drawn from U(0.85, 1.15). Its lowest model boundary
(of judder growing at ``--min-growth``, default ``judder check``'s 1 1/s,
as the chart's verdict sees it) at the frequencies of ``--grid`` is
perturbed by ``--noise`` (3 %) multiplicative Gaussian noise; a point
above ``p_max`` (1.5 bar) is censored, as on the bench. With ``--step``
the onsets are found on a grid of amplitudes, as a chart finds them: each
noisy onset rounded up to the grid, with the amplitude tried below it
(:func:`on_grid`). Each boundary is
fitted from the preset's values with the defaults of ``judder fit``
(:func:`stability.fit.fit_boundary`). A boundary with too few onsets
for the parameters is refused by the fit, and counted apart. The script
prints one line per boundary (on stderr), then one JSON object with the
coverage of each parameter (how many of the 95 % intervals reported hold
the truth) and the fit times; it exits with 1 if a parameter is covered
by fewer than 90 % of them (18 of 20: the nominal 19 less about its
binomial standard deviation)::

    .venv/bin/python benchmarks/fit_coverage.py              # 20 boundaries
    .venv/bin/python benchmarks/fit_coverage.py --names c12,mu_g,k24
    .venv/bin/python benchmarks/fit_coverage.py --grid uniform --min-growth 0
    .venv/bin/python benchmarks/fit_coverage.py --step 0.1

``--write-example FILE`` writes ``examples/measured_boundary.csv``.
"""

import argparse
import json
import sys
import time

import numpy as np

from sources import get_preset
from infra.errors import JudderError
from stability.fit import fit_boundary, model_boundary

BAR = 1e5
TRUTH = "paper-4dof-fitted"
#: Each fitted parameter of a truth is the preset's times U(1 - s, 1 + s).
SPREAD = 0.15


def noisy_boundary(truth, freq_hz, p_max, noise, rng, min_growth):
    """The truth's lowest boundary with multiplicative Gaussian noise, Pa
    (NaN: censored, including points the noise pushed above p_max)."""
    clean = model_boundary(truth, freq_hz, p_max, min_growth=min_growth)
    noisy = clean * (1 + noise * rng.standard_normal(len(freq_hz)))
    return np.where(noisy > p_max, np.nan, noisy)


def on_grid(measured, step, p_max):
    """Onsets found on a grid of amplitudes ``step, 2 step, ...`` up to
    ``p_max`` (Pa): the lowest amplitude of the grid at or above each
    onset, and the one below it (NaN: censored, also where the grid's
    onset lies above ``p_max``)."""
    onset = np.ceil(measured / step - 1e-9) * step
    onset = np.where(onset > p_max * (1 + 1e-9), np.nan, onset)
    return onset, onset - step


#: Frequencies of examples/measured_boundary.csv, Hz: every 10 Hz over
#: the bench's range, every 2.5 Hz where tongue 2 and the combination
#: tongue come below 1.5 bar, as a test engineer refines a sweep where
#: judder appears.
EXAMPLE_FREQS = np.union1d(np.arange(60.0, 201.0, 10.0),
                           np.arange(95.0, 130.1, 2.5))


def write_example(path, seed=7, noise=0.03, p_max=1.5 * BAR):
    """Write examples/measured_boundary.csv: the preset's boundary of
    judder growing at check's 1 1/s at :data:`EXAMPLE_FREQS`, with
    ``noise`` multiplicative noise (``seed``), censored above ``p_max``."""
    from infra.criteria import DEFAULT_MIN_GROWTH_PER_S
    measured = noisy_boundary(get_preset(TRUTH), EXAMPLE_FREQS, p_max,
                              noise, np.random.default_rng(seed),
                              DEFAULT_MIN_GROWTH_PER_S)
    rows = ["freq_hz,p_f_bar,tried_bar"] + [
        f"{f:g}," + ("" if np.isnan(p) else f"{p / BAR:.4f}")
        + f",{p_max / BAR:g}" for f, p in zip(EXAMPLE_FREQS, measured)]
    with open(path, "w", encoding="utf-8") as out:
        out.write("\n".join(rows) + "\n")


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--boundaries", type=int, default=20)
    parser.add_argument("--truth", default=TRUTH,
                        help=f"preset the truths scatter about (default "
                        f"{TRUTH})")
    parser.add_argument("--first-seed", type=int, default=0)
    parser.add_argument("--grid", choices=("bench", "uniform"),
                        default="bench",
                        help="bench: the example boundary's frequencies "
                        "(every 10 Hz, every 2.5 Hz over 95-130 Hz); "
                        "uniform: --points over 60-200 Hz")
    parser.add_argument("--points", type=int, default=15)
    parser.add_argument("--noise", type=float, default=0.03)
    parser.add_argument("--pf-max", type=float, default=1.5, help="bar")
    parser.add_argument("--step", type=float, default=0.0,
                        help="bar: onsets found on a grid of amplitudes of "
                        "this step (default 0: as measured)")
    parser.add_argument("--names", default="mu_g,k24")
    parser.add_argument("--min-growth", type=float, default=None,
                        help="1/s (default: fit_boundary's)")
    parser.add_argument("--error-model", default=None,
                        help="default: fit_boundary's")
    parser.add_argument("--uncertainty", default=None,
                        help="default: fit_boundary's")
    parser.add_argument("--workers", type=int, default=1)
    parser.add_argument("--write-example", metavar="FILE.csv",
                        help="write examples/measured_boundary.csv's "
                        "boundary to FILE.csv and stop")
    args = parser.parse_args(argv)
    if args.write_example:
        write_example(args.write_example)
        return 0

    preset = get_preset(args.truth)
    names = tuple(args.names.split(","))
    freq = (EXAMPLE_FREQS if args.grid == "bench"
            else np.linspace(60.0, 200.0, args.points))
    p_max = args.pf_max * BAR
    options = {k: v for k, v in (("min_growth", args.min_growth),
                                 ("error_model", args.error_model),
                                 ("uncertainty", args.uncertainty))
               if v is not None}
    min_growth = options.get("min_growth",
                             fit_boundary.__kwdefaults__["min_growth"])
    inside = {n: 0 for n in names}
    refused, unsuccessful, seconds = [], [], []
    for seed in range(args.first_seed, args.first_seed + args.boundaries):
        rng = np.random.default_rng(seed)
        truth = preset.replace(**{n: preset[n] * rng.uniform(
            1 - SPREAD, 1 + SPREAD) for n in names})
        measured = noisy_boundary(truth, freq, p_max, args.noise, rng,
                                  min_growth)
        below = None
        if args.step:
            measured, below = on_grid(measured, args.step * BAR, p_max)
        began = time.perf_counter()
        try:
            result = fit_boundary(preset, freq, measured, p_max,
                                  names=names, seed=seed, below=below,
                                  workers=args.workers, curve_points=0,
                                  **options)
        except JudderError as error:
            refused.append(seed)
            print(f"boundary {seed}: refused: {error}", file=sys.stderr,
                  flush=True)
            continue
        seconds.append(time.perf_counter() - began)
        cells = []
        for name, value, low, high in zip(result.names, result.values,
                                          result.ci_low, result.ci_high):
            hit = bool(low <= truth[name] <= high)
            inside[name] += hit
            cells.append(f"{name} {truth[name]:.5g} -> {value:.5g} "
                         f"[{low:.5g}, {high:.5g}]{'' if hit else ' MISS'}")
        if not result.success:
            unsuccessful.append(seed)
        print(f"boundary {seed}: {int(np.sum(~np.isnan(measured)))} points "
              f"with judder, {seconds[-1]:.1f} s, {result.uncertainty}, "
              f"success {result.success}; " + "; ".join(cells),
              file=sys.stderr, flush=True)
        for problem in result.problems:
            print(f"    {problem}", file=sys.stderr)
    print(json.dumps({
        "name": "fit-coverage-95", "truth": args.truth,
        "boundaries": args.boundaries, "grid": args.grid,
        "points": len(freq),
        "noise": args.noise, "step_bar": args.step, "names": names,
        "min_growth": min_growth,
        "coverage": {n: f"{inside[n]}/{len(seconds)}" for n in names},
        "refused_boundaries": refused,
        "unsuccessful_boundaries": unsuccessful,
        "seconds_median": round(float(np.median(seconds)), 2),
        "seconds_max": round(float(np.max(seconds)), 2)}))
    return 0 if all(inside[n] >= 0.9 * len(seconds) for n in names) \
        else 1


if __name__ == "__main__":
    sys.exit(main())
