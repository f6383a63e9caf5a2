"""The sections of ``judder report``, one function each, and the page
around them.

Each section function takes the results of the studies it shows (computed
by :func:`studies.report.report`) and returns its HTML; its
figures go through :meth:`Page.figure`, which embeds them and keeps
their titles in order. Nothing here computes a study, except
:func:`fit_section`, whose fit decides what the section says.
"""

import base64
from dataclasses import dataclass, field, replace
import datetime
import html
import io
import re

import numpy as np

from infra.criteria import (CANNOT_TELL, ENGAGEMENT_DURATION_S, JUDDER,
                            NO_JUDDER, SLOW_GROWTH)
from infra.errors import in_options
from infra.files import MARK
from infra.numbers import format_interval, format_uncertain, readable_number
from infra.provenance import current
from infra.units import PA_PER_BAR

from ._words import (growth_words, margin_words, nonlinear_words, orbit_words,
                     response_words)

_CSS = """
@page{size:A4;margin:14mm 13mm}
body{font-family:sans-serif;max-width:1000px;margin:2em auto;padding:0 1em;
color:#111;line-height:1.4}
h1{font-size:1.5em}h2{font-size:1.2em;border-bottom:1px solid #999;
margin-top:1.6em}
h2,h3{break-after:avoid;page-break-after:avoid}
table{border-collapse:collapse;margin:0.8em 0}
td,th{border:1px solid #bbb;padding:0.2em 0.6em;text-align:left;
font-size:0.9em;vertical-align:top}
th{background:#eee}
table.facts th{width:12em}
img{max-width:100%;height:auto;display:block;margin:0.8em auto}
figure{margin:0.5em 0;break-inside:avoid;page-break-inside:avoid}
figcaption{font-size:0.85em;color:#444;text-align:center}
tr,.keep{break-inside:avoid;page-break-inside:avoid}
table{break-inside:avoid;page-break-inside:avoid}
p:has(+ table){break-after:avoid;page-break-after:avoid}
.verdict{font-size:1.1em;padding:0.6em;border:2px solid #333}
.judder{border-color:#b00;background:#fee}
.slow{border-color:#a60;background:#fff6e0}
.safe{border-color:#070;background:#efe}
.none{border-color:#555;background:#f4f4f4}
.small{font-size:0.85em;color:#444}
@media print{body{margin:0;padding:0;max-width:none;font-size:10pt}}
"""


@dataclass
class Page:
    """The report being written: its sections and embedded figures.

    Attributes
    ----------
    description : str
        The driveline, for the title and the figures' titles.
    sections : list of str
        HTML of each section, in order.
    figures : list of str
        Titles of the embedded figures, in order.
    """

    description: str
    sections: list = field(default_factory=list)
    figures: list = field(default_factory=list)

    def figure(self, title, fig):
        """``fig`` as an embedded ``<figure>`` captioned ``title``."""
        self.figures.append(title)
        return f"<figure>{_png(fig)}<figcaption>{html.escape(title)}" \
               f"</figcaption></figure>"

    def html(self):
        """The whole page: title, sections numbered, the style sheet."""
        stamp = datetime.datetime.now(datetime.timezone.utc).strftime(
            "%Y-%m-%d %H:%M UTC")
        description = html.escape(self.description)
        provenance = html.escape(current().words())
        return (
            "<!DOCTYPE html><html lang=\"en\"><head><meta charset=\"utf-8\">"
            f"<meta name=\"generator\" content=\"{MARK} {provenance}\">"
            f"<title>judder report: {description}</title>"
            f"<style>{_CSS}</style></head><body>"
            f"<h1>Clutch judder from dither: {description}</h1>"
            f'<p class="small">judder report, {stamp}, {provenance}. '
            "Dither frequency in Hz, amplitude in bar, parameters in SI units. Figures and "
            "equations as numbered in \"Parametric excitation as a cause of "
            "clutch judder: theoretical study and experimental "
            "validation\".</p>"
            + _number_sections("".join(self.sections)) + "</body></html>")


#: Width of the report's figures, inches: the text width of the printed
#: A4 page (210 mm less the 13 mm margins of ``@page``: 184 mm, 7.24 in),
#: a little less. Each figure is drawn at this width and printed at it,
#: so its text prints at the size it is set in (7 pt and more).
FIGURE_WIDTH_IN = 7.2
#: Tallest figure, inches (203 mm): it, its caption, a heading and a
#: paragraph fit on one printed page (269 mm of text height).
FIGURE_MAX_HEIGHT_IN = 8.0
#: Lowest height of a figure drawn narrower than it was made, as a share
#: of its width: a wide row of panels keeps room for its titles, labels
#: and legends when it is narrowed to the page.
_MIN_ASPECT = 0.55


def printed_size(width_in, height_in):
    """The size (inches) a figure made at ``width_in x height_in`` is
    drawn and printed at in the report: the page's text width
    (:data:`FIGURE_WIDTH_IN`) at most, the height shrunk with the width
    but not below :data:`_MIN_ASPECT` of the width (nor above the
    figure's own height), and :data:`FIGURE_MAX_HEIGHT_IN` at most."""
    width = min(width_in, FIGURE_WIDTH_IN)
    height = max(height_in * width / width_in,
                 min(height_in, _MIN_ASPECT * width))
    return width, min(height, FIGURE_MAX_HEIGHT_IN)


def _png(fig, dpi=150):
    """A figure as a base64 PNG ``<img>``, redrawn (its layout is
    constrained) at :func:`printed_size` and shown at that size in
    inches, on screen and on paper; closes the figure."""
    import matplotlib.pyplot as plt

    from infra.plotstyle import redraw_at
    width, height = printed_size(*fig.get_size_inches())
    redraw_at(fig, width, height)
    buffer = io.BytesIO()
    fig.savefig(buffer, format="png", dpi=dpi)
    plt.close(fig)
    data = base64.b64encode(buffer.getvalue()).decode("ascii")
    return (f'<img alt="" style="width:{width:.3f}in" '
            f'src="data:image/png;base64,{data}">')


def _table(header, rows):
    head = "".join(f"<th>{html.escape(str(h))}</th>" for h in header)
    body = "".join("<tr>" + "".join(f"<td>{html.escape(str(c))}</td>"
                                    for c in row) + "</tr>" for row in rows)
    return f"<table><thead><tr>{head}</tr></thead><tbody>{body}</tbody></table>"


def _keep(part):
    """``part`` (a heading and what opens its section) kept on one printed
    page."""
    return f'<div class="keep">{part}</div>'


def _number_sections(body):
    """Number the ``<h2>`` headings 1, 2, ... in their order (a number a
    section wrote itself is replaced), so the numbering has no gap
    whichever sections the report has."""
    count = [0]

    def numbered(match):
        count[0] += 1
        return f"<h2>{count[0]}. "
    return re.sub(r"<h2>(?:\d+\. )?", numbered, body)


def verdict_text(v, engagement_s=ENGAGEMENT_DURATION_S):
    """The configured dither's verdict in words, from a record of
    ``judder check`` (:func:`setting_record`) with the
    leading ``|lambda|`` added: the verdict word, what the multiplier
    does, the growth against an engagement of ``engagement_s`` seconds,
    the highest safe amplitude and the safe band, and both margins to
    judder."""
    tongue = v["tongue"]
    if not v["inside_stability_tongue"]:
        what = "every multiplier inside the unit circle"
    else:
        what = (f"{v['kind']} instability"
                + ("" if tongue is None else
                   f" in tongue {tongue['number'] or '?'}"))
    growth = growth_words(v, engagement_s)
    if v["verdict"] == SLOW_GROWTH:
        growth += (f", slower than the judder-relevant "
                   f"{v['min_growth_per_s']:g} 1/s")
    amplitude, frequency = margin_words(v)
    settled = ""
    if "settled_amplitude_rpm" in v:
        settled = response_words(v) + "; "
    # how far it may go, in check's words: the highest safe amplitude at
    # its frequency and the safe band at its amplitude
    from .check import highest_safe_words, safe_band_words
    far = ("" if "safe_band_hz" not in v else
           f"{highest_safe_words(v)}; {safe_band_words(v)}; ")
    return (f"{v['verdict']} at {v['freq_hz']:g} Hz, {v['p_f_bar']:g} bar: "
            f"{what} (|\u03bb| = {v['leading_abs']:.4f}); {settled}"
            f"{growth}; {far}{amplitude}; {frequency}.")


def _window_text(advice):
    """The safe dither windows of ``judder advise`` in one sentence."""
    op = advice.operating
    top = op.p_max / PA_PER_BAR
    full = [w for w in advice.windows if w.full_range]
    head = (f"Within {op.freq_hz[0]:g}-{op.freq_hz[1]:g} Hz, keeping "
            f"{op.margin_p_f / PA_PER_BAR:g} bar and {op.margin_hz:g} Hz "
            "from every judder-relevant tongue: ")
    if full:
        return head + f"safe up to {top:g} bar at " + ", ".join(
            f"{w.freq_hz[0]:.1f}-{w.freq_hz[1]:.1f} Hz" for w in full) + "."
    best = int(np.argmax(advice.safe_p_f))
    return head + (f"no frequency is safe up to {top:g} bar; the most "
                   f"amplitude is {advice.safe_p_f[best] / PA_PER_BAR:.3f} "
                   f"bar, at {advice.freq_hz[best]:.1f} Hz.")


def _design_text(advice):
    """The smallest design change of ``judder advise`` in one sentence
    (factors within 1 % of 1 left out), and the small changes the search
    found and dropped as unnecessary."""
    a = advice.advice
    if a is None:
        return "not searched."
    if not a.success:
        return f"none found: {a.message}."
    advised = advice.advised_params()
    changes = [f"{n} x{f:.2f} ({readable_number(advice.params[n])} to "
               f"{readable_number(advised[n])} {advice.params.specs[n].unit})"
               for n, f in zip(a.names, a.factors) if abs(f - 1) > 0.01]
    if not changes:
        return "none needed: the window is already clear."
    dropped = [f"{n} x{f:.3f}" for n, f in a.dropped.items()
               if abs(f - 1) > 5e-4]
    return (", ".join(changes) + " clears the window; the map recomputed "
            f"with it has {advice.judder_points} judder points of "
            f"{advice.verification.kind.size}"
            + (f" ({', '.join(dropped)} dropped as unnecessary: the window "
               "stays clear without " + ("it" if len(dropped) == 1 else "them")
               + ")" if dropped else "") + ".")


def summary_section(verdict, advice, advice_error, min_growth,
                    driveline=""):
    """The first screen: the verdict of the configured dither (or why
    there is none), the safe dither window and the smallest design change
    of ``judder advise``, of ``driveline`` (words: which driveline the
    report judges)."""
    if verdict is None:
        css, text = "none", (
            "No dither setting given (`freq_hz`, `p_f_bar`): choose one in the safe "
            "window below, or check one with judder check.")
    else:
        css = {JUDDER: "judder", SLOW_GROWTH: "slow"}.get(verdict["verdict"],
                                                          "safe")
        text = verdict_text(verdict)
    if advice is None:
        window = design = f"not computed: {advice_error}"
    else:
        window, design = _window_text(advice), _design_text(advice)
    rows = "".join(
        f"<tr><th>{html.escape(head)}</th><td>{html.escape(body)}</td></tr>"
        for head, body in (("Safe dither window", window),
                           ("Smallest design change", design)))
    return (
        "<h2>Verdict and advice</h2>"
        + (f'<p class="small">Judged: {html.escape(driveline)}.</p>'
           if driveline else "")
        + f'<p class="verdict {css}">{html.escape(text)}</p>'
        f'<table class="facts">{rows}</table>'
        '<p class="small">JUDDER: a settled oscillation of the upstream '
        "speed above the NVH limit (30 rpm) or an instability growing "
        f"faster than {min_growth:g} 1/s, at least one e-fold within an "
        "engagement; "
        "SLOW GROWTH: unstable (inside a stability tongue) but growing "
        "slower, no judder within an engagement; STABLE: no instability. "
        "Sources: judder check and judder advise (valve range 60-200 Hz, "
        "up to 0.7 bar); the evidence follows.</p>")


def setting_section(page, point, freq_hz, p_f_bar):
    """The configured dither's Floquet multipliers (Fig. 15)."""
    from stability.plots import multipliers_figure
    return _keep(
        "<h2>The configured dither: its multipliers</h2>"
        + page.figure(f"Floquet multipliers at {freq_hz:g} Hz, {p_f_bar:g} "
                      "bar (Fig. 15)",
                      multipliers_figure([point], title="Floquet multipliers "
                                         f"at {freq_hz:g} Hz, {p_f_bar:g} "
                                         f"bar, {page.description}")))


def map_section(page, stability, tongue_records, min_growth, p_max_bar,
                searched_hz, mode=""):
    """The stability map with the exact tongues (Fig. 14) and the table of
    their tips (``tongue_records``: the report's ``tongues`` data): where
    each becomes unstable and where it judders (up to ``p_max_bar``); a
    sentence instead of the table where no tongue reaches ``p_max_bar``
    over the frequencies searched (``searched_hz``: lowest, highest).
    ``mode``: the words of :func:`sources.dither_modes.mode_words` for
    a hybrid Modelica class, whose linearisation holds in one mode."""
    return (_keep(
        "<h2>Where it judders: the stability map</h2>"
        + (f"<p>{html.escape(stability.params.model)} is "
           f"{html.escape(mode)}.</p>" if mode else "")
        + f'<p class="small">Judder-relevant: growing faster than '
        f"{min_growth:g} 1/s (judder check `min_growth` {min_growth:g}); "
        "slower growth is shaded grey; the lines are the exact stability "
        "boundaries (Fig. 14).</p>"
        + page.figure("Stability map with the exact tongue boundaries and "
                      "numbers (Fig. 14)",
                      stability.figure(
                          title=f"stability map, {page.description}",
                          stacked=True)))
        + _tip_table(stability, tongue_records, min_growth, p_max_bar,
                     searched_hz))


def _tip_table(stability, tongue_records, min_growth, p_max_bar,
               searched_hz):
    """The table of the tongue tips, or the sentence saying that none
    reaches ``p_max_bar`` (with the map's largest growth rate)."""
    if not tongue_records:
        growth = float(np.max(stability.map.growth_rate))
        return (f"<p>No tongue reaches {p_max_bar:g} bar between "
                f"{searched_hz[0]:g} and {searched_hz[1]:g} Hz: no "
                "stability boundary, so no tip to tabulate. The largest "
                f"growth rate on the map is {growth:.3g} 1/s"
                + (" (every point decays)." if growth < 0 else ".")
                + "</p>")
    tip_rows = [(t["number"] or "-", t["kind"], t["resonance"] or "-",
                 f"{t['tip_freq_hz']:.2f}", f"{t['tip_p_f_bar']:.4f}",
                 "-" if t["judder_tip_p_f_bar"] is None else
                 f"{t['judder_tip_p_f_bar']:.4f}")
                for t in tongue_records]
    return (
        "<p>Tongue tips, numbers as in Fig. 14: where each tongue becomes "
        "unstable (|lambda| = 1; its tip, refined between grid points) "
        f"and the lowest amplitude where it judders (grows at "
        f"{min_growth:g} 1/s or faster; - : not up to {p_max_bar:g} "
        "bar):</p>"
        + _table(("#", "kind", "resonance", "tip f [Hz]",
                  "unstable from p_f [bar]", "judders from p_f [bar]"),
                 tip_rows))


def kinds_section(page, inside):
    """Fig. 15 by kind: the multipliers just inside the lowest tongue of
    each kind (``inside``: their Floquet results); empty without one."""
    from stability.plots import multipliers_figure
    if not inside:
        return ""
    return _keep(
        "<h3>How the multipliers leave the unit circle, by kind</h3>"
        + page.figure("Floquet multipliers just inside the lowest tongue of "
                      "each kind (Fig. 15)",
                      multipliers_figure(inside, title="Floquet multipliers "
                                         "by kind of instability (Fig. 15), "
                                         f"{page.description}")))


def advice_section(page, advice):
    """The safe dither windows and the design parameters' ranking of
    ``judder advise``, with its figure (the text kept together, the
    figure, a page's width and 193 mm high, free to go overleaf: kept
    with the text it left two thirds of a page empty)."""
    return _keep(
        "<h2>Safe dither windows and the design change</h2>"
        + f"<p>{html.escape(_window_text(advice))}</p>"
        + ("<p>Design parameters ranked by how much of the way out of "
           "the window a relative change takes the judder-relevant "
           "tongues (the share of that way a change of the value by a "
           "factor e = 2.72 moves the tongue that needs most; 1 = all "
           "the way): "
           + html.escape(", ".join(f"{n} {share:.2f}"
                         for n, share, _ in advice.ranking))
           + ".</p>" if advice.ranking else
           "<p>No judder-relevant tongue is in the window, so no design "
           "parameter is ranked: there is nothing to move out of it.</p>")
    ) + page.figure(
        "Safe dither amplitude per frequency"
        + (", and the map of the advised design" if advice.verification
           is not None else " (no design change was found, so no map of "
           "one)") + " (judder advise)",
        advice.figure(title=page.description, stacked=True))


def tip_ranking(tip_shifts, tongue_number):
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


def focus_tongue(found, freq_hz):
    """Number of the tongue the ranking follows: the one nearest the
    configured dither frequency, else the lowest tip."""
    numbered = [t for t in found if t.number is not None]
    if not numbered:
        return None
    if freq_hz is None:
        return min(numbered, key=lambda t: t.tip_p_f).number
    return min(numbered, key=lambda t: abs(t.tip_freq_hz - freq_hz)).number


def _rankings_differ(ranking, advice):
    """Why the sensitivity ranking and ``judder advise``'s differ, when
    their first parameters do."""
    if advice is None or not ranking or not advice.ranking:
        return ""
    first, design = ranking[0]["parameter"], advice.ranking[0][0]
    if first == design:
        return ""
    return (
        f"<p>This ranking puts {html.escape(first)} first, judder advise "
        f"puts {html.escape(design)} first: they answer different "
        "questions. Here each parameter is halved and doubled and the "
        "table gives how far the tip of one tongue moves, mostly in "
        "amplitude (the tip amplitude scales as 1/mu_g). judder advise "
        "asks how far a small relative change of a design parameter "
        "(inertias, stiffnesses, damping; the friction gradient is not "
        "among them by default) moves every judder-relevant tongue out of "
        "the valve's window, mostly in frequency, which the inertias and "
        "stiffnesses set (Eq. 15).</p>")


def _tongues_of_cases(cases):
    """``k12 x0.5 (tip 0.81 bar at 102.3 Hz), ...``: the lowest tip of
    each case of a sensitivity study that has a tongue."""
    found = []
    for case in cases:
        if case.tongues:
            tip = min(case.tongues, key=lambda t: t.tip_p_f)
            found.append(f"{case.parameter} x{case.factor:.3g} (tip "
                         f"{tip.tip_p_f / PA_PER_BAR:.3g} bar at "
                         f"{tip.tip_freq_hz:.1f} Hz)")
    return ", ".join(found)


def sensitivity_section(page, sens, focus, ranking, near_setting, advice):
    """The sensitivity study (Fig. 17, 18): the ranking of the
    parameters by how far they move tongue ``focus``'s tip
    (:func:`tip_ranking`), why it may differ from ``judder advise``'s, and
    the figure. ``near_setting``: the focus is the tongue nearest the
    configured dither. Without a focus (no numbered tongue of the
    nominal driveline up to the amplitudes searched) a sentence says so
    and which variations bring a tongue below them; the figure is left
    out when no case has a tongue."""
    if focus is None:
        return _no_focus_section(page, sens)
    return (_keep(
        "<h2>What moves the tongues: sensitivity</h2>"
        "<p>Each parameter halved and doubled (Fig. 17, 18):</p>"
        + page.figure("Sensitivity of the stability boundary (Fig. 17, 18)",
                      sens.figure(title=f"sensitivity, {page.description}")))
        + f"<p>Ranking by the largest relative move of tongue {focus}'s tip"
        + (" (the tongue nearest the configured dither)"
           if near_setting else "")
        + ": the tip where it becomes unstable (|lambda| = 1), as the "
        "figure's boundaries are; where it judders lies higher (the tip "
        "table's last column).</p>"
        + _table(("parameter", "tip p_f moves up to [%]",
                  "tip f moves up to [%]", "tongue vanishes"),
                 [(e["parameter"], f"{e['p_f_percent']:.1f}",
                   f"{e['freq_percent']:.2f}",
                   "yes" if e["vanishes"] else "no") for e in ranking])
        + _rankings_differ(ranking, advice))


def sensitivity_refused(error):
    """The sensitivity section when the study was refused (``error``, its
    message: a changed parameter set that leaves the mode of a hybrid
    class)."""
    return _keep("<h2>What moves the tongues: sensitivity</h2>"
                 "<p><b>Not computed</b>: "
                 f"{html.escape(str(error))}.</p>")


def _no_focus_section(page, sens):
    """The sensitivity section when the nominal driveline has no
    numbered tongue up to the amplitudes searched: nothing to rank."""
    study = sens.study
    top = study.nominal.boundaries.p_max / PA_PER_BAR
    freqs = study.nominal.boundaries.freq_hz
    where = f"{top:g} bar between {freqs.min():g} and {freqs.max():g} Hz"
    names = ", ".join(dict.fromkeys(c.parameter for c in study.cases))
    varied = _tongues_of_cases(study.cases)
    nominal = ("no tongue of the nominal driveline reaches " + where
               if not study.nominal.tongues else
               "no tongue of the nominal driveline that reaches " + where
               + " grows from a resonance of Fig. 14's numbering")
    head = ("<h2>What moves the tongues: sensitivity</h2>"
            f"<p>Each of {html.escape(names)} halved and doubled (Fig. 17, "
            f"18): {nominal}, so there is no tongue tip to rank.")
    if not varied and not study.nominal.tongues:
        return _keep(head + " Nor does any tongue reach it with these "
                     "variations: there is no boundary to draw.</p>")
    # the panels of the parameters whose variations have a tongue
    shown = {c.parameter for c in study.cases if c.tongues} or {
        c.parameter for c in study.cases}
    drawn = replace(sens, study=replace(
        study, cases=[c for c in study.cases if c.parameter in shown]))
    return _keep(
        head + (f" With the variations, tongues reach it at {varied}."
                if varied else "") + "</p>"
        + page.figure("Sensitivity of the stability boundary (Fig. 17, 18)",
                      drawn.figure(title=f"sensitivity, {page.description}")))


def threshold_section(page, values, study):
    """The friction-gradient threshold without dither (Fig. 19) of a
    registry driveline, from :func:`judder.threshold`."""
    return _keep(
        "<h2>Without dither: the friction-gradient threshold</h2>"
        f"<p>This study puts the mean pressure's damping into the slip "
        "damping (Eq. 2-4 taken literally, as Fig. 19 needs), while the "
        "maps above keep only the dither's fluctuating part (see "
        "docs/theory.md). With it, this driveline "
        f"is unstable without any dither for mu_g below "
        f"{study.study.threshold:.3g} s/rad (its mu_g is "
        f"{values['mu_g']:.3g} s/rad"
        + (", so it judders without dither" if values["mu_g"]
           < study.study.threshold else "")
        + ").</p>"
        + page.figure("Largest real part against mu_g and the threshold "
                      "against the external damping (Fig. 19)",
                      study.figure(stacked=True)))


def engagement_section(page, run, paper):
    """The held-slip bench run (or the class's run) through the FMU at
    the configured dither (Fig. 7, 8), read as a chart reads a bench run;
    ``paper``: a registry driveline (its bench model, held at a steady
    slip: it never engages) rather than a Modelica class."""
    from pysim.bench.engagement import judder_words
    first = run.summaries[0]
    return (
        ("<h2>The held-slip bench run" if paper else
         "<h2>The engagement of the class's FMU")
        + f"</h2><p>Through the {html.escape(run.model_class)} FMU"
        + ("" if not paper else
           f" (friction law: {html.escape(run.friction_law)})")
        + ("" if paper else " from its start values (a steady slip)")
        + ": upstream speed peak "
        f"{first['speed_peak_amplitude_rpm']:.3g} rpm at "
        f"{first['speed_peak_freq_hz']:.2f} Hz; read as a chart reads "
        "a bench run: " + html.escape(judder_words(first))
        + f"; Floquet exponent of the bench's linearisation (the "
        f"driveline with the damping of the bench's speed control, "
        f"so not section 1's) {first['floquet_exponent_per_s']:+.2f} 1/s"
        + ("" if first.get("orbit_kind") is None else
           "; the periodic orbit it settles on: " + orbit_words(first))
        + ("" if first.get("linearisation_holds") is not False else
           ". Nonlinear: " + nonlinear_words(first))
        + ".</p>"
        # one figure per run: side by side they were 13 in wide, printed
        # at half size
        + "".join(page.figure(
            f"{'Held-slip bench run' if paper else 'Engagement'} {label} "
            f"(Fig. {7 if index == 0 else 8})",
            run.figure(title=f"time-domain run {label}, "
                       f"{page.description}", only=index))
            for index, (label, _) in enumerate(run.runs)))


def fit_section(bench, names, values, source, fitted, error):
    """The fit to the bench data, shown only when the data
    determine every fitted value (else one sentence saying why not).

    ``fitted`` is the fit's result, or None with ``error`` the
    :class:`~infra.errors.JudderError` that refused it.

    Returns the section's HTML, its data (``fit``, ``fit_determined``,
    ``fit_status``, ``fit_problems``) and the fit report to draw (None when
    the fit is not shown)."""
    freqs, measured, tried, min_growth, below_bar, spread = bench
    onsets = int(np.sum(np.isfinite(measured)))
    head = _keep("<h2>The bench data and the fit</h2>"
                 f"<p>{len(freqs)} measured points from {source}, {onsets} "
                 f"with judder; fitting {', '.join(names)} to the model's "
                 f"boundary of judder growing at {min_growth:g} 1/s or "
                 "faster.</p>")
    if fitted is None:
        # in the report's own arguments: it fits `fit_names`, and a known
        # scatter is given to judder fit
        error = in_options(str(error), {"names": "`fit_names`",
                                        "scatter": "`scatter` of judder fit"})
        status = f"no fit: {error}"
        # the page, as the sensitivity section's, in the options typed
        return (head + "<p><b>No fit is shown</b>: "
                f"{html.escape(str(error))}"
                ".</p>", {"fit": None, "fit_determined": False,
                          "fit_status": status, "fit_problems": [str(error)]},
                None)
    r = fitted.fit
    problems = list(r.problems)
    if not r.determined:
        missing = list(r.undetermined) + [n for n in r.at_bound
                                          if n not in r.undetermined]
        status = ("no fit: the bench data do not determine "
                  + ", ".join(missing or r.names))
        return (head + f"<p><b>No fit is shown</b>: the bench data do not "
                f"determine {html.escape(', '.join(missing or r.names))}. "
                + " ".join(html.escape(p[0].upper() + p[1:]) + "."
                           for p in problems) + "</p>",
                {"fit": None, "fit_determined": False, "fit_status": status,
                 "fit_problems": problems}, None)
    lines = fitted.text()
    status = "fitted " + "; ".join(line.strip() for line in lines[:len(
        r.names)])
    rows = [(n, f"{s0:.5g}", format_uncertain(v, s, values.specs[n].unit),
             format_interval(lo, hi, s))
            for n, s0, v, s, lo, hi in zip(r.names, r.start, r.values, r.std,
                                           r.ci_low, r.ci_high)]
    text = (head + _table(("parameter", "start", "fitted ± 1 sigma",
                           "95 % interval"), rows)
            + "".join(f"<p>{html.escape(line)}</p>"
                      for line in lines[len(r.names):])
            + "".join(f"<p>problem: {html.escape(p)}</p>" for p in problems))
    return (text, {"fit": {n: {"value": v, "std": s, "ci95": [lo, hi]}
                           for n, v, s, lo, hi in zip(r.names, r.values,
                                                      r.std, r.ci_low,
                                                      r.ci_high)},
                   "fit_determined": True, "fit_status": status,
                   "fit_success": bool(r.success), "fit_problems": problems},
            fitted)


def chart_figure(page, chart, group):
    """The experimental stability chart (Fig. 10) of a chart file
    (``judder chart --out``) read back, as the fit's section shows it."""
    from pathlib import Path

    from pysim.bench.plots import runs_figure

    from .inputs import read_chart_runs
    title = Path(chart).name + (f", group {group}" if group else "")
    runs, boundary = read_chart_runs(chart, group)
    return page.figure("Experimental stability chart (Fig. 10)",
                       runs_figure(runs, boundary, title=title)) \
        + _estimated_dithers(runs)


#: Runs the report lists with a dither estimated from the pressure: the
#: least certain ones.
ESTIMATED_RUNS_LISTED = 10


def _estimated_dithers(runs):
    """The runs (:func:`studies.inputs.read_chart_runs`) whose dither
    frequency or amplitude was estimated from the pressure, the least
    certain amplitude first: the frequency and the amplitude each as
    estimated, with its standard uncertainty, or as given (an amplitude
    given beside the pressure's estimate of it), and what the sampling
    could not support or the estimate contradicts; "" where none was."""
    from pathlib import Path
    std = np.asarray(runs["p_f_std_bar"], dtype=float)
    estimated = np.flatnonzero(np.isfinite(std) & ~(
        runs["freq_given"] & runs["p_f_given"]))
    if not len(estimated):
        return ""
    pressure = np.asarray(runs["dither_p_f_bar"], dtype=float)
    relative = std[estimated] / np.maximum(pressure[estimated], 1e-300)
    order = estimated[np.argsort(-relative)][:ESTIMATED_RUNS_LISTED]

    def frequency(i):
        return (f"{runs['freq_hz'][i]:.4g} (given)" if runs["freq_given"][i]
                else format_uncertain(float(runs["freq_hz"][i]),
                                      float(runs["freq_std_hz"][i])))

    def amplitude(i):
        read = format_uncertain(float(pressure[i]), float(std[i]), "bar")
        return (f"{runs['p_f_bar'][i]:.4g} bar (given; the pressure's "
                f"{read})" if runs["p_f_given"][i] else read)
    rows = [(Path(str(runs["source_file"][i])).name, frequency(i),
             amplitude(i),
             # a frequency that may be an alias gives no verdict
             CANNOT_TELL.lower() if runs["dither_aliased"][i] else
             JUDDER.lower() if runs["judder"][i] else NO_JUDDER.lower(),
             str(runs["dither_warnings"][i]) or "-")
            for i in order]
    given = {name: int(np.count_nonzero(runs[key][estimated]))
             for name, key in (("frequency", "freq_given"),
                               ("amplitude", "p_f_given"))}
    return (f"<p>The dither of {len(estimated)} of the {len(std)} runs was "
            "estimated from the pressure (a least-squares sinusoid)"
            + "".join(f"; the {name} of {count} of them was given"
                      for name, count in given.items() if count)
            + ". The pressure's amplitudes are uncertain by "
            + (f"{100 * relative.min():.2g} to " if len(estimated) > 1
               else "") + f"{100 * relative.max():.2g} % (standard "
            "uncertainty)"
            + (f"; the {len(order)} least certain" if len(order) < len(
                estimated) else "") + ":</p>"
            + _table(("run", "dither frequency ± 1 sigma (Hz)",
                      "amplitude ± 1 sigma", "verdict",
                      "what the sampling cannot support, or contradicts"),
                     rows))


def driveline_section(values, modes):
    """The driveline (an appendix): natural frequencies, damping and the
    table of its parameters."""
    rows = [(name, f"{values[name]:.6g}", spec.unit, spec.description)
            for name, spec in values.specs.items()]
    # the table flows on (its rows are never split): a whole-section keep
    # left most of a page empty before this appendix
    return (_keep(
        "<h2>The driveline and its parameters</h2>"
        f"<p>Natural frequencies ({modes['natural_frequencies_from']}): "
        + ", ".join(f"{f:.3f} Hz" for f in modes["natural_frequencies_hz"])
        + ("" if modes["damping_factor_12"] is None else
           "; clutch-damper damping factor zeta_12 (Eq. 16): "
           f"{modes['damping_factor_12_percent']:.2f} %")
        + "; damped modes without dither: " + ", ".join(
            f"{m['frequency_hz']:.3f} Hz ({100 * m['damping_ratio']:.2f} %)"
            for m in modes["damped_modes"]) + ".</p>")
        + _table(("parameter", "value", "unit", "meaning"), rows))
