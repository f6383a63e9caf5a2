"""Which equations or variables make a model unbalanced, and where.

rumoca refuses an unbalanced model with counts only ("unbalanced model:
16 equations, 15 unknowns"). :func:`explain_unbalanced` flattens a probe
that ``extends`` the model and adds as many free variables (too many
equations) or determined ones (too few) as the counts differ by, so that
rumoca accepts it, and reads the probe's incidence: a maximum matching of
equations to unknowns (the derivatives of the states and the algebraic
variables) leaves the excess unmatched, and the alternating paths from
it give the over-determined equations or the under-determined variables
(the Dulmage-Mendelsohn parts), each with its file and line. Where
rumoca counts Integer or Boolean unknowns, which the back end does not
compile, the message says so instead.
"""

import re
import tempfile
from pathlib import Path

import casadi
import numpy as np
from scipy.sparse import csr_matrix
from scipy.sparse.csgraph import maximum_bipartite_matching

from infra.errors import JudderError

__all__ = ["excess", "explain_unbalanced"]

_UNBALANCED = re.compile(r"unbalanced model: (\d+) equations, (\d+) unknowns")
_PROBE = "JudderBalanceProbe"
#: Equations or variables listed in a message at most.
_SHOWN = 12


def excess(incidence):
    """The over- and under-determined parts of a bipartite incidence.

    Parameters
    ----------
    incidence : array_like of bool, shape (equations, unknowns)

    Returns
    -------
    over, under : list of int
        Equations reachable by alternating paths from the equations a
        maximum matching leaves unmatched, and unknowns reachable from the
        unmatched unknowns (both empty for a structurally regular system).
    """
    incidence = np.asarray(incidence, dtype=bool)
    rows, cols = incidence.shape
    if rows == 0 or cols == 0:
        return list(range(rows)), list(range(cols))
    match = maximum_bipartite_matching(csr_matrix(incidence.astype(float)),
                                       perm_type="column")
    owner = np.full(cols, -1)
    owner[match[match >= 0]] = np.flatnonzero(match >= 0)
    over = _reachable(np.flatnonzero(match < 0), lambda row: [
        owner[c] for c in np.flatnonzero(incidence[row]) if owner[c] >= 0])
    under = _reachable(np.flatnonzero(owner < 0), lambda col: [
        match[r] for r in np.flatnonzero(incidence[:, col]) if match[r] >= 0])
    return over, under


def _reachable(starts, step):
    """Sorted nodes reached from ``starts`` by ``step(node) -> nodes``."""
    seen, pending = set(), list(starts)
    while pending:
        node = pending.pop()
        if node not in seen:
            seen.add(node)
            pending += step(node)
    return sorted(int(n) for n in seen)


def explain_unbalanced(message, model_name, roots, load_flat_model):
    """The equations or variables in excess, if ``message`` is rumoca's
    refusal of an unbalanced model; otherwise (or if the probe cannot be
    read) ``""``.

    ``load_flat_model`` is the front end's
    (:func:`fmu.frontend.load_flat_model`), which calls this function when
    rumoca refuses a model: passed in, so that this module stays below the
    front end."""
    found = _UNBALANCED.search(message)
    if not found:
        return ""
    difference = int(found.group(1)) - int(found.group(2))
    if difference == 0:
        return ""
    with tempfile.TemporaryDirectory(prefix="judder-balance-") as tmp:
        probe = Path(tmp) / f"{_PROBE}.mo"
        probe.write_text(_probe_source(model_name, difference))
        try:
            flat = load_flat_model(probe, _PROBE, [*roots, tmp], cache=False,
                                   hybrid=True)
        except JudderError as exc:    # the front end's FrontEndError
            # rumoca's count may be wrong where the back end would refuse
            # the model anyway (MSL's Clutch: Boolean modes with pre())
            return "" if str(probe) in str(exc) else \
                f"; balanced or not, the FMU back end refuses it: {exc}"
        return _describe(flat, difference, str(probe))


def _probe_source(model_name, difference):
    count = abs(difference)
    names = [f"judder_probe{k + 1}" for k in range(count)]
    lines = [f"model {_PROBE}", f"  extends {model_name};"]
    lines += [f"  Real {name};" for name in names]
    if difference < 0:   # too few equations: each probe adds one net
        lines.append("equation")
        for name in names:
            lines += [f"  {name} = 0;", f"  2*{name} = 0;"]
    lines.append(f"end {_PROBE};")
    return "\n".join(lines) + "\n"


def _describe(flat, difference, probe_file):
    unknowns = [(v.derivative if v.role == "state" else v.symbol, v)
                for v in flat.variables
                if v.role in ("state", "algebraic", "output")
                and not v.name.startswith("judder_probe")]
    equations = [(r, place) for r, place in zip(flat.residuals, flat.places)
                 if not place.startswith(probe_file)]
    column = casadi.vertcat(casadi.SX(0, 1), *[u for u, _ in unknowns])
    incidence = np.zeros((len(equations), len(unknowns)), dtype=bool)
    for i, (residual, _) in enumerate(equations):
        used = {s.name() for s in casadi.symvar(residual)}
        incidence[i] = [column[j].name() in used
                        for j in range(column.shape[0])]
    over, under = excess(incidence)
    if difference > 0 and over:
        return _listed(f"{difference} equation(s) too many, among these "
                       f"{len(over)} over-determined equations",
                       [f"{equations[i][1]}: 0 = {equations[i][0]}"
                        for i in over])
    if difference < 0 and under:
        return _listed(f"{-difference} equation(s) missing, for these "
                       f"{len(under)} under-determined variables",
                       [f"{unknowns[j][1].where}: {unknowns[j][1].name}"
                        for j in under])
    return ""


def _listed(what, items):
    """``what``, then the first :data:`_SHOWN` items (``...`` for more)."""
    return (f"\n{what}: " + "; ".join(items[:_SHOWN])
            + ("; ..." if len(items) > _SHOWN else ""))
