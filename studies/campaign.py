"""``judder campaign``: bench emulator: engagement acquisitions over a
dither grid.
"""

from dataclasses import dataclass
from pathlib import Path

from ._common import checked_values, timed
from .bench import bench_fmu


def campaign(folder, freq_hz, p_f_bar, engine_rpm=(1000.0,),
             temperatures=("65-70",), duration=3.0, noise_rpm=0.5, seed=1,
             formats=("csv", "mf4"), parameters=None, changes=None,
             workers=None, progress=None):
    """``judder campaign``: emulate a bench campaign of engagements into
    ``folder`` (resumed when run again).

    Parameters
    ----------
    folder : path
    freq_hz, p_f_bar : sequence of float
        Dither grid, Hz and bar.
    engine_rpm : sequence of float
        Motor speeds, rpm.
    temperatures : sequence of str
        Keys of :data:`pysim.simulation.campaigns.TEMPERATURES`.

    Returns
    -------
    CampaignResult
    """
    from pysim.simulation.campaigns import Campaign, run_campaign
    values = checked_values(parameters, changes, freq_hz=freq_hz,
                            p_f_bar=p_f_bar)
    if not values.source_kind.is_chain:
        bench_fmu(values)       # refuses a class or FMU, naming the bench
    plan = Campaign(freq_hz=tuple(freq_hz), p_f_bar=tuple(p_f_bar),
                    engine_rpm=tuple(engine_rpm),
                    temperatures=tuple(temperatures), duration=duration,
                    noise_rpm=noise_rpm, formats=tuple(formats), seed=seed)
    rows, seconds = timed(run_campaign, plan, values, folder,
                           workers=workers, callback=progress)
    return CampaignResult(rows=rows, index=str(Path(folder) / "index.csv"),
                          seconds=seconds)


@dataclass(frozen=True)
class CampaignResult:
    """``judder campaign``: the index rows of the campaign folder."""

    rows: list
    index: str
    seconds: float

    @property
    def failed(self):
        return [r for r in self.rows if r["status"] != "ok"]

    def as_dict(self):
        return {"runs": len(self.rows),
                "ok": len(self.rows) - len(self.failed),
                "reused": sum(bool(r.get("reused")) for r in self.rows),
                "failed": self.failed, "index": self.index,
                "seconds": self.seconds}
