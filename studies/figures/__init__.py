"""Figures of application results, one module per kind: they draw
:mod:`judder`'s own records (a plot lives with or above the result it
draws), over :mod:`stability.plots` and the look of :mod:`infra.plotstyle`:

* :mod:`~studies.figures.check`: ``judder check``'s settings and margins;
* :mod:`~studies.figures.advice`: ``judder advise``'s safe windows;
* :mod:`~studies.figures.crosscheck`: ``judder crosscheck``'s verdicts;
* :mod:`~studies.figures.compare`: ``judder compare``'s two maps;
* :mod:`~studies.figures.threshold`: ``judder threshold``'s Fig. 19.
"""
