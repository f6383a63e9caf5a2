"""``judder campaign``: bench emulator: engagement acquisitions over a
dither grid.
"""

from infra.errors import JudderError
from infra.files import check_folder_writable
from studies._preflight import check_campaign, check_campaign_disk, check_work
from studies.campaign import campaign

from ._arguments import model_options, workers_option
from ._model import parameters_of
from ._output import Progress, emit
from ._values import DURATION, SEED, Grid, Listed, Quantity

#: The command's --help text.
DESCRIPTION = (
    "Emulate a bench campaign (section 3): one engagement per dither "
    "frequency x amplitude x engine speed x oil temperature, speeds "
    "sampled by a 41-tooth pick-up (684 samples/s at 1000 rpm) with "
    "noise, pressure at 1 kHz; one CSV and/or MF4 per run and "
    "OUT/index.csv. Runs in parallel; an interrupted or failed campaign "
    "resumes when run again.")


OUTPUTS = ()


AMPLITUDE = "pf"


def check_campaign_folder(text):
    """A campaign folder: a non-empty path that is not a file, in a
    writable place."""
    if not str(text).strip():
        raise JudderError(f"--out {text!r}: allowed: a folder name (the "
                          "campaign folder, created if needed)")
    check_folder_writable(text, "--out", text)


def check_outputs(args, seen):
    """The campaign's --out is a folder (:func:`check_campaign_folder`)."""
    check_campaign_folder(args.out)


def add_arguments(p):
    """The options of ``judder campaign``."""
    p.add_argument("--freq", type=Grid("--freq", "Hz"),
                   default="70:130:31", metavar="START:STOP:N",
                   help="dither frequencies, Hz (default 70:130:31: "
                        "tongues 5, 2 and 6 of the paper's driveline)")
    p.add_argument("--pf", type=Grid("--pf", "bar"),
                   default="0.1:0.7:7", metavar="START:STOP:N",
                   help="dither amplitudes, bar (default 0.1:0.7:7)")
    p.add_argument("--rpm", type=Listed("--rpm", Quantity("--rpm", "rpm", 0.0,
                                                           low_open=True)),
                   default="1000", metavar="N1,N2",
                   help="engine (motor) speeds, rpm (default 1000; the "
                        "paper also used 1500)")
    p.add_argument("--temperatures", default="65-70", metavar="T1,T2|all",
                   help="oil temperature ranges (55-60, 65-70, 75-80, "
                        "85-90, or all): each run at the middle of its "
                        "range, the external damping scaled with the oil's "
                        "viscosity (pysim.simulation.campaigns.oil_viscosity)")
    p.add_argument("--duration", type=DURATION, default=3.0, metavar="S",
                   help="length of each engagement, s (default 3: the "
                        "0.6 s pressure ramp, then the judder's growth)")
    p.add_argument("--noise-rpm", type=Quantity("--noise-rpm", "rpm", 0.0),
                   default=0.5,
                   help="speed measurement noise, rpm (default 0.5)")
    p.add_argument("--seed", type=SEED, default=1, help="noise seed")
    p.add_argument("--format", default="csv,mf4", metavar="csv,mf4",
                   help="file formats per run (default both)")
    workers_option(p)
    p.add_argument("--out", required=True, metavar="DIR",
                   help="campaign folder (created; an existing campaign "
                        "there is resumed)")
    model_options(p, modelica=False)


def run(args):
    """Bench emulator: a campaign of engagement acquisitions."""
    from pysim.simulation.campaigns import TEMPERATURES
    freqs = args.freq
    amplitudes = args.pf
    if freqs[0] <= 0:
        raise JudderError("--freq: allowed: frequencies > 0 Hz")
    rpm = args.rpm
    temperatures = (list(TEMPERATURES) if args.temperatures == "all"
                    else [t.strip() for t in args.temperatures.split(",")])
    for option, values in (("--rpm", [f"{n:g}" for n in rpm]),
                           ("--temperatures", temperatures)):
        twice = next((v for i, v in enumerate(values) if v in values[:i]),
                     None)
        if twice is not None:
            raise JudderError(f"{option}: {twice} is given twice; allowed: "
                              "each value once (one run per setting)")
    formats = tuple(f.strip() for f in args.format.split(","))
    if not set(formats) <= {"csv", "mf4"} or not formats:
        raise JudderError(f"--format {args.format!r}: allowed: csv, mf4 or "
                          "csv,mf4")
    params, changes = parameters_of(args)
    runs = (len(freqs) * len(amplitudes) * len(rpm) * len(temperatures))
    check_work("--freq x --pf x --rpm x --temperatures", runs, "runs")
    check_campaign_disk(args.out, runs, args.duration, max(rpm), formats)
    check_campaign(runs, args.duration, max(rpm), args.workers)
    with Progress(runs, "bench runs") as progress:
        result = campaign(args.out, freqs, amplitudes, engine_rpm=rpm,
                          temperatures=temperatures,
                          duration=args.duration,
                          noise_rpm=args.noise_rpm, seed=args.seed,
                          formats=formats, parameters=params,
                          changes=changes, workers=args.workers,
                          progress=progress)
    data = result.as_dict()
    text = (f"{data['runs']} runs ({data['ok']} ok"
            + (f"; {data['reused']} already in the folder with the same "
               "settings, kept" if data["reused"] else "")
            + f") in {result.seconds:.1f} s; index {result.index}"
            + "".join(f"\n  failed {r['run_id']}: {r['message']}"
                      for r in result.failed))
    emit(args, data, text)
    if result.failed:
        raise JudderError(f"{len(result.failed)} runs failed; the others "
                          "were written (run the same command again to "
                          "retry)")
