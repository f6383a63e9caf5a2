"""The ``judder`` commands, one module each, registered in :data:`COMMANDS`.

A command module holds its command line: ``DESCRIPTION`` (its
``--help`` text), ``OUTPUTS`` (the files it writes: option attribute,
option, suffixes; ``None`` for a figure; checked before any work),
optionally ``AMPLITUDE`` (the option holding its largest dither
amplitude, checked against the mean pressure) and ``check_outputs(args,
seen)`` (checks of its own outputs), ``add_arguments(parser)`` (its
options, parsed once with their units by argparse ``type=``), ``run(args)``
(the options turned into a study's arguments, the study called, its
``--out``/``--plot`` written and its text or JSON printed). The study
itself, the function and the result it returns, is :mod:`studies`.

:data:`COMMANDS` is the one place a command is added: the command line
(:mod:`judder.cli`) makes its subcommands and ``--help`` from it. Nothing here imports a
command module: ``judder --help`` lists the commands from this table
alone, and ``judder map`` imports the map's module only.

Modules whose names start with ``_`` are shared by the commands: option
groups and value parsers (``_arguments``, ``_values``), the options that
carry the studies' arguments in their messages (``_flags``), the
parameter set the model options select (``_model``) and outputs
(``_output``).
"""

from dataclasses import dataclass
from importlib import import_module

__all__ = ["Command", "COMMANDS", "command_module"]


@dataclass(frozen=True)
class Command:
    """One ``judder`` command.

    Attributes
    ----------
    name : str
        The subcommand, and the module ``judder.commands.<name>``.
    function : str
        The study it runs (a key of :data:`studies.STUDIES`).
    summary : str
        One line for ``judder --help``.
    """

    name: str
    function: str
    summary: str


#: Every command, in the order of ``judder --help``.
COMMANDS = {c.name: c for c in (
    Command("params", "params", "show, or save as TOML, a parameter set"),
    Command("eig", "eig", "natural frequencies and damping factor"),
    Command("floquet", "floquet", "Floquet multipliers at one point"),
    Command("map", "stability_map",
            "stability map over frequency x amplitude"),
    Command("check", "check", "is a dither setting safe, and by how much"),
    Command("advise", "advise", "safe dither windows and the design change "
                                "that clears the dither range"),
    Command("tongues", "tongues", "tongue boundaries, labels and tips"),
    Command("compare", "compare", "two parameter sets side by side: "
                                  "frequencies, tips, windows, verdicts"),
    Command("sensitivity", "sensitivity",
            "tongue shifts per parameter (Fig. 17, 18)"),
    Command("threshold", "threshold",
            "friction-gradient threshold without dither (Fig. 19)"),
    Command("fit", "fit",
            "fit parameters to a measured boundary (section 4.2)"),
    Command("simulate", "simulate", "bench engagement with dither (Fig. 7, "
                                    "8), run through the FMU"),
    Command("orbit", "orbit", "periodic orbit of a dithered engagement, "
                              "its stability and the predicted chart"),
    Command("crosscheck", "crosscheck",
            "FMU growth rates against Floquet exponents"),
    Command("campaign", "campaign", "bench emulator: engagement "
                                    "acquisitions over a dither grid"),
    Command("chart", "chart", "experimental stability chart from bench "
                              "acquisitions (Fig. 10, 11)"),
    Command("report", "report", "one HTML file with the paper's figures "
                                "and tables for a driveline"),
    Command("envelope", "envelope", "broadest unstable region over "
                                    "uncertain parameters (Fig. 16)"),
)}



def command_module(name):
    """The module of command ``name`` (imported on first use)."""
    return import_module(f"{__name__}.{COMMANDS[name].name}")
