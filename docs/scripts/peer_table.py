#!/usr/bin/env python3
"""The default's image error against every peer's best, per scene, from sslr-bench's results.csv.

Usage: docs/scripts/peer_table.py BENCH_OUT/results.csv > table.md
Needs a run with the composite reference and the peers' configurations, e.g.
  sslr-bench --grid full --configs "adaptive-l/high,hiz,dda,ffx-sssr,position-buffer" --scenes ...
      --size WxH --frames 1 --warmup 0 --no-curves --no-temporal --no-glossy
Prints one markdown row per scene with mirror pixels: the default (adaptive-l high), the traversal
alone at the default's step cap (hiz steps112), the best DDA and FFX SSSR configurations (FFX's
worst too), the tutorial, and whether the default is at most all of them. A peer counts as lower
only by more than one part in a million (two configurations that find the same hits differ by
float noise). The last line counts the scenes. Then, for each scene where a peer is lower, where
its gain lies: the default's and each lower peer's mean squared error (x 1e5, over all mirror
pixels) split by where the true reflection lies (the compositeVisible/Occluded/OffScreen/
EscapedShare columns): on the screen, a hidden side, off the screen, escaped.
"""
import csv
import sys

COLUMN = "compositeRmse"
TIE = 1e-6
TRUTH = [("on screen", "compositeVisibleShare"), ("hidden side", "compositeOccludedShare"),
         ("off screen", "compositeOffScreenShare"), ("escaped", "compositeEscapedShare")]


def by_truth(row):
    """The run's mean squared error by where the truth lies (x 1e5), None without the columns."""
    if any(row.get(c) in ("", None) for _, c in TRUTH):
        return None
    mse = float(row[COLUMN]) ** 2
    return [1e5 * mse * float(row[c]) for _, c in TRUTH]


def main(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    if not rows or COLUMN not in rows[0]:
        sys.exit(f"{path}: no {COLUMN} column (run sslr-bench with the composite reference)")
    scenes = {}
    for r in rows:
        if r[COLUMN] not in ("", None):
            scenes.setdefault(r["scene"], []).append(r)
    print("| scene | default | traversal alone (112) | best DDA | FFX SSSR best (worst) thickness | tutorial | default ≤ all? |")
    print("|---|---|---|---|---|---|---|")
    counted = lower_somewhere = 0
    gains = []
    for scene, runs in scenes.items():
        def pick(method, label=None):
            return [r for r in runs if r["method"] == method and (label is None or r["label"] == label)]

        default = pick("adaptive-l", "high")
        if not default or float(default[0][COLUMN]) == 0.0:
            continue
        d = float(default[0][COLUMN])
        peers = {}
        rows_of = {}
        cells = []
        hiz = pick("hiz", "steps112")
        if hiz:
            peers["traversal"] = float(hiz[0][COLUMN])
            rows_of["traversal"] = hiz[0]
        cells.append(f"{peers['traversal']:.4f}" if hiz else "–")
        dda = sorted(pick("dda"), key=lambda r: float(r[COLUMN]))
        if dda:
            peers["dda " + dda[0]["label"]] = float(dda[0][COLUMN])
            rows_of["dda " + dda[0]["label"]] = dda[0]
        cells.append(f"{float(dda[0][COLUMN]):.4f} ({dda[0]['label']})" if dda else "–")
        ffx = sorted(pick("ffx-sssr"), key=lambda r: float(r[COLUMN]))
        if ffx:
            peers["ffx " + ffx[0]["label"]] = float(ffx[0][COLUMN])
            rows_of["ffx " + ffx[0]["label"]] = ffx[0]
        cells.append(f"{float(ffx[0][COLUMN]):.4f} ({ffx[0]['label']}), {float(ffx[-1][COLUMN]):.4f}" if ffx else "–")
        tutorial = [r for r in pick("position-buffer") if r["default"] in ("1", "true", "True")]
        if tutorial:
            peers["tutorial"] = float(tutorial[0][COLUMN])
            rows_of["tutorial"] = tutorial[0]
        cells.append(f"{peers['tutorial']:.4f}" if tutorial else "–")
        lower = [k for k, v in peers.items() if v < d * (1.0 - TIE)]
        counted += 1
        lower_somewhere += bool(lower)
        verdict = "yes" if not lower else "no: " + ", ".join(f"{k} {peers[k]:.4f}" for k in lower)
        print(f"| `{scene}` | {d:.4f} | " + " | ".join(cells) + f" | {verdict} |")
        for k in lower:
            gains.append((scene, default[0], k, rows_of[k]))
    print(f"\n{counted} scenes; the default is at most every peer's best on {counted - lower_somewhere}.")
    split = [(scene, name, by_truth(dr), by_truth(pr)) for scene, dr, name, pr in gains]
    split = [x for x in split if x[2] is not None and x[3] is not None]
    if split:
        print("\n| scene | lower peer | " + " | ".join(f"{t}: default → peer" for t, _ in TRUTH) + " |")
        print("|---|---|" + "---|" * len(TRUTH))
        for scene, name, dv, pv in split:
            print(f"| `{scene}` | {name} | " + " | ".join(f"{a:.2f} → {b:.2f}" for a, b in zip(dv, pv)) + " |")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
