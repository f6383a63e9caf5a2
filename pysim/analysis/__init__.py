"""Time histories read, simulated or measured alike: spectra, growth
rates and free-response fits (:mod:`~pysim.analysis.signals`), and the
judder verdict of one run (:mod:`~pysim.analysis.verdict`)."""
