"""Results in words, as the commands print them and the report writes
them: a check's growth against an engagement and both margins, and an
engagement's periodic orbit and nonlinearity."""

from infra.criteria import NO_JUDDER


def _named(tongue):
    """`` (tongue N)`` of a record's tongue, or nothing."""
    return "" if tongue is None else f" (tongue {tongue['number'] or '?'})"


def growth_words(record, engagement_s):
    """The growth of a record in words: rate, e-folding time against an
    engagement of ``engagement_s`` seconds."""
    rate = record["growth_rate_per_s"]
    if record["e_folding_time_s"] is None:
        return f"decays at {-rate:.3g} 1/s"
    efold = record["e_folding_time_s"]
    return (f"grows at {rate:.3g} 1/s, one e-fold in {efold:.3g} s ("
            + ("longer than" if efold > engagement_s else "within")
            + f" a {engagement_s:g} s engagement)")


def margin_words(record):
    """Both margins of a record in plain words (amplitude, frequency),
    the amplitude one with where the setting's frequency becomes unstable
    (|lambda| = 1) as well as judder (growth >= min-growth)."""
    bar = record["margin_bar"]
    rate = f">= {record['min_growth_per_s']:g} 1/s"
    tongue = record["margin_bar_tongue"]
    which = f"({rate})" if tongue is None else \
        f"({rate}, tongue {tongue['number'] or '?'})"
    top = record["p_f_bar"] + (record["margin_bar_at_least"] or 0.0)
    unstable = record.get("unstable_boundary_p_f_bar")
    here = f" at {record['freq_hz']:g} Hz"
    if record["min_growth_per_s"] == 0 or unstable is None:
        onset = ""
    else:
        onset = f"; unstable (|lambda| > 1){here} from {unstable:.3f} bar"
    if bar is None and unstable is None:
        amplitude = f"stable (|lambda| < 1){here} up to {top:.3g} bar"
    elif bar is None:
        amplitude = f"no judder ({rate}){here} up to {top:.3g} bar" + onset
    elif bar >= 0:
        amplitude = f"{bar:.3f} bar below judder {which}" + onset
    else:
        amplitude = (f"{-bar:.3f} bar above the judder boundary {which}"
                     + onset)
    hz = record["margin_hz"]
    if hz is None:
        search = record["frequency_search_hz"]
        frequency = (f"no dither frequency has parametric judder at "
                     f"{record['p_f_bar']:g} bar" + ("" if search is None else
                              f" in the range searched, {search[0]:.3g} to "
                              f"{search[1]:.3g} Hz (from a quarter of the "
                              "lowest to four times the highest setting)"))
    elif hz > 0:
        frequency = (f"parametric judder begins {hz:.2f} Hz away, at "
                     f"{record['crossing_hz']:.2f} Hz"
                     + _named(record["margin_hz_tongue"]))
    else:
        frequency = (f"inside a band of parametric judder that ends "
                     f"{-hz:.2f} Hz away, at {record['crossing_hz']:.2f} Hz"
                     + _named(record["margin_hz_tongue"]))
    return amplitude, frequency


def orbit_words(summary):
    """The periodic orbit an engagement settles on, in words (an
    engagement summary of :func:`judder.simulate`): its size, kind,
    growth and whether it judders; '' without one."""
    if summary.get("orbit_kind") is None:
        return ""
    return (f"{summary['orbit_settled_rpm']:.3g} rpm, "
            f"{summary['orbit_kind']} "
            f"({summary['orbit_growth_per_s']:+.2f} 1/s), "
            + (f"judder ({summary['orbit_mechanism']})"
               if summary["orbit_mechanism"] else NO_JUDDER.lower()))


def nonlinear_words(summary):
    """Why an engagement need not follow the Floquet verdict (the
    dither's forced slip swing beyond the friction curve's linear range),
    in words; '' where the linearisation holds."""
    if summary.get("linearisation_holds") is not False:
        return ""
    return (f"the dither's forced slip swing "
            f"(+-{summary['forced_slip_amplitude_rad_s']:.2g} rad/s) exceeds "
            f"the friction curve's linear range "
            f"(+-{summary['friction_linear_range_rad_s']:.2g} rad/s), so the "
            "run need not follow the Floquet verdict")


def response_words(record):
    """The settled oscillation and the mechanism, in words."""
    words = (f"settled oscillation {record['settled_amplitude_rpm']:.3g} "
             f"rpm (limit {record['judder_limit_rpm']:g} rpm"
             + (f", quasi-periodic, integrated over "
                f"{record['integrated_s']:.1f} s" if record["quasi_periodic"]
                and record["integrated_s"] else "")
             + ")")
    if not record["converged"]:
        words += " (the orbit did not converge: no verdict from it)"
    if record["mechanism"]:
        words += f", {record['mechanism']}"
    return words
