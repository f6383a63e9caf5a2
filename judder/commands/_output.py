"""What a command writes: its output files checked before any work (a
folder, an unknown format, a file judder did not write), written
atomically after it, and the text or JSON it prints.
"""

from pathlib import Path
import sys

from infra.errors import JudderError
from infra.files import all_or_none, check_output, save_figure, to_json
from infra.provenance import (
    Provenance,
    current,
    file_digest,
    input_digest,
    tool_version,
)

#: Options that do not change a result: how it is shown, where it is
#: written (``out`` also of a folder, a checkpoint resumed or not), how
#: the work is spread; the outputs' own options are added.
NOT_INPUTS = {"handler", "outputs", "output_check", "read_too", "amplitude",
              "flags",
              "version", "json", "force", "workers", "scheduler", "out",
              "checkpoint"}


def written(*paths):
    return "".join(f"\nwrote {p}" for p in paths if p)


def output_files(**paths):
    return {name: (None if path is None else str(path))
            for name, path in paths.items()}


def write_outputs(args, result, save=None, figure=None):
    """Write --out (``result.save``) and --plot (``result.figure``),
    atomically, both or neither (:func:`infra.files.all_or_none`);
    keyword arguments for each; returns their paths."""
    with all_or_none():
        if args.out:
            result.save(args.out, force=args.force, **(save or {}))
        if args.plot:
            save_plot(args.plot, result.figure(**(figure or {})))
    return output_files(out=args.out, plot=args.plot)


def save_plot(path, figure):
    """Save a figure the command drew, then free it (``main`` may run
    many commands in one process)."""
    import matplotlib.pyplot as plt
    try:
        save_figure(path, figure)
    finally:
        plt.close(figure)


def _figure_formats():
    from matplotlib.backend_bases import FigureCanvasBase
    return set(FigureCanvasBase.get_supported_filetypes())


def check_outputs(args):
    """Refuse every output of the command before any work: a folder, a
    parent that is a file, an unwritable folder, an unknown format, or a
    file judder did not write (unless --force); see
    :func:`infra.files.check_output`. A command's own checks
    (``check_outputs(args, seen)`` of its module, ``seen`` the resolved
    paths of its outputs) follow."""
    force = getattr(args, "force", False)
    seen = {}
    for attribute, option, suffixes in args.outputs:
        path = getattr(args, attribute, None)
        if path is None:
            continue
        check_output(path, option, suffixes or _figure_formats(), force)
        key = Path(path).resolve()
        if key in seen:
            raise JudderError(f"{option} {path} is also given as "
                              f"{seen[key]}; allowed: a different file for "
                              "each output")
        seen[key] = option
    if args.output_check is not None:
        args.output_check(args, seen)


def provenance_of(args):
    """The tool's version and the digest of a command's inputs
    (:func:`infra.provenance.input_digest`): its options but those of
    :data:`NOT_INPUTS` and its outputs. The small text files the options
    name (:data:`studies.inputs.TEXT_INPUTS`, a ``period:`` file) are
    checked by size and type first (:func:`studies.inputs.check_input`):
    a folder or a huge file is refused before any of it is hashed."""
    skip = NOT_INPUTS | {attribute for attribute, _, _ in args.outputs}
    options = {name: value for name, value in vars(args).items()
               if name not in skip}
    _check_text_inputs(options)
    if getattr(args, "read_too", None) is not None:
        # the files the command reads that no option names (an index's
        # acquisitions): their bytes, under the names that list them
        options["read_too"] = {name: file_digest(path) for name, path in
                               args.read_too(args).items()}
    # the command's name is an input like its options
    return Provenance(tool_version(),
                      input_digest(options.pop("command"), options))


def _check_text_inputs(options):
    """Refuse a text input that is no small regular file, by its size
    and type, before the digest reads it."""
    from studies.inputs import TEXT_INPUTS, check_input
    for name, value in options.items():
        values = value if isinstance(value, (list, tuple)) else [value]
        for one in values:
            if not isinstance(one, (str, Path)) or not str(one):
                continue
            if name in TEXT_INPUTS:
                check_input(one, "FILE" if name == "files" else
                            "--" + name.replace("_", "-"))
            elif str(one).startswith("period:") and str(one)[7:]:
                check_input(str(one)[7:], "--dither-wave period:")


def emit(args, data, text):
    """Print ``data`` as JSON with --json (with ``provenance``: the
    version and the input digest), else ``text``, its arguments in the
    command's options (:func:`judder.commands._flags.in_flags`)."""
    from ._flags import in_flags
    if args.json and isinstance(data, dict):
        data = {**data, "provenance": current().as_dict()}
    print(to_json(data) if args.json
          else in_flags(text, getattr(args, "flags", None)))


def make_parents(*paths):
    for path in paths:
        if path is not None:
            Path(path).parent.mkdir(parents=True, exist_ok=True)


class Progress:
    """tqdm bar on stderr (shown on a terminal only) as a map callback."""

    def __init__(self, total, description):
        from tqdm import tqdm
        self._bar = tqdm(total=total, desc=description, unit="freq",
                         disable=None, file=sys.stderr)

    def __enter__(self):
        return self._update

    def _update(self, done, total):
        if self._bar.total != total:
            self._bar.total = total
        self._bar.update(done - self._bar.n)

    def __exit__(self, *exc):
        self._bar.close()
        return False
