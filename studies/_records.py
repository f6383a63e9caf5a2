"""Small helpers of the result records: CSV text, and ``None`` for a
number that is not finite (strict JSON).
"""

import csv
import io
import math


def finite_or_none(value):
    """A float for JSON, None where it is NaN or infinite (undetermined,
    censored)."""
    value = float(value)
    return value if math.isfinite(value) else None


def rows_to_csv(rows, columns=None):
    """CSV of a list of dicts; None becomes an empty cell."""
    columns = list(columns or (rows[0] if rows else []))
    buffer = io.StringIO()
    writer = csv.writer(buffer, lineterminator="\n")
    writer.writerow(columns)
    for row in rows:
        writer.writerow(["" if row[c] is None else row[c] for c in columns])
    return buffer.getvalue()
