#!/usr/bin/env python3
"""Markdown tables for docs/results.md from sslr-bench's results.json.

Usage: docs/scripts/results_tables.py BENCH_OUT/results.json > tables.md
Prints: the defaults per scene, the fastest configuration of each method reaching recall 0.95
(with ratios), the presets, the representations (depth against stored positions) and the cost
curves.
"""
import json
import sys
from collections import OrderedDict

TARGET = 0.95
METHODS = ["adaptive-l", "hiz", "dda", "position-buffer"]


def ms(v):
    """Milliseconds with three significant digits (a GPU's 0.123 ms and llvmpipe's 123 ms alike)."""
    return f"{v:.3g}" if v < 100 else f"{v:.0f}"


def main(path):
    with open(path) as f:
        r = json.load(f)
    runs = r["runs"]
    scenes = list(OrderedDict((x["scene"], 1) for x in runs))

    def of(scene, method=None):
        return [x for x in runs if x["scene"] == scene and (method is None or x["method"] == method)]

    print("### Defaults\n")
    print("| scene | method (default config) | time ms | × tutorial demo | recall@1px | p95 px | false hits | fetches/px |")
    print("|---|---|---|---|---|---|---|---|")
    for s in scenes:
        tut = next(x for x in of(s, "position-buffer") if x["default"])
        for m in METHODS:
            d = next((x for x in of(s, m) if x["default"]), None)
            if d is None:
                continue
            print(f"| {s} | {m} {d['label']} | {ms(d['timeMedianMs'])} | {d['timeMedianMs'] / tut['timeMedianMs']:.2f} | "
                  f"{d['recall1px']:.3f} | {d['p95ErrorPx']:.3f} | {100 * d['falseHitRate']:.2f}% | {d['fetchesPerTracedPixel']:.1f} |")

    print(f"\n### Fastest configuration of each method reaching recall@1px ≥ {TARGET}\n")
    print("| scene | adaptive L (any preset, ± fallback) | hierarchical alone | McGuire-Mara DDA | tutorial's march | DDA / adaptive L |")
    print("|---|---|---|---|---|---|")
    for s in scenes:
        cells, best = [], {}
        for m in METHODS:
            ok = [x for x in of(s, m) if x["recall1px"] is not None and x["recall1px"] >= TARGET]
            if ok:
                b = min(ok, key=lambda x: x["timeMedianMs"])
                best[m] = b
                cells.append(f"{b['label']}: {ms(b['timeMedianMs'])} ms ({b['recall1px']:.3f}, {100 * b['falseHitRate']:.2f}% false)")
            else:
                top = max(x["recall1px"] for x in of(s, m))
                cells.append(f"none (best {top:.3f})")
        ratio = (f"{best['dda']['timeMedianMs'] / best['adaptive-l']['timeMedianMs']:.2f}"
                 if "dda" in best and "adaptive-l" in best else "–")
        print(f"| {s} | " + " | ".join(cells) + f" | {ratio} |")

    print("\n### Presets (time, recall@1px)\n")
    presets = ["low", "medium", "high", "high-no-fallback", "high-inline", "high-deferred", "ultra"]
    print("| preset | " + " | ".join(scenes) + " |")
    print("|---|" + "---|" * len(scenes))
    for p in presets:
        row = []
        for s in scenes:
            x = next((x for x in of(s, "adaptive-l") if x["label"] == p), None)
            row.append(f"{ms(x['timeMedianMs'])} ms, {x['recall1px']:.3f}" if x else "–")
        print(f"| {p} | " + " | ".join(row) + " |")

    print("\n### Representations alone: depth versus stored position\n")
    print("| scene | median position error | max (relative) | hit agreement | recall@1px depth / stored |")
    print("|---|---|---|---|---|")
    for sc in r.get("scenes", []):
        print(f"| {sc['scene']} | {sc['positionErrorMedian']:.1e} | {sc['positionErrorMax']:.1e} "
              f"({sc['positionErrorMaxRelative']:.1e}) | {100 * sc['hitAgreementDepthVsStored']:.3f}% | "
              f"{sc['recall1pxDepth']:.4f} / {sc['recall1pxStored']:.4f} |")

    curves = r.get("costCurves", [])
    for curve in ("resolution", "fraction"):
        pts = [c for c in curves if c["curve"] == curve]
        if not pts:
            continue
        keys = list(OrderedDict(((c["width"], c["height"], c["reflectivePercent"]), 1) for c in pts))
        methods = list(OrderedDict((c["method"], 1) for c in pts))
        print(f"\n### Cost against {curve}\n")
        print("| point | traced share | " + " | ".join(f"{m} ms" for m in methods) + " | adaptive-l / baseline |")
        print("|---|---|" + "---|" * len(methods) + "---|")
        for k in keys:
            row = {c["method"]: c for c in pts if (c["width"], c["height"], c["reflectivePercent"]) == k}
            name = f"reflective-{k[2]}" if k[2] >= 0 else f"{k[0]}×{k[1]}"
            share = next(iter(row.values()))["tracedFraction"]
            ratio = row["adaptive-l"]["timeMedianMs"] / row["baseline"]["timeMedianMs"]
            print(f"| {name} | {share:.3f} | " + " | ".join(f"{ms(row[m]['timeMedianMs'])}" for m in methods)
                  + f" | {ratio:.2f} |")


if __name__ == "__main__":
    main(sys.argv[1])
