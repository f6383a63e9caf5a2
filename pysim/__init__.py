"""Time-domain engagement simulation with fmpy and bench-data processing.

Empty until the FMUs exist (see the README's roadmap): it will drive the
FMUs built by ``make fmu`` and turn bench time histories into experimental
stability charts.
"""
