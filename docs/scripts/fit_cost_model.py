#!/usr/bin/env python3
"""Fits the ray-work cost model to a GPU run's sslr-bench results and checks its predictions.

Per tracer, a frame's time t = a + b x longestChain + c x simt32 (least squares), over the
configurations whose frame is shaped as a GPU runs it by default: the Gpu profile, full
resolution, the traversal inline (the software profile, deferred and half-resolution
configurations are left out). Prints the coefficients (src/host/bench/cost_model.cpp holds
them), the error in the fit and with each scene left out of the fit; with --check, the error of
predictedH100Ms (the model in the code) against the times measured.

Usage: docs/scripts/fit_cost_model.py [--check] results.csv [results.csv ...]   (needs numpy)
"""
import csv
import sys

import numpy as np


def family(r):
    """Which fit a configuration belongs to; None where its frame is not shaped as fitted."""
    m, label = r["method"], r["label"]
    if m == "baseline":
        return None
    if m == "adaptive-l":
        if "software" in label or "deferred" in label or label == "high-half":
            return None
        return "adaptive-l alone" if label in ("low", "high-no-fallback") else "traversal"
    return "traversal" if m == "hiz" else m


def design(rows):
    return np.array([[1.0, float(r["longestChain"]), float(r["simt32"])] for r in rows])


def fit(rows):
    coef = {}
    for f in sorted({family(r) for r in rows}):
        sub = [r for r in rows if family(r) == f]
        if len(sub) >= 3:
            coef[f] = np.linalg.lstsq(design(sub), np.array([float(r["timeMedianMs"]) for r in sub]), rcond=None)[0]
    return coef


def errors(coef, rows):
    return np.array([abs(design([r])[0] @ coef[family(r)] / float(r["timeMedianMs"]) - 1.0) for r in rows])


def summary(e):
    return "median %.1f%%, 90th percentile %.1f%%, largest %.1f%%" % tuple(100 * np.percentile(e, [50, 90, 100]))


def main(argv):
    check = "--check" in argv
    files = [a for a in argv if a != "--check"]
    if not files:
        sys.exit(__doc__)
    rows = [r for f in files for r in csv.DictReader(open(f, newline="")) if family(r)]
    rows = [r for r in rows if float(r["simt32"]) > 0]
    coef = fit(rows)
    print("tracer: a (ms), b (ms per chain step), c (ms per 32-lane group step); configurations")
    for f, c in coef.items():
        print("  %-18s %.5f  %.5f  %.4e  (%d)" % (f, c[0], c[1], c[2], sum(family(r) == f for r in rows)))
    print("in the fit:", summary(errors(coef, rows)))
    left_out = []
    for scene in sorted({r["scene"] for r in rows}):
        left_out.extend(errors(fit([r for r in rows if r["scene"] != scene]), [r for r in rows if r["scene"] == scene]))
    print("each scene left out of the fit:", summary(np.array(left_out)))
    if check:
        e = np.array([abs(float(r["predictedH100Ms"]) / float(r["timeMedianMs"]) - 1.0)
                      for r in rows if r.get("predictedH100Ms")])
        print("predictedH100Ms against the times measured (%d configurations): %s" % (len(e), summary(e)))


if __name__ == "__main__":
    main(sys.argv[1:])
