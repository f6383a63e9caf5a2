"""The test bench's FMU: the bench engagement model a run needs.

The bench's parameters, its linearisation and its orbit model are read
from its ``Judder.Data`` records (:mod:`stability.bench`); only a run of
the bench (``simulate``, ``campaign``) builds its FMU, here.
"""

from infra.errors import JudderError

__all__ = ["bench_fmu", "refuse_bench_of_class"]


def bench_fmu(values):
    """The driveline's bench engagement model and its FMU (built if
    needed)."""
    from fmu.store import ensure_fmu
    from stability.bench import bench_class
    model_class = bench_class(values)
    return model_class, ensure_fmu(model_class)


def refuse_bench_of_class(values, names):
    """Bench parameters given with a Modelica class or an FMU, which has
    no bench model: refused, saying where its parameters go."""
    raise JudderError(f"`bench` {', '.join(names)} is not allowed with the "
                      f"class {values.model}; allowed: its parameters with "
                      "`changes` (the bench parameters belong to the bench "
                      "model)")
