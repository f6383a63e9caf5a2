"""Numbers as an engineer reads them: a value with the digits its
uncertainty supports.

The uncertainty keeps two significant digits and the value is rounded to
the same decimal place (the GUM's convention, JCGM 100:2008, 7.2.6);
digits are grouped by threes with a space (SI brochure, 5.4.4) from
10 000 up; very large or small numbers share one power of ten.
"""

import math

__all__ = ["format_uncertain", "format_interval", "readable_number"]

#: Decimal places beyond which numbers are written with a power of ten.
_MAX_DECIMALS = 6


def _decimals(std):
    """Decimal places that keep two significant digits of ``std``."""
    return 1 - math.floor(math.log10(std))


def _group(text, separator=" "):
    """Digits grouped by threes from 10 000 up (``'34690'`` ->
    ``'34 690'``; ``'3856'`` stays)."""
    sign = "-" if text.startswith("-") else ""
    whole, _, fraction = text.lstrip("-").partition(".")
    if len(whole) > 4:
        head = len(whole) % 3 or 3
        whole = separator.join([whole[:head]] + [whole[i:i + 3] for i in
                                                 range(head, len(whole), 3)])
    return sign + whole + ("." + fraction if fraction else "")


def readable_number(value, digits=4):
    """``value`` to ``digits`` significant digits, without an exponent
    between 1e-3 and 1e7, grouped by a thin space from 10 000 on (for
    figures: 34 860, not 3.486e+04).

    Examples
    --------
    >>> readable_number(34858.1)
    '34\u2009860'
    >>> readable_number(0.0220), readable_number(3856.2), readable_number(2e9)
    ('0.022', '3856', '2e+09')
    """
    value = float(value)
    if value == 0 or not math.isfinite(value):
        return f"{value:g}"
    magnitude = math.floor(math.log10(abs(value)))
    if not -3 <= magnitude < 7:
        return f"{value:.{digits}g}"
    decimals = max(0, digits - 1 - magnitude)
    text = f"{round(value, digits - 1 - magnitude):.{decimals}f}"
    if decimals:
        text = text.rstrip("0").rstrip(".")
    return _group(text, "\u2009")


def _fixed(number, decimals):
    return _group(f"{round(number, decimals):.{max(decimals, 0)}f}")


def _scaled(value, std):
    """``(exponent, decimals)`` of the power-of-ten form, or
    ``(0, decimals)`` where fixed notation reads well."""
    decimals = _decimals(std)
    if decimals <= _MAX_DECIMALS and abs(value) < 1e9 and std < 1e9:
        return 0, decimals
    exponent = math.floor(math.log10(max(abs(value), std)))
    return exponent, decimals + exponent


def format_uncertain(value, std, unit=""):
    """``value +- std`` with the digits ``std`` supports.

    Parameters
    ----------
    value, std : float
        Value and standard uncertainty (``std`` infinite, NaN or zero:
        the value alone, with six significant digits).
    unit : str
        Appended after a space.

    Examples
    --------
    >>> format_uncertain(34690.8, 117.3, "N m/rad")
    '34 690 ± 120 N m/rad'
    >>> format_uncertain(0.0193698, 0.00095, "s/rad")
    '0.01937 ± 0.00095 s/rad'
    >>> format_uncertain(3.2e-9, 4.5e-10)
    '(3.20 ± 0.45)e-9'
    >>> format_uncertain(10.0, float("inf"), "N m s/rad")
    '10 N m s/rad'
    """
    suffix = f" {unit}" if unit else ""
    if not (math.isfinite(std) and std > 0 and math.isfinite(value)):
        return f"{value:.6g}{suffix}"
    exponent, decimals = _scaled(value, std)
    if exponent == 0:
        return f"{_fixed(value, decimals)} ± {_fixed(std, decimals)}{suffix}"
    scale = 10.0 ** exponent
    return (f"({value / scale:.{max(decimals, 0)}f} ± "
            f"{std / scale:.{max(decimals, 0)}f})e{exponent}{suffix}")


def format_interval(low, high, std):
    """``[low, high]`` with the digits of ``std`` (see
    :func:`format_uncertain`).

    Examples
    --------
    >>> format_interval(34450.2, 34931.7, 117.3)
    '[34 450, 34 930]'
    >>> format_interval(1.0, float("inf"), float("inf"))
    '[1, inf]'
    """
    if not (math.isfinite(std) and std > 0):
        return f"[{low:.6g}, {high:.6g}]"
    exponent, decimals = _scaled(max(abs(low), abs(high)) if math.isfinite(
        max(abs(low), abs(high))) else 0.0, std)
    if exponent == 0:
        return f"[{_fixed(low, decimals)}, {_fixed(high, decimals)}]"
    scale = 10.0 ** exponent
    d = max(decimals, 0)
    return f"[{low / scale:.{d}f}, {high / scale:.{d}f}]e{exponent}"
