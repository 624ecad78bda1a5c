"""Small numeric helpers: median of the known values, relative spread, straight-line fit."""

import statistics


def med(xs):
    xs = [x for x in xs if x is not None]
    return statistics.median(xs) if xs else None


def mad_rel(xs):
    """Median absolute deviation over the median: a robust run-to-run spread."""
    m = statistics.median(xs)
    return statistics.median(abs(x - m) for x in xs) / m if m > 0 else None


def fit_line(points):
    """Least-squares y = a + b x; returns (a, b)."""
    n = len(points)
    if n < 2:
        return None
    mx = sum(x for x, _ in points) / n
    my = sum(y for _, y in points) / n
    sxx = sum((x - mx) ** 2 for x, _ in points)
    if sxx <= 0:
        return None
    b = sum((x - mx) * (y - my) for x, y in points) / sxx
    return my - b * mx, b
