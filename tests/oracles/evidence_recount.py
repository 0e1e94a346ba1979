"""What pd_oracle.py and roc_oracle.py both recount, straight from docs/evidence.md with no code
shared with owsim: a target's rows in a flight's truth.csv, and the Clopper-Pearson interval
(scipy.stats.beta.ppf). Imported by those scripts (their folder is first on sys.path)."""
import csv
import math
import os

from scipy.stats import beta


def target_rows(flight, target):
    """{object id: [truth.csv rows]} of TARGET (an object id or class:CLASS) in FLIGHT."""
    by_object = {}
    with open(os.path.join(flight, "truth.csv"), newline="") as f:
        for row in csv.DictReader(f):
            wanted = (row["class"] == target[6:]) if target.startswith("class:") else (
                row["object"] == target)
            if wanted:
                by_object.setdefault(row["object"], []).append(row)
    return by_object


def clopper_pearson(k, n, confidence):
    """The two-sided interval of k hits in n at CONFIDENCE; (nan, nan) when n is 0."""
    if n == 0:
        return (math.nan, math.nan)
    a = 1 - confidence
    lo = 0.0 if k == 0 else beta.ppf(a / 2, k, n - k + 1)
    hi = 1.0 if k == n else beta.ppf(1 - a / 2, k + 1, n - k)
    return (lo, hi)
