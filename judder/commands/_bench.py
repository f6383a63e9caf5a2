"""The ``--bench NAME=VALUE`` values of ``simulate`` and ``fit``: the
bench parameters, their units and allowed ranges (the bench itself:
:mod:`judder.bench`)."""


from infra.errors import JudderError

from ._values import option_value

#: Bench parameters of ``simulate --bench``: unit and allowed range
#: (low, high, low_open, integer).
BENCH_PARAMETERS = {
    "w_motor": ("rad/s", 0.0, 2e3, True, False),
    "w_gearbox": ("rad/s", 0.0, 2e3, False, False),
    "w_op": ("rad/s", 0.0, 2e3, False, False),
    "delta_mu": ("1", 0.0, 1.0, True, False),
    "t_engage": ("s", 0.0, 3600.0, False, False),
    "t_ramp": ("s", 0.0, 3600.0, True, False),
    "p_load": ("Pa", 0.0, 1e8, False, False),
    "load_share": ("1", 0.0, 10.0, False, False),
    "N_c_load": ("1", 1.0, 100.0, False, True),
    "d_control": ("N m s/rad", 0.0, 1e7, False, False),
}


def bench_values(assignments):
    """``NAME=VALUE`` strings of --bench, checked against
    :data:`BENCH_PARAMETERS` (SI, or with a unit: w_motor=1000rpm)."""
    values = {}
    for text in assignments:
        name, sep, value = text.partition("=")
        name = name.strip()
        if not sep or name not in BENCH_PARAMETERS:
            raise JudderError(f"--bench {text!r} is not allowed; allowed: "
                              "NAME=VALUE with NAME one of "
                              f"{', '.join(BENCH_PARAMETERS)}")
        unit, low, high, low_open, integer = BENCH_PARAMETERS[name]
        number = option_value(value, f"--bench {name}", unit, low, high,
                              low_open)
        if integer and number != int(number):
            raise JudderError(f"--bench {text!r} is not allowed; allowed: a "
                              f"whole number from {low:g} to {high:g}")
        values[name] = number
    return values












