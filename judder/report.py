"""``judder report``: the paper's figure set and tables for one driveline,
in one self-contained HTML file.

The report runs the API functions a user would run one by one
(:func:`judder.api.eig`, :func:`~judder.api.stability_map`,
:func:`~judder.api.tongues`, :func:`~judder.api.floquet`,
:func:`~judder.api.sensitivity`, :func:`~judder.api.fit`) and lays their
numbers and figures out for a reader who was not at the computer: what
the driveline is, where it judders, whether the configured dither is
safe and by how much, what moves the tongues most, and how well the model
matches the bench. Figures are embedded as base64 PNG, so the file opens
anywhere without its neighbours.
"""

import base64
import datetime
import html
import io
import shutil
import subprocess
import tempfile
import dataclasses
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

from infra.errors import JudderError
from infra.files import (MARK, atomic_write, keeps_foreign_files, mark_pdf,
                         write_text)
from infra.units import PA_PER_BAR

from stability.relevance import DEFAULT_MIN_GROWTH_PER_S

from . import api

__all__ = ["ReportResult", "build_report", "print_pdf",
           "DEFAULT_SENSITIVITY"]

#: Parameters varied in the report's sensitivity study, per model: those
#: of Fig. 17 and 18 where the model has them.
DEFAULT_SENSITIVITY = ("k12", "k24", "k", "J1", "J2", "J24", "J3", "J4",
                       "mu_g", "c12", "c")

#: Kinds of the Fig. 15 panels, in the paper's order (a, b, c); each
#: panel is drawn just inside (1.5 times the tip amplitude) the
#: driveline's lowest tongue of that kind.
_KIND_ORDER = ("single-period", "double-period", "combination")


@dataclass(frozen=True)
class ReportResult:
    """``judder report``: the HTML text and the numbers in it.

    Attributes
    ----------
    html : str
        The self-contained page.
    data : dict
        The numbers of its tables (the ``--json`` output).
    figures : list of str
        Titles of the embedded figures, in order.
    """

    html: str
    data: dict
    figures: list = field(default_factory=list)

    def as_dict(self):
        return {**self.data, "figures": list(self.figures)}

    @keeps_foreign_files
    def save(self, path):
        """Write the HTML file (atomically)."""
        write_text(path, self.html, overwrite=True)

    @keeps_foreign_files
    def save_pdf(self, path, html_path):
        """Print the saved HTML file ``html_path`` to PDF with a headless
        Chromium (Debian's ``chromium``; ``make browser`` installs it)."""
        print_pdf(html_path, path)


def _png(fig, dpi=100):
    """A figure as a base64 PNG ``<img>``; closes the figure."""
    import matplotlib.pyplot as plt
    buffer = io.BytesIO()
    fig.savefig(buffer, format="png", dpi=dpi)
    plt.close(fig)
    data = base64.b64encode(buffer.getvalue()).decode("ascii")
    return f'<img alt="" src="data:image/png;base64,{data}">'


def _table(header, rows):
    head = "".join(f"<th>{html.escape(str(h))}</th>" for h in header)
    body = "".join("<tr>" + "".join(f"<td>{html.escape(str(c))}</td>"
                                    for c in row) + "</tr>" for row in rows)
    return f"<table><thead><tr>{head}</tr></thead><tbody>{body}</tbody></table>"


def _verdict_text(v):
    """The configured dither's verdict in words, from a record of
    ``judder check`` (:func:`judder.results.setting_record`) with the
    leading ``|lambda|`` added."""
    tongue = v["margin_bar_tongue"] or v["margin_hz_tongue"]
    named = "" if tongue is None else \
        f" (tongue {tongue['number'] or '?'}, {tongue['kind']})"
    boundary = ("stability boundary" if not v["min_growth_per_s"] else
                f"boundary of judder growing at {v['min_growth_per_s']:g} "
                "1/s")
    where = (f"the {boundary} at {v['freq_hz']:g} Hz is "
             f"{v['boundary_p_f_bar']:.3g} bar{named}"
             if v["boundary_p_f_bar"] is not None else
             f"no tongue reaches {v['freq_hz']:g} Hz below "
             f"{v['p_f_bar'] + v['margin_bar_at_least']:g} bar")
    edge = ("" if v["margin_hz"] is None else
            f"; the nearest tongue edge at {v['p_f_bar']:g} bar is "
            f"{abs(v['margin_hz']):.3g} Hz away, at "
            f"{v['crossing_hz']:.2f} Hz")
    if v["verdict"] == "judder":
        return (f"JUDDER: {v['kind']} instability, growing at "
                f"{v['growth_rate_per_s']:.3g} 1/s "
                f"(|lambda| = {v['leading_abs']:.4f}); {where}, so the "
                f"dither amplitude is {-v['margin_bar']:.3g} bar above it"
                + edge)
    if v["verdict"] == "slow-growth":
        text = (f"no judder: {v['kind']} instability growing at only "
                f"{v['growth_rate_per_s']:.3g} 1/s (|lambda| = "
                f"{v['leading_abs']:.4f}), slower than the judder-relevant "
                f"{v['min_growth_per_s']:g} 1/s; {where}")
    else:
        text = (f"no judder: stable (|lambda| = {v['leading_abs']:.4f}, "
                f"decay {v['growth_rate_per_s']:.3g} 1/s); {where}")
    if v["margin_bar"] is not None:
        text += f", a margin of {v['margin_bar']:.3g} bar in amplitude"
    return text + edge


def _ranking(tip_shifts, tongue_number):
    """Per parameter, the largest relative move of one tongue's tip (in
    amplitude and frequency) over its variations, largest first."""
    table = {}
    for row in tip_shifts:
        if row["tongue"] != tongue_number:
            continue
        base_p = row["tip_p_f_bar"] - row["d_p_f_bar"] if row["present"] \
            else None
        entry = table.setdefault(row["parameter"],
                                 {"parameter": row["parameter"],
                                  "p_f_percent": 0.0, "freq_percent": 0.0,
                                  "vanishes": False})
        if not row["present"]:
            entry["vanishes"] = True
            continue
        base_f = row["tip_freq_hz"] - row["d_freq_hz"]
        entry["p_f_percent"] = max(entry["p_f_percent"],
                                   abs(100 * row["d_p_f_bar"] / base_p))
        entry["freq_percent"] = max(entry["freq_percent"],
                                    abs(100 * row["d_freq_hz"] / base_f))
    return sorted(table.values(), key=lambda e: (
        not e["vanishes"], -max(e["p_f_percent"], e["freq_percent"])))


_CSS = """
body{font-family:sans-serif;max-width:1200px;margin:2em auto;padding:0 1em;
color:#111;line-height:1.4}
h1{font-size:1.5em}h2{font-size:1.2em;border-bottom:1px solid #999;
margin-top:2em}
table{border-collapse:collapse;margin:0.8em 0}
td,th{border:1px solid #bbb;padding:0.2em 0.6em;text-align:left;
font-size:0.9em}
th{background:#eee}
img{max-width:100%;height:auto;display:block;margin:0.8em 0}
.verdict{font-size:1.1em;padding:0.6em;border:2px solid #333}
.judder{border-color:#b00;background:#fee}
.safe{border-color:#070;background:#efe}
.small{font-size:0.85em;color:#444}
@media print{h2{page-break-before:auto}img{page-break-inside:avoid}}
"""


def build_report(parameters=None, changes=None, description=None,
                 freq_hz=None, p_f_bar=None, chart=None, boundary=None,
                 group=None, fit_names=("c12", "mu_g", "k24"),
                 sensitivity_names=None, grid_freq=None, map_freq=None,
                 map_pf=None, p_max_bar=1.5, method="dyson", workers=None,
                 engagement=False, min_growth=DEFAULT_MIN_GROWTH_PER_S,
                 progress=None):
    """``judder report``: the figures and tables of the paper for one
    driveline.

    Parameters
    ----------
    parameters, changes
        The driveline, as for every API function.
    description : str, optional
        How the set was chosen (preset, file, ``--set``), for the title.
    freq_hz, p_f_bar : float, optional
        The configured dither setting (Hz, bar): its verdict, margin and
        multipliers (Fig. 15) head the report.
    chart : path, optional
        An experimental chart (``judder chart --out``): its boundary is
        fitted and drawn (Fig. 16a).
    boundary : path, optional
        A measured boundary CSV instead of ``chart``.
    group : str, optional
        The chart's group, when it has several.
    fit_names : sequence of str
        Parameters fitted to the bench data.
    sensitivity_names : sequence of str, optional
        Parameters of the sensitivity study (default: those of
        :data:`DEFAULT_SENSITIVITY` the model has).
    grid_freq : array_like, optional
        Frequencies of the tongue and sensitivity boundaries, Hz (default
        10-220 Hz, 300 points).
    map_freq, map_pf : array_like, optional
        Grid of the map, Hz and bar (default 5-250 Hz x 0-``p_max_bar``,
        300 x 150).
    p_max_bar : float
        Largest amplitude searched, bar.
    min_growth : float
        Judder-relevant growth rate, 1/s (:mod:`stability.relevance`):
        the verdict and the map's shading use it, as ``judder check``
        and ``judder map`` do (0: every instability); the tongues and
        tips are the stability boundaries of Fig. 14.
    engagement : bool
        With a dither setting: also run the bench engagement at it and
        without dither through the FMU (Fig. 7, 8; a few seconds); for a
        Modelica class, its own FMU from its steady slip
        (:func:`judder.api.simulate`). Refused for an FMU of ``--fmu``.
    progress : callable, optional
        ``progress(done, total)`` over the report's sections.

    Returns
    -------
    ReportResult
    """
    from stability.plotting import multipliers_figure
    from .inputs import read_boundary, read_chart_boundary
    values = api.params(parameters, changes).params
    description = description or values.model
    grid_freq = np.linspace(10, 220, 300) if grid_freq is None \
        else np.asarray(grid_freq, dtype=float)
    map_freq = np.linspace(5, 250, 300) if map_freq is None else map_freq
    map_pf = np.linspace(0, p_max_bar, 150) if map_pf is None else map_pf
    names = [n for n in (sensitivity_names or DEFAULT_SENSITIVITY)
             if sensitivity_names or n in values.specs]
    # bench data first: a bad file is refused before any work
    bench = None
    if chart:
        bench = read_chart_boundary(chart, group)
    elif boundary:
        bench = (*read_boundary(boundary, "--boundary"), p_max_bar)
    for option, given in (("--sensitivity", names),
                          ("--fit", fit_names if bench else ())):
        unknown = [n for n in given if n not in values.specs]
        if unknown:
            raise JudderError(f"{option}: unknown parameter "
                              f"{unknown[0]!r} for the {values.model} "
                              "model; allowed names: "
                              f"{', '.join(values.specs)}")
    paper = values.driveline is not None     # a registry driveline
    run_engagement = engagement and freq_hz is not None and (
        not paper or values.driveline.bench_class is not None)
    if run_engagement:
        from .timedomain import class_fmu
        class_fmu(values, "report --engagement")   # refuses --fmu now
    steps = 6 + bool(bench)
    done = [0]

    def step():
        done[0] += 1
        if progress:
            progress(done[0], steps)

    sections, figures, data = [], [], {"model": values.model,
                                       "description": description}

    def figure(title, fig):
        figures.append(title)
        return f"<figure>{_png(fig)}<figcaption>{html.escape(title)}" \
               f"</figcaption></figure>"

    # the driveline
    eig = api.eig(values).as_dict()
    data["natural_frequencies_hz"] = list(eig["natural_frequencies_hz"])
    data["damping_factor_12_percent"] = eig["damping_factor_12_percent"]
    rows = [(name, f"{values[name]:.6g}", spec.unit, spec.description)
            for name, spec in values.specs.items()]
    sections.append(
        "<h2>1. The driveline</h2>"
        "<p>Natural frequencies (Eq. 15): "
        + ", ".join(f"{f:.3f} Hz" for f in eig["natural_frequencies_hz"])
        + ("" if eig["damping_factor_12"] is None else
           "; clutch-damper damping factor zeta_12 (Eq. 16): "
           f"{eig['damping_factor_12_percent']:.2f} %")
        + "; damped modes without dither: " + ", ".join(
            f"{m['frequency_hz']:.3f} Hz ({100 * m['damping_ratio']:.2f} %)"
            for m in eig["damped_modes"]) + ".</p>"
        + _table(("parameter", "value", "unit", "meaning"), rows))
    step()

    # tongues, and the map they are drawn over
    tongues = api.tongues(grid_freq, p_max_bar, values, method=method)
    stability = dataclasses.replace(
        api.stability_map(map_freq, map_pf, values, method=method,
                          min_growth=min_growth),
        boundaries=tongues.boundaries, tongues=tongues.tongues)
    step()
    data["tongues"] = [
        {"number": t.number, "kind": t.kind, "resonance": t.resonance,
         "tip_freq_hz": t.tip_freq_hz, "tip_p_f_bar": t.tip_p_f / PA_PER_BAR}
        for t in tongues.tongues]
    tip_rows = [(t["number"] or "-", t["kind"], t["resonance"] or "-",
                 f"{t['tip_freq_hz']:.2f}", f"{t['tip_p_f_bar']:.4f}")
                for t in data["tongues"]]

    # the configured dither
    if freq_hz is not None and p_f_bar is not None:
        # judder check at the setting, at the growth rate that shades
        # the map (the tongues are the stability boundaries of Fig. 14)
        checked = api.check([freq_hz], [p_f_bar], values,
                            min_growth=min_growth,
                            p_max_bar=max(p_max_bar, 2 * p_f_bar),
                            sensitivity=())
        point = checked.checks[0].floquet
        verdict = {**checked.records()[0],
                   "leading_abs": float(point.leading_abs)}
        data["verdict"] = verdict
        css = "judder" if verdict["verdict"] == "judder" else "safe"
        sections.insert(0, (
            f"<h2>Verdict: dither at {freq_hz:g} Hz, {p_f_bar:g} bar</h2>"
            f'<p class="verdict {css}">'
            f"{html.escape(_verdict_text(verdict))}</p>"
            '<p class="small">Source: judder check --min-growth '
            f"{min_growth:g}; the map below shades slower growth grey, its "
            "tongues are the stability boundaries (Fig. 14).</p>"
            + figure(f"Floquet multipliers at {freq_hz:g} Hz, {p_f_bar:g} "
                     "bar (Fig. 15)",
                     multipliers_figure([point], title="Floquet multipliers "
                                        "at the configured dither"))))
    step()

    sections.append(
        "<h2>2. Where it judders: the stability map</h2>"
        + figure("Stability map with the exact tongue boundaries and "
                 "numbers (Fig. 14)",
                 stability.figure(title=f"stability map, {description}"))
        + "<p>Tongue tips (lowest amplitude that judders, refined between "
          "grid points); numbers as in Fig. 14:</p>"
        + _table(("#", "kind", "resonance", "tip f [Hz]", "tip p_f [bar]"),
                 tip_rows))
    # Fig. 15 by kind, at points just inside each kind's lowest tongue
    inside = []
    for kind in _KIND_ORDER:
        found = [t for t in tongues.tongues if t.kind == kind]
        if found:
            t = min(found, key=lambda t: t.tip_p_f)
            inside.append(api.floquet(t.tip_freq_hz,
                                      min(1.5 * t.tip_p_f / PA_PER_BAR,
                                          p_max_bar), values,
                                      method=method).result)
    if inside:
        sections.append(
            "<h3>How the multipliers leave the unit circle, by kind</h3>"
            + figure("Floquet multipliers just inside the lowest tongue of "
                     "each kind (Fig. 15)",
                     multipliers_figure(inside, title="Floquet multipliers "
                                        "by kind of instability (Fig. 15)")))

    # sensitivity
    sens = api.sensitivity(names, grid_freq, p_max_bar, parameters=values,
                           method=method, workers=workers)
    step()
    focus = _focus_tongue(tongues.tongues, freq_hz)
    ranking = _ranking(sens.tip_shifts, focus)
    data["sensitivity_ranking"] = {"tongue": focus, "ranking": ranking}
    sections.append(
        "<h2>3. What moves the tongues: sensitivity</h2>"
        f"<p>Each parameter halved and doubled (Fig. 17, 18). Ranking by "
        f"the largest relative move of tongue {focus}'s tip"
        + (" (the tongue nearest the configured dither)"
           if freq_hz is not None else "") + ":</p>"
        + _table(("parameter", "tip p_f moves up to [%]",
                  "tip f moves up to [%]", "tongue vanishes"),
                 [(e["parameter"], f"{e['p_f_percent']:.1f}",
                   f"{e['freq_percent']:.2f}",
                   "yes" if e["vanishes"] else "no") for e in ranking])
        + figure("Sensitivity of the stability boundary (Fig. 17, 18)",
                 sens.figure(title=f"sensitivity, {description}")))

    # without dither (Fig. 19): a study of the paper's chains
    if paper:
        threshold = api.threshold(np.linspace(-1e-3, 1e-3, 41),
                                  np.linspace(0, 2, 21), values)
        data["mu_g_threshold"] = float(threshold.study.threshold)
        sections.append(_threshold_section(values, threshold, figure))
    step()

    if run_engagement:
        run = api.simulate(freq_hz, p_f_bar, compare="none",
                           parameters=values, method=method)
        first = run.summaries[0]
        data["engagement"] = first
        sections.append(
            "<h2>5. The engagement "
            + ("on the bench model" if paper else "of the class's FMU")
            + f"</h2><p>Through the {html.escape(run.model_class)} FMU"
            + ("" if paper else " from its start values (a steady slip)")
            + ": upstream speed peak "
            f"{first['speed_peak_amplitude_rpm']:.3g} rpm at "
            f"{first['speed_peak_freq_hz']:.2f} Hz; judder read as a chart "
            "reads a bench run: "
            + ("none" if not first["judder"] else str(first["judder_kind"]))
            + f"; Floquet exponent of its linearisation "
            f"{first['floquet_exponent_per_s']:+.2f} 1/s"
            + ("" if first.get("linearisation_holds") is not False else
               f". The dither's forced slip swing "
               f"({first['forced_slip_amplitude_rad_s']:.2g} rad/s) exceeds "
               f"the friction curve's linear range "
               f"({first['friction_linear_range_rad_s']:.2g} rad/s): the run "
               "is nonlinear and need not follow the Floquet verdict")
            + ".</p>"
            + figure("Engagement with the configured dither and without "
                     "(Fig. 7, 8)",
                     run.figure(title=f"time-domain run, {description}")))

    # bench data
    if bench:
        freqs, measured, tried = bench
        report = api.fit(freqs, measured / PA_PER_BAR, tried,
                         names=list(fit_names), parameters=values,
                         method=method, starts=1, workers=workers)
        step()
        r = report.fit
        data["fit"] = {n: {"value": v, "ci95": [lo, hi]} for n, v, lo, hi
                       in zip(r.names, r.values, r.ci_low, r.ci_high)}
        data["fit_success"] = bool(r.success)
        sections.append(
            "<h2>6. The bench data and the fit</h2>"
            f"<p>{len(freqs)} measured points from "
            f"{html.escape(str(chart or boundary))}; fitted "
            + ", ".join(r.names) + f"; residual rms "
            f"{r.residual_rms_bar:.3g} bar.</p>"
            + _table(("parameter", "start", "fitted", "95 % interval"),
                     [(n, f"{s0:.5g}", f"{v:.5g}", f"[{lo:.5g}, {hi:.5g}]")
                      for n, s0, v, lo, hi in zip(r.names, r.start,
                                                  r.values, r.ci_low,
                                                  r.ci_high)])
            + "".join(f"<p>problem: {html.escape(p)}</p>"
                      for p in r.problems)
            + figure("Measured and fitted boundaries (Fig. 16a)",
                     report.figure()))
    step()

    stamp = datetime.datetime.now(datetime.timezone.utc).strftime(
        "%Y-%m-%d %H:%M UTC")
    page = (
        "<!DOCTYPE html><html lang=\"en\"><head><meta charset=\"utf-8\">"
        f"<meta name=\"generator\" content=\"{MARK}\">"
        f"<title>judder report: {html.escape(description)}</title>"
        f"<style>{_CSS}</style></head><body>"
        f"<h1>Clutch judder from dither: {html.escape(description)}</h1>"
        f'<p class="small">judder report, {stamp}. Dither frequency in Hz, '
        "amplitude in bar, parameters in SI units. Figures and equations "
        "as numbered in \"Parametric excitation as a cause of clutch "
        "judder: theoretical study and experimental validation\".</p>"
        + "".join(sections) + "</body></html>")
    return ReportResult(html=page, data=data, figures=figures)


def _threshold_section(values, threshold, figure):
    """Section 4: the friction-gradient threshold without dither (Fig.
    19) of a registry driveline, from :func:`judder.api.threshold`."""
    return (
        "<h2>4. Without dither: the friction-gradient threshold</h2>"
        f"<p>With the mean pressure in the slip damping, this driveline "
        f"is unstable without any dither for mu_g below "
        f"{threshold.study.threshold:.3g} s/rad (its mu_g is "
        f"{values['mu_g']:.3g} s/rad"
        + (", so it judders without dither" if values["mu_g"]
           < threshold.study.threshold else "")
        + ").</p>"
        + figure("Largest real part against mu_g and the threshold "
                 "against the external damping (Fig. 19)",
                 threshold.figure()))


def _focus_tongue(found, freq_hz):
    """Number of the tongue the ranking follows: the one nearest the
    configured dither frequency, else the lowest tip."""
    numbered = [t for t in found if t.number is not None]
    if not numbered:
        return None
    if freq_hz is None:
        return min(numbered, key=lambda t: t.tip_p_f).number
    return min(numbered, key=lambda t: abs(t.tip_freq_hz - freq_hz)).number


#: Flags of a headless Chromium that reads only the given file.
CHROMIUM_FLAGS = ("--headless", "--no-sandbox", "--disable-gpu",
                  "--disable-background-networking",
                  "--disable-component-update", "--disable-sync",
                  "--no-first-run", "--no-pdf-header-footer")


def print_pdf(html_path, pdf_path):
    """Print an HTML file to PDF with headless Chromium, atomically.

    Raises
    ------
    JudderError
        No Chromium on the PATH, or it failed.
    """
    browser = shutil.which("chromium") or shutil.which("chromium-browser")
    if browser is None:
        raise JudderError("--pdf needs Chromium (Debian: apt-get install "
                          "chromium, or make browser); the HTML report "
                          "was written")
    with tempfile.TemporaryDirectory() as scratch:
        target = Path(scratch) / "report.pdf"
        proc = subprocess.run(
            [browser, *CHROMIUM_FLAGS, f"--user-data-dir={scratch}/profile",
             f"--print-to-pdf={target}", Path(html_path).resolve().as_uri()],
            capture_output=True, text=True, timeout=300)
        if not target.exists() or target.stat().st_size == 0:
            raise JudderError(f"--pdf: chromium could not print the report "
                              f"(exit {proc.returncode})")
        # marked, so that the next run may replace it (the overwrite rule)
        data = mark_pdf(target.read_bytes())
    atomic_write(pdf_path, lambda stream: stream.write(data))
