"""Census of ``Modelica.Mechanics.Rotational.Examples`` from the user's MSL.

Builds each of the 17 examples to an FMI 2.0 FMU with ``python -m fmu``
from the unmodified Modelica Standard Library (``--msl``, default
``../shared/msl``), then runs it with fmpy as Model Exchange and as
Co-Simulation to its experiment's StopTime (relative tolerance 1e-8).
Prints one row per example and the count that build and run to the end
(issue 43 asks for at least 16 of 17); ``--json FILE`` writes the rows.

Run: ``.venv/bin/python benchmarks/msl_census.py [--msl DIR] [--json FILE]``.
"""

import argparse
import json
from pathlib import Path
import subprocess
import sys
import tempfile
import time

ROOT = Path(__file__).resolve().parents[1]

#: The examples of MSL 4.x's Modelica.Mechanics.Rotational.Examples.
EXAMPLES = ("First", "FirstGrounded", "Friction", "CoupledClutches",
            "LossyGearDemo1", "LossyGearDemo2", "LossyGearDemo3",
            "ElasticBearing", "Backlash", "RollingWheel", "HeatLosses",
            "SimpleGearShift", "EddyCurrentBrake", "GenerationOfFMUs",
            "OneWayClutch", "OneWayClutchDisengaged", "CompareBrakingTorque")


def census_row(name, msl, folder):
    """Build one example and run it both ways: a dict of what happened."""
    import fmpy
    started = time.perf_counter()
    built = subprocess.run(
        [sys.executable, "-m", "fmu",
         f"Modelica.Mechanics.Rotational.Examples.{name}", "--library",
         str(msl), "--out", str(folder), "--fmi", "2.0"],
        capture_output=True, text=True, cwd=ROOT)
    row = {"name": name, "built": built.returncode == 0,
           "build_s": round(time.perf_counter() - started, 1)}
    if not row["built"]:
        lines = built.stderr.strip().splitlines()
        row["error"] = lines[-1][:300] if lines else ""
        return row
    path = folder / f"{name}.fmu"
    experiment = fmpy.read_model_description(path).defaultExperiment
    stop = float(experiment.stopTime) if experiment and \
        experiment.stopTime else 1.0
    row["stop_s"] = stop
    for kind in ("ModelExchange", "CoSimulation"):
        try:
            result = fmpy.simulate_fmu(path, fmi_type=kind, stop_time=stop,
                                       relative_tolerance=1e-8)
            reached = float(result["time"][-1])
            row[kind] = "ran" if reached >= stop * (1 - 1e-9) else \
                f"stopped at {reached:g} s"
        except Exception as exc:     # fmpy raises plain Exceptions
            row[kind] = f"failed: {str(exc)[:150]}"
    return row


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--msl", default=str(ROOT.parent / "shared" / "msl"),
                        help="folder holding the Modelica package "
                             "(default ../shared/msl)")
    parser.add_argument("--json", help="write the rows to this file")
    args = parser.parse_args(argv)
    msl = Path(args.msl)
    if not (msl / "Modelica").is_dir():
        parser.error(f"--msl {msl}: no Modelica package there; allowed: "
                     "the folder that holds Modelica/ (MSL 4.x)")
    rows = []
    with tempfile.TemporaryDirectory(prefix="msl-census-") as folder:
        for name in EXAMPLES:
            row = census_row(name, msl, Path(folder))
            rows.append(row)
            print(json.dumps(row), flush=True)
    running = [r["name"] for r in rows if r.get("ModelExchange") == "ran"
               and r.get("CoSimulation") == "ran"]
    print(f"build and run to StopTime (ME and CS): {len(running)} of "
          f"{len(rows)}; not: "
          + ", ".join(r["name"] for r in rows if r["name"] not in running))
    if args.json:
        Path(args.json).write_text(json.dumps(rows, indent=1))


if __name__ == "__main__":
    main()
