"""``judder report``: its numbers, and that a real browser renders it.

The browser is Debian's Chromium (``make browser`` installs it; ``make
test`` depends on that target). Without it the browser tests skip and say
so; everything else runs.
"""

import re
import shutil
import subprocess
from pathlib import Path

import numpy as np
import pytest

from infra.errors import JudderError
from matplotlib.image import imread

from judder.cli import main
from studies.inputs import load_parameters
from facts import names

ROOT = Path(__file__).resolve().parents[1]
EXAMPLES = ROOT / "examples"
CHROMIUM = shutil.which("chromium") or shutil.which("chromium-browser")
BROWSER_FLAGS = ("--headless", "--no-sandbox", "--disable-gpu",
                 "--disable-background-networking",
                 "--disable-component-update", "--disable-sync",
                 "--no-first-run")

#: Written into a copy of the report: once the page has loaded, every
#: image's state and decoded size go into an attribute of <body>.
PROBE = ("<script>window.addEventListener('load',()=>{document.body."
         "setAttribute('data-images',[...document.images].map(i=>i.complete"
         "+':'+i.naturalWidth+'x'+i.naturalHeight).join(' '));});</script>")


#: The smallest text (pt, as set) of each figure the module's report
#: embedded, in order (filled by the ``report`` fixture).
DRAWN = []
#: Texts of those figures that leave them or overlap another.
CLASHES = []


@pytest.fixture(autouse=True)
def _chain(chain_by_default):
    """This module pins the example chain's report."""



def _smallest_text_pt(fig):
    """The smallest font size (pt) of the visible, non-empty texts of a
    drawn figure: tick labels, titles, legends, tongue numbers."""
    from matplotlib.text import Text
    return min(t.get_fontsize() for t in fig.findobj(Text)
               if t.get_visible() and t.get_text().strip())


def _recording_figures(monkeypatch, drawn, clashes=None):
    """Let the report embed its figures as it does, and append each one's
    smallest text (pt) to ``drawn`` and its clipped or colliding texts
    (``test_figures``' check) to ``clashes``."""
    import sys
    sys.path.insert(0, str(ROOT / "tests"))
    from matplotlib.backends.backend_agg import FigureCanvasAgg
    from test_figures import _text_problems
    from studies import _report_sections as sections
    embed = sections._png

    def recording(fig, *args, **kwargs):
        img = embed(fig, *args, **kwargs)      # draws it
        drawn.append(_smallest_text_pt(fig))
        if clashes is not None:
            FigureCanvasAgg(fig)              # closed: a canvas again
            clashes.extend(_text_problems(fig))
        return img
    monkeypatch.setattr(sections, "_png", recording)


@pytest.fixture(scope="module")
def report(tmp_path_factory):
    """A report of the example driveline with a dither setting and the
    example boundary, on small grids."""
    folder = tmp_path_factory.mktemp("report")
    out = folder / "report.html"
    DRAWN.clear()
    CLASHES.clear()
    with pytest.MonkeyPatch.context() as patch:
        _recording_figures(patch, DRAWN, CLASHES)
        patch.setattr("stability.bench.default_driveline",
                      lambda values: "chain")
        status = _run_report(folder, out)
    assert status == 0
    return out


def _run_report(folder, out):
    return main(["report", "--param-file",
                 str(EXAMPLES / "driveline.toml"), "--freq", "105",
                 "--pf", "0.2", "--boundary",
                 str(EXAMPLES / "measured_boundary.csv"), "--fit", "mu_g",
                 "--sensitivity", "k24,mu_g", "--grid=10:220:60",
                 "--map-freq=5:250:40", "--map-pf=0:1.5:16",
                 "--workers=1", "--set", "mu_g=0.011", "--out",
                 str(out)]
                + (["--pdf", str(folder / "report.pdf")] if CHROMIUM
                 else []))


#: Smallest text a printed figure may have, pt.
READABLE_PT = 7.0


def _embedded_figures(page):
    """Each embedded PNG of a report: (its width in inches as drawn: pixels
    over the dots per inch of its pHYs chunk, the width its ``<img>``
    is given in inches, None if none)."""
    import base64
    import struct
    out = []
    for attributes, data in re.findall(
            r'<img([^>]*?)src="data:image/png;base64,([^"]+)"', page):
        png = base64.b64decode(data)
        width_px = struct.unpack(">I", png[16:20])[0]
        per_metre = struct.unpack(">I", png[png.index(b"pHYs") + 4:
                                            png.index(b"pHYs") + 8])[0]
        given = re.search(r'style="[^"]*width:\s*([\d.]+)in', attributes)
        out.append((width_px / (per_metre * 0.0254),
                    float(given.group(1)) if given else None))
    return out


def _text_width_in(page):
    """Text width of the printed page, inches: A4 less the left and right
    margins of the report's ``@page`` rule."""
    margins = re.search(r"@page\{size:A4;margin:([\d.]+)mm ([\d.]+)mm\}",
                        page)
    return (210.0 - 2 * float(margins.group(2))) / 25.4


def _assert_printed_text_readable(page, drawn):
    """Every figure's smallest text, at the scale it is printed (its
    given width, or the text width if narrower, over the width it was
    drawn at), is at least :data:`READABLE_PT`."""
    figures = _embedded_figures(page)
    assert len(figures) == len(drawn) > 0
    text_width = _text_width_in(page)
    for (drawn_in, given_in), smallest in zip(figures, drawn):
        printed_in = min(given_in or drawn_in, text_width)
        printed_pt = smallest * printed_in / drawn_in
        assert printed_pt >= READABLE_PT, (drawn_in, printed_in, smallest)


def test_report_figures_print_readable_text(report):
    """Issue 33: the report printed legends and ticks at 3.6-5.6 pt (a
    14 in figure on 184 mm); each figure is now drawn at the width it is
    printed, so its smallest text (7 pt) prints at 7 pt."""
    page = report.read_text()
    _assert_printed_text_readable(page, DRAWN)
    # drawn at the page's width, no text leaves its figure or collides
    assert CLASHES == [], "\n".join(CLASHES)
    figures = _embedded_figures(page)
    assert len(figures) == 7
    for drawn_in, given_in in figures:
        assert drawn_in == pytest.approx(given_in, abs=0.01)
        assert drawn_in <= _text_width_in(page)


def _text(html):
    return re.sub(r"<[^>]+>", " ", re.sub(r"<img[^>]*>", "", html))


def test_report_states_the_verdict_tips_ranking_and_fit(report):
    html = report.read_text()
    text = " ".join(_text(html).split())
    # 105 Hz, 0.2 bar is inside tongue 2 of the example driveline with
    # mu_g halved: `judder floquet --freq 105 --pf 0.2 --param-file
    # examples/driveline.toml --set mu_g=0.011` gives 1.000668, 0.0701 1/s
    # (one e-fold in 1 / 0.0701 = 14.3 s), slower than the judder-relevant
    # 1 1/s that `judder check` uses
    # and its settled oscillation, the chain's linear forced response
    # (26 rpm, under the 30 rpm limit)
    verdict = next(line for line in text.splitlines()
                   if "SLOW GROWTH at 105 Hz, 0.2 bar" in line)
    names(verdict, "tongue 2", "|\u03bb| = 1.0007", "26 rpm", "30 rpm",
          "0.0701 1/s", "14.3 s", "1 s engagement", "1 1/s")
    assert "(judder check --min-growth 1)" in text
    # tongue 2's tip, refined between grid points: 105.776 Hz, 0.1084 bar
    # (`judder tongues` on 500 frequencies; twice the 0.0542 bar of
    # mu_g = 0.022, as the tip scales with 1/mu_g)
    row = re.search(r"2 single-period f2 ([\d.]+) ([\d.]+) ([\d.]+)", text)
    assert float(row.group(1)) == pytest.approx(105.776, abs=0.01)
    assert float(row.group(2)) == pytest.approx(0.1084, abs=1e-4)
    # and where it judders (1 1/s), higher: the judder tip of `judder
    # tongues` on the report's grid
    assert "where each tongue becomes unstable (|lambda| = 1" in text
    from judder.api import tongues
    late = tongues(np.linspace(10, 220, 60), 1.5, load_parameters(
        param_file=EXAMPLES / "driveline.toml"), {"mu_g": 0.011})
    judder_tip = next(t for t in late.judder_tongues if t.number == 2)
    assert float(row.group(3)) == pytest.approx(
        judder_tip.tip_p_f / 1e5, abs=1e-4)
    assert float(row.group(3)) > float(row.group(2))
    # halving and doubling mu_g moves the tip by 100 % (tip ~ 1/mu_g),
    # more than k24 does: mu_g is ranked first
    ranking = re.search(r"tongue vanishes (\w+) ([\d.]+) [\d.]+ no (\w+)",
                        text)
    assert ranking.group(1) == "mu_g" and ranking.group(3) == "k24"
    assert float(ranking.group(2)) == pytest.approx(100.0, abs=0.5)
    # judder advise ranks design parameters (mu_g is not one): the report
    # says why the two rankings differ
    assert "puts mu_g first, judder advise puts" in text
    # the ranking's tip is the unstable one, said so (issue 33)
    names(text, "tongue 2's tip", "|lambda| = 1")
    assert "they answer different questions" in text
    # without dither: mu_g* = -1.25e-4 c_i with every c_i = 0.1
    assert "for mu_g below -1.25e-05 s/rad" in text
    # the example boundary was made from this set (mu_g = 0.022) with
    # 3 % noise: the fit, started at 0.011, finds it again
    fit = re.search(r"mu_g 0\.011 ([\d.]+) ± ([\d.]+) s/rad \[([\d.]+), "
                    r"([\d.]+)\]", text)
    assert float(fit.group(1)) == pytest.approx(0.022, rel=0.03)
    assert float(fit.group(3)) < 0.022 < float(fit.group(4))
    assert "scatter of the onsets:" in text
    # self-contained: every image is inline, nothing is fetched
    assert html.count("<img") == 7
    assert html.count('src="data:image/png;base64,') == 7
    assert not re.search(r'(src|href)="(?!data:)', html)


def _first_screen_and_numbers(html):
    """The text before the first figure, and the numbers of the <h2>
    headings in order."""
    first = " ".join(_text(html.split("<figure>")[0]).split())
    numbers = [int(n) for n in re.findall(r"<h2>(\d+)\. ", html)]
    return first, numbers


def test_report_opens_with_verdict_window_and_design(report):
    html = report.read_text()
    first, numbers = _first_screen_and_numbers(html)
    # the decision comes before any evidence: verdict, safe window,
    # design change (judder advise's numbers, not a paraphrase)
    verdict = first.index("SLOW GROWTH at 105 Hz")
    window = first.index("Safe dither window")
    design = first.index("Smallest design change")
    assert verdict < window < design
    from judder import api
    from studies.inputs import load_parameters
    example = load_parameters(param_file=EXAMPLES / "driveline.toml")
    advice = api.advise(example, {"mu_g": 0.011})
    for w in advice.windows:
        if w.full_range:
            assert f"{w.freq_hz[0]:.1f}-{w.freq_hz[1]:.1f} Hz" in first
    for name, factor in zip(advice.advice.names, advice.advice.factors):
        if abs(factor - 1) > 0.01:
            assert f"{name} x{factor:.2f}" in first
    assert (f"has {advice.judder_points} judder points of "
            f"{advice.verification.kind.size}") in first
    # sections numbered 1, 2, ... without a gap
    assert numbers == list(range(1, len(numbers) + 1)) and len(numbers) >= 7


def test_report_without_a_setting_still_gives_the_window(tmp_path):
    out = tmp_path / "r.html"
    status = main(["report", "--sensitivity", "k24", "--grid=10:220:40",
                   "--map-freq=5:250:20", "--map-pf=0:1.5:8",
                   "--workers=1", "--out", str(out)])
    assert status == 0
    first, numbers = _first_screen_and_numbers(out.read_text())
    assert first.index("No dither setting given (--freq, --pf)") \
        < first.index("Safe dither window Within 60-200 Hz")
    assert numbers == list(range(1, len(numbers) + 1))


def test_report_verdict_is_judder_check_at_its_growth_rate():
    # the same setting against the stability boundary (--min-growth 0):
    # judder, 0.2 bar above the boundary that `judder check` computes
    from judder import api
    from studies.inputs import load_parameters
    from studies._report_sections import verdict_text
    example = load_parameters(param_file=EXAMPLES / "driveline.toml")
    check = api.check([105.0], [0.2], example, {"mu_g": 0.011},
                      min_growth=0.0, sensitivity=())
    record = {**check.records()[0],
              "leading_abs": check.checks[0].floquet.leading_abs}
    text = verdict_text(record)
    assert text.startswith("JUDDER at 105 Hz, 0.2 bar")
    names(text, "tongue 2", "|\u03bb| = 1.0007", "26 rpm", "30 rpm",
          "parametric", "0.0701 1/s", "14.3 s")
    clause = next(c for c in text.split("; ")
                  if " bar above the judder boundary" in c)
    above = float(clause.split(" bar above the judder boundary")[0])
    # how far it may go, as check says it: no band, it judders
    names(text, "highest safe amplitude at 105 Hz",
          "no safe dither frequency")
    assert 0.2 - above == pytest.approx(record["boundary_p_f_bar"],
                                        abs=5e-4)
    assert 0 < above < 0.2


@pytest.mark.parametrize("args, words", [
    (["--freq", "105"], ["--freq and --pf go together"]),
    (["--freq", "105", "--pf", "-1"], ["--pf -1", ">= 0 bar"]),
    (["--sensitivity", "k99"], ["--sensitivity", "'k99'", "k12"]),
    (["--chart", "missing.npz"], ["--chart missing.npz"]),
    (["--grid", "0:220:10"], ["--grid 0 is not allowed", ">= 0.001"]),
])
def test_report_refuses_bad_input(args, words, tmp_path, capsys):
    out = tmp_path / "r.html"
    status = main(["report", *args, "--grid=10:220:10" if "--grid" not in
                   args else "--workers=1", "--map-freq=5:250:5",
                   "--map-pf=0:1.5:3", "--out", str(out)])
    assert status == 2
    err = capsys.readouterr().err
    assert err.startswith("judder: error:") and "Traceback" not in err
    for word in words:
        assert word in err
    assert not out.exists()


def _chromium(*args, cwd):
    return subprocess.run([CHROMIUM, *BROWSER_FLAGS,
                           f"--user-data-dir={cwd / 'profile'}", *args],
                          capture_output=True, text=True, timeout=120,
                          cwd=cwd)


@pytest.mark.skipif(CHROMIUM is None, reason="no chromium: run `make "
                    "browser` (Debian's chromium package)")
def test_report_renders_in_chromium(report, tmp_path):
    probe = tmp_path / "probe.html"
    probe.write_text(report.read_text().replace("</body>",
                                                PROBE + "</body>"))
    dom = _chromium("--virtual-time-budget=10000", "--dump-dom",
                    probe.as_uri(), cwd=tmp_path).stdout
    states = re.search(r'data-images="([^"]*)"', dom).group(1).split()
    assert len(states) == 7
    for state in states:
        complete, size = state.split(":")
        width, height = map(int, size.split("x"))
        assert complete == "true" and width > 300 and height > 300, state
    for words in ("Verdict and advice", "SLOW GROWTH at 105 Hz, 0.2 bar",
                  "Tongue tips",
                  "What moves the tongues", "The bench data and the fit"):
        assert words in dom
    # and it draws: a screenshot of the top of the page is not blank
    shot = tmp_path / "shot.png"
    _chromium("--window-size=1200,2400", f"--screenshot={shot}",
              report.as_uri(), cwd=tmp_path)
    pixels = imread(shot)[..., :3]
    dark = np.mean(pixels.mean(axis=2) < 0.6)
    assert 0.01 < dark < 0.6


@pytest.mark.skipif(CHROMIUM is None, reason="no chromium: run `make "
                    "browser` (Debian's chromium package)")
def test_report_prints_to_pdf(report):
    from infra.files import written_by_us
    pdf = (report.parent / "report.pdf").read_bytes()
    assert pdf.startswith(b"%PDF-")
    # marked as the tool's: a second run replaces it without --force
    assert written_by_us(report.parent / "report.pdf")
    # one page object per printed page: the report is several pages long
    assert len(re.findall(rb"/Type\s*/Page[^s]", pdf)) >= 3
    # A4 (595 x 842 pt), not Letter (612 x 792)
    boxes = re.findall(rb"/MediaBox\s*\[\s*0 0 ([\d.]+) ([\d.]+)", pdf)
    assert boxes
    for width, height in boxes:
        assert float(width) == pytest.approx(595.3, abs=1.0)
        assert float(height) == pytest.approx(841.9, abs=1.0)
    # the figures as Chromium printed them: each at the width it was
    # drawn, so its smallest text prints at its own size (>= 7 pt)
    printed = _printed_image_widths_in(pdf)
    figures = _embedded_figures(report.read_text())
    assert len(printed) == len(figures) == len(DRAWN)
    for printed_in, (drawn_in, _), smallest in zip(printed, figures, DRAWN):
        assert printed_in == pytest.approx(drawn_in, abs=0.02)
        assert smallest * printed_in / drawn_in >= READABLE_PT


def _printed_image_widths_in(pdf):
    """Width (inches) of each image a Chromium PDF draws, in page order:
    the unit square of each ``Do`` through the transformation matrices
    (``q``, ``Q``, ``cm``) of its page's content stream."""
    import zlib
    # a match never runs on into the next object (``endobj``): a tagged
    # PDF has dictionaries without a stream before a stream's
    within = rb"(?:(?!endobj).)*?"
    streams = {int(n): body for n, body in re.findall(
        rb"(\d+) 0 obj\s*<<" + within + rb">>\s*stream\r?\n(.*?)endstream",
        pdf, re.S)}
    widths = []
    for ref in re.findall(rb"/Type\s*/Page\b[^s]" + within
                          + rb"/Contents\s+(\d+) 0 R", pdf, re.S):
        matrix, saved = np.eye(3), []
        for line in zlib.decompress(streams[int(ref)]).decode(
                "latin-1").split("\n"):
            words = line.split()
            if line == "q":
                saved.append(matrix)
            elif line == "Q":
                matrix = saved.pop()
            elif words[-1:] == ["cm"] and len(words) == 7:
                a, b, c, d, e, f = map(float, words[:6])
                matrix = np.array([[a, b, 0], [c, d, 0], [e, f, 1]]) @ matrix
            elif words[-1:] == ["Do"]:
                left = np.array([0, 0, 1]) @ matrix
                right = np.array([1, 0, 1]) @ matrix
                widths.append(abs(right[0] - left[0]) / 72.0)
    return widths


def test_report_shows_no_fit_the_data_cannot_determine():
    # the README's chart: three onsets cannot give c12, mu_g and k24
    from studies.inputs import load_parameters
    from studies._report_sections import fit_section
    example = load_parameters(param_file=EXAMPLES / "driveline.toml")
    bench = (np.array([210.0, 212.0, 214.0]),
             np.array([0.8, 0.6, 0.8]) * 1e5, 0.8, 1.0,
             np.array([0.6, 0.4, 0.6]), 0.25)
    from studies.fit import fit
    freqs, measured, tried, growth, below, spread = bench
    with pytest.raises(JudderError) as refused:
        fit(freqs, measured / 1e5, tried, names=["c12", "mu_g", "k24"],
            parameters=example, starts=1, workers=1, min_growth=growth,
            below_bar=below, threshold_spread=spread)
    text, data, fitted = fit_section(bench, ("c12", "mu_g", "k24"),
                                     example, "chart.npz", None,
                                     refused.value)
    assert fitted is None and data["fit"] is None
    assert not data["fit_determined"]
    assert "No fit is shown" in text and "needs at least 5" in text
    assert data["fit_status"].startswith("no fit: the measured boundary has "
                                         "3 points with judder")
    # in the report's words: its `fit_names` (--fit on the command line),
    # a known scatter through judder fit (issue 33)
    from judder.commands._flags import in_flags
    assert "fit fewer parameters (`fit_names`)" in data["fit_status"]
    assert "(`scatter` of judder fit)" in data["fit_status"]
    assert "fit fewer parameters (--fit)" in in_flags(data["fit_status"])
    # the section names the study's arguments; the page judder report
    # writes speaks in the options typed (judder.commands.report)
    assert "fit fewer parameters (`fit_names`)" in text
    page = in_flags(text)
    assert "fit fewer parameters (--fit)" in page
    assert "(--scatter of judder fit)" in page and "`" not in page


def test_report_shows_the_experimental_chart_beside_the_fit(tmp_path):
    """Issue 31: with --chart the bench section shows the chart (Fig.
    10), whether or not a fit can be shown (here it cannot: one onset
    for three parameters)."""
    import sys
    sys.path.insert(0, str(ROOT / "tests"))
    from test_fitting import _synthetic_chart
    from studies.chart import ChartResult
    from studies.inputs import read_chart_runs
    from sources import get_preset
    chart, _ = _synthetic_chart(get_preset("paper-4dof-fitted"),
                                np.array([100.0, 105.0, 160.0]),
                                np.array([0.1, 0.2, 0.3]), limit_rpm=1e6)
    npz = tmp_path / "chart.npz"
    ChartResult(chart=chart, seconds=0.0).save(npz)
    runs, boundary = read_chart_runs(npz)
    assert len(runs["freq_hz"]) == 9 and runs["judder"].sum() == 1
    assert boundary == [(100.0, None, 0.3), (105.0, 0.3, 0.3),
                        (160.0, None, 0.3)]
    out = tmp_path / "report.html"
    drawn, clashes = [], []
    with pytest.MonkeyPatch.context() as patch:
        _recording_figures(patch, drawn, clashes)
        assert main(["report", "--chart", str(npz), "--grid=10:220:30",
                     "--map-freq=5:250:20", "--map-pf=0:1.5:8",
                     "--sensitivity", "mu_g", "--workers=1", "--out",
                     str(out)]) == 0
    page = out.read_text()
    assert "Experimental stability chart (Fig. 10)" in page
    assert "No fit is shown" in page
    # the chart (drawn by the bench-data module) prints readable too
    _assert_printed_text_readable(page, drawn)
    assert clashes == [], "\n".join(clashes)


def _pages_of_tables(pdf):
    """The pages (page object numbers) each table of a Chromium PDF is
    drawn on, in the order of its structure tree (Chromium tags its
    PDFs: a ``/S /Table`` element whose descendants' marked content
    lies on the pages their ``/Pg`` name)."""
    objects = {int(n): body for n, body in re.findall(
        rb"(\d+) 0 obj\s*(.*?)endobj", pdf, re.S)}

    def pages(number):
        body, out = objects[number], set()
        kids = re.search(rb"/K\s*(\[.*?\]|\d+ 0 R|\d+)", body, re.S)
        page = re.search(rb"/Pg\s+(\d+) 0 R", body)
        if kids is None:
            return out
        refs = [int(r) for r in re.findall(rb"(\d+) 0 R", kids.group(1))]
        if page and re.search(rb"\d", re.sub(rb"\d+ 0 R", b"",
                                             kids.group(1))):
            out.add(int(page.group(1)))        # marked content on it
        for ref in refs:
            if b"/StructElem" in objects.get(ref, b""):
                out |= pages(ref)
        return out
    return [pages(n) for n, body in sorted(objects.items())
            if re.search(rb"/S\s*/Table\b", body)]


@pytest.mark.skipif(CHROMIUM is None, reason="no chromium: run `make "
                    "browser` (Debian's chromium package)")
def test_printed_tables_never_split_across_pages(tmp_path):
    # six tables of 14 rows between paragraphs, with the report's style
    # sheet: without `break-inside: avoid` on tables, the third of them
    # straddled a page break (checked); with it each lies on one page
    from infra.pdf import print_pdf
    from studies._report_sections import Page, _table
    filler = "".join(f"<p>Filler paragraph {k} of the section.</p>"
                     for k in range(9))
    rows = [(f"J{k}", 0.1 * k, "kg m^2", "an inertia") for k in range(14)]
    page = Page(description="a test page")
    page.sections = [f"<h2>Section {k}</h2>{filler}<p>Table {k}:</p>"
                     + _table(("parameter", "value", "unit", "meaning"),
                              rows) for k in range(6)]
    html_path = tmp_path / "tables.html"
    html_path.write_text(page.html())
    print_pdf(html_path, tmp_path / "tables.pdf")
    tables = _pages_of_tables((tmp_path / "tables.pdf").read_bytes())
    assert len(tables) == 6
    assert len(set().union(*tables)) >= 3     # the page has several pages
    assert all(len(pages) == 1 for pages in tables), tables
