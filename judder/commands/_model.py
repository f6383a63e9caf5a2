"""The parameter set a command's model options select.

``--model``, ``--preset``, ``--param-file`` and ``--set``, or a driveline
of one's own (``--modelica``, ``--fmu``), turned into a parameter set and
its explicit changes (:func:`parameters_of`), its title on figures, and
the warning when the dither amplitude reaches the mean pressure.
"""

import numpy as np

from infra.errors import JudderError
from infra.quantities import parse_quantity
from infra.units import PA_PER_BAR
from studies.bench import refuse_bench_of_class
from studies.inputs import friction_of, load_parameters, read_input

from ._values import check_file_pressure, check_plain_pressure, check_pressures


def parameters_of(args, dithered=True):
    """Base parameter set and explicit changes of a command's options
    (``dithered``: the command linearises the dither, see
    :func:`own_driveline`).

    Returns
    -------
    params : drivelines.Parameters, ModelicaParameters or FmuParameters
        From --fmu, --modelica, --param-file, --preset or --model.
    changes : dict
        The --set values, validated (SI).
    """
    params = (own_driveline(args, args.param_file, "--param-file",
                            dithered)
              or load_parameters(preset=args.preset, model=args.model,
                                 param_file=args.param_file))
    changed = params.with_overrides(args.set)
    names = [text.partition("=")[0].strip() for text in args.set]
    if args.param_file:
        check_file_pressure(params, args.param_file)
    for text in args.set:
        check_plain_pressure(text)
    if args.friction not in (None, "bounded"):
        fixed = sorted({"mu0", "mu_g"} & set(names))
        if fixed and args.friction != "straight":
            raise JudderError(f"--set {fixed[0]} is not allowed with "
                              f"--friction {args.friction}; allowed: the "
                              "table's own value and slope at the bench's "
                              "slip (give another table)")
        friction = friction_of(changed, args.friction, args.oil_temp,
                               getattr(args, "decimal", None))
        return friction, {name: friction[name] for name in names}
    if args.oil_temp is not None:
        friction_of(params, args.friction, args.oil_temp)   # refuses
    return params, {name: changed[name] for name in names}


def parameter_file(args, path, option):
    """The parameter set of a file of ``judder params --save`` for the
    model the options select (``--also`` of ``advise``): a preset's
    file, or with --modelica/--fmu a file of ``judder params --modelica
    CLASS --save`` (``--fmu FILE.fmu --save``)."""
    from sources import load_toml
    return own_driveline(args, path, option) or load_toml(
        read_input(path, option), source=str(path))


def own_driveline(args, path=None, option="--param-file", dithered=True):
    """The parameter set of ``--fmu FILE.fmu`` (docs/fmu-path.md) or
    ``--modelica CLASS [--library DIR]`` (docs/onemodel.md), with the
    values of the file ``path`` if given; None if neither is given.
    With ``dithered`` (every command but ``params``) a class that
    certainly lacks the dither's parameters is refused from its source,
    before the flatten."""
    refused = getattr(args, "refused_fmu", None)
    if refused is not None:     # a command that runs the time domain
        from studies.timedomain import fmu_refusal
        raise fmu_refusal(args.fmu_refused_by, refused)
    fmu, modelica = getattr(args, "fmu", None), getattr(args, "modelica", None)
    for flag, given, allowed in (
            ("--fmu", fmu, "a .fmu file"),
            ("--modelica", modelica, "a full class name, e.g. "
                                     "Judder.Examples.Driveline5DOFGeared")):
        if given is not None and not given.strip():
            raise JudderError(f"{flag} {given!r} is empty; allowed: "
                              f"{allowed}")
    if fmu:
        from sources.fmus import FmuParameters
        flag, given = "--fmu", fmu
        replaced = ("modelica", "library", "model", "preset")
    elif modelica:
        from sources.modelica import ModelicaParameters
        flag, given = "--modelica", modelica
        replaced = ("model", "preset")
    else:
        # options of a class or an FMU given without one were ignored
        for flag, given, owner in (
                ("--library", getattr(args, "library", None),
                 "a --modelica class"),
                ("--dither-amplitude",
                 getattr(args, "dither_amplitude", "p_f") != "p_f",
                 "a --modelica class or an --fmu"),
                ("--dither-frequency",
                 getattr(args, "dither_frequency", "f_dither")
                 != "f_dither", "a --modelica class or an --fmu")):
            if given:
                raise JudderError(f"{flag} is for {owner}; allowed: no "
                                  f"{flag} with a preset or a parameter "
                                  "file")
        return None
    for name in replaced:
        if getattr(args, name, None) is not None:
            raise JudderError(f"{flag} {given} replaces "
                              f"--{name.replace('_', '-')}; give one")
    names = {"amplitude": args.dither_amplitude,
             "frequency": args.dither_frequency}
    # every --library, in order (a tuple: the compiled class is cached
    # per class and library)
    library = tuple(args.library) if args.library else None
    if modelica and dithered:
        from sources.modelica import check_dither_declared
        check_dither_declared(modelica, library, **names)
    base = (FmuParameters(fmu, **names) if fmu else
            ModelicaParameters(modelica, library, **names))
    if path is None:
        return base
    return base.replace(**_file_values(path, option, base.model,
                                       f"{flag} {given}"))


def _file_values(path, option, model, selected):
    """The ``[parameters]`` of a file of ``judder params --save`` whose
    ``model`` is ``model``."""
    import tomllib
    try:
        table = tomllib.loads(read_input(path, option))
    except tomllib.TOMLDecodeError as exc:
        raise JudderError(f"{option} {path}: not TOML ({exc})") from None
    if table.get("model") != model or \
            not isinstance(table.get("parameters"), dict):
        raise JudderError(
            f"{option} {path}: model = {table.get('model')!r} is not "
            f"{model!r} of {selected} (or the [parameters] table is "
            f"missing); allowed: a file of `judder params {selected} "
            "--save`")
    return _flat(table["parameters"])


def _flat(table, prefix=""):
    """TOML reads ``housing.phi0 = 0`` as a table; back to dotted names."""
    flat = {}
    for key, value in table.items():
        if isinstance(value, dict):
            flat.update(_flat(value, f"{prefix}{key}."))
        else:
            flat[f"{prefix}{key}"] = value
    return flat


def model_title(args, params):
    """The model and every change the options made, for figure titles:
    ``'4dof, paper-4dof-fitted, c12=20'``."""
    source = (getattr(args, "param_file", None)
              or getattr(args, "preset", None)
              or ("start values of the FMU" if getattr(args, "fmu", None)
                  else "defaults of the class"
                  if getattr(args, "modelica", None) else "paper preset"))
    changes = [text.replace(" ", "") for text in getattr(args, "set", [])]
    return ", ".join([f"{params.model} driveline", str(source)] + changes)


def check_plausible(args):
    """Warn when the command's largest dither amplitude reaches the mean
    pressure of its parameter set (see :func:`check_pressures`)."""

    if args.amplitude is None:
        return
    value = getattr(args, args.amplitude, None)
    if value is None:
        return
    p_max_bar = float(np.max(value))
    params, _ = parameters_of(args)
    check_pressures(p_max_bar * PA_PER_BAR, params,
                    "--pf" if args.amplitude == "pf" else "--pf-max")


def parse_bench(assignments, values):
    """The ``--bench NAME=VALUE`` texts as SI numbers, by the units the
    bench declares (``w_motor=1000rpm``, ``p_load=9.8bar``).

    The ranges are checked by :func:`check_bench`, where the API takes
    the values.
    """
    names = [text.partition("=")[0].strip() for text in assignments]
    if assignments and not values.source_kind.is_chain:
        refuse_bench_of_class(values, names)
    from stability.bench import bench_parameters
    parameters = bench_parameters(values) if assignments else {}
    bench = {}
    for text, name in zip(assignments, names):
        _, sep, value = text.partition("=")
        if not sep or name not in parameters:
            raise JudderError(f"--bench {text!r} is not allowed; allowed: "
                              "NAME=VALUE with NAME one of "
                              f"{', '.join(parameters)}")
        bench[name] = parse_quantity(value.strip(), parameters[name].unit,
                                     f"--bench {name}")
    return bench
