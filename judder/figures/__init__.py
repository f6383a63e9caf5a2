"""Figures of application results, one module per kind: they draw
:mod:`judder`'s own records (a plot lives with or above the result it
draws), over :mod:`stability.plots` and the look of :mod:`infra.plotstyle`:

* :mod:`~judder.figures.check`: ``judder check``'s settings and margins;
* :mod:`~judder.figures.advice`: ``judder advise``'s safe windows;
* :mod:`~judder.figures.crosscheck`: ``judder crosscheck``'s verdicts;
* :mod:`~judder.figures.compare`: ``judder compare``'s two maps;
* :mod:`~judder.figures.threshold`: ``judder threshold``'s Fig. 19.
"""
