"""Bench data: acquisitions read from the files benches write, and the
experimental stability charts drawn from them (section 3.2).

:mod:`~pysim.bench_data.readers` reads a file through the reader its
suffix names in :data:`~pysim.bench_data.readers.READERS` (one private
module per format: ``_csv``, ``_mdf``, ``_tdms``, ``_mat``);
:mod:`~pysim.bench_data.acquisition` holds what is read (channel specs,
channels, acquisitions); :mod:`~pysim.bench_data.channels` picks the
channels by role and brings each into SI, in the units
:mod:`~pysim.bench_data.units` knows; :mod:`~pysim.bench_data.speed_channels`
tells what a speed channel's samples are; :mod:`~pysim.bench_data.charts`
makes experimental stability charts of many runs, and
:mod:`~pysim.bench_data.plots` draws them.
"""
