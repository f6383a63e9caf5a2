"""Runs read and judged, measured or simulated alike: the files benches
write, the judder verdict of one run, and the charts of many (section 3.2).

Bench files: :mod:`~pysim.bench.readers` reads a file through the reader
its suffix names in :data:`~pysim.bench.readers.READERS` (one private
module per format: ``_csv``, ``_mdf``, ``_tdms``, ``_mat``);
:mod:`~pysim.bench.acquisition` holds what is read (channel specs,
channels, acquisitions); :mod:`~pysim.bench.channels` picks the
channels by role and brings each into SI, in the units
:mod:`~pysim.bench.units` knows; :mod:`~pysim.bench.speed_channels`
tells what a speed channel's samples are.

Judging a run: :mod:`~pysim.bench.signals` (spectra, growth rates,
free-response fits), :mod:`~pysim.bench.dither` (the dither in a
pressure channel), :mod:`~pysim.bench.verdict` (the judder verdict of
one run) and :mod:`~pysim.bench.engagement` (what an engagement shows:
spectrum peaks, verdict, lock-up).

Charts: :mod:`~pysim.bench.charts` makes experimental stability charts
of many runs and :mod:`~pysim.bench.plots` draws them;
:mod:`~pysim.bench.run_plots` draws single runs (Fig. 7, 8).
"""
