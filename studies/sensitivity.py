"""``judder sensitivity``: tongue shifts per parameter (Fig. 17, 18)."""

from dataclasses import dataclass

from infra.errors import JudderError
from infra.files import keeps_foreign_files, write_text
from infra.units import PA_PER_BAR
from sources.dither_modes import check_modes_of_changes, check_modes_up_to
from stability.monodromy import DEFAULT_METHOD

from ._common import checked_values, timed
from ._records import rows_to_csv
from .tongues import tongue_record


def sensitivity(names, freq_hz, p_max_bar=1.5, factors=(0.5, 2.0),
                values=None, parameters=None, changes=None,
                method=DEFAULT_METHOD, workers=None, progress=None,
                driveline=None):
    """``judder sensitivity``: tongue tips with parameters varied (Fig. 17,
    18), and the paper's conclusions of section 4.3 where the driveline is
    the paper's.

    Parameters
    ----------
    names : sequence of str
        Parameters to vary.
    factors : sequence of float
        Multipliers of the nominal values (used when ``values`` is None).
    values : sequence of float, optional
        Absolute values instead, SI.
    workers : int, optional
        Processes (default all cores).
    driveline : {'chain', 'bench'}, optional
        The driveline whose tongues move (:func:`stability.bench.
        driveline_view`; default the bench where the preset has one).

    Returns
    -------
    SensitivityResult
    """
    from stability.sensitivity import (paper_conclusions, sensitivity_study,
                                       tip_shifts)

    from stability.bench import driveline_view
    nominal, driveline = driveline_view(
        checked_values(parameters, changes, freq_hz=freq_hz,
                       p_max_bar=p_max_bar), driveline)
    check_modes_up_to(nominal, freq_hz, p_max_bar)
    for name in names:
        if name not in nominal.specs:
            raise JudderError(f"`names`: unknown parameter {name!r} for the "
                              f"{nominal.model} model; allowed names: "
                              f"{', '.join(nominal.specs)}")
    # each changed set in the nominal mode, held up to p_max_bar, as the
    # nominal one (the study's own values: the factors of the nominal
    # values, or the values given)
    check_modes_of_changes(nominal, [
        {name: float(value)} for name in names for value in (
            values if values is not None else
            [nominal[name] * factor for factor in factors])],
        freq_hz, p_max_bar)
    study, seconds = timed(
        sensitivity_study, nominal, names, freq_hz, p_max_bar * PA_PER_BAR,
        factors=factors, values=values, method=method, workers=workers,
        callback=progress)
    conclusions = (paper_conclusions(study)
                   if nominal.source_kind.is_chain
                   and nominal.driveline.paper_sensitivity else [])
    return SensitivityResult(params=nominal, study=study,
                             tip_shifts=tip_shifts(study),
                             conclusions=conclusions, seconds=seconds,
                             method=method, driveline=driveline)


@dataclass(frozen=True)
class SensitivityResult:
    """``judder sensitivity``: tip shifts per varied parameter.

    ``study`` is the :class:`stability.sensitivity.SensitivityStudy`;
    ``tip_shifts`` and ``conclusions`` as
    :func:`stability.sensitivity.tip_shifts` and
    :func:`stability.sensitivity.paper_conclusions` give them.
    """

    params: object
    study: object
    tip_shifts: list
    conclusions: list
    seconds: float
    method: str
    driveline: str = "chain"

    @property
    def cases(self):
        return 1 + len(self.study.cases)

    def as_dict(self):
        from stability.bench import driveline_words
        return {"model": self.params.model, "driveline": self.driveline,
                "driveline_description": driveline_words(self.params,
                                                         self.driveline),
                "method": self.method,
                "seconds": self.seconds, "cases": self.cases,
                "min_growth_per_s": 0.0,
                "nominal_tongues": [tongue_record(t)
                                    for t in self.study.nominal.tongues],
                "tip_shifts": self.tip_shifts,
                "paper_conclusions": self.conclusions}

    @keeps_foreign_files
    def save(self, path):
        write_text(path, rows_to_csv(self.tip_shifts))

    def figure(self, title=None):
        return self.study.plot(
            title=title or f"{self.params.model}: sensitivity of the "
                           "unstable boundary ($|\\lambda| = 1$)",
            params=self.params)
