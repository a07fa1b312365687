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
float noise). The last line counts the scenes.
"""
import csv
import sys

COLUMN = "compositeRmse"
TIE = 1e-6


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
    for scene, runs in scenes.items():
        def pick(method, label=None):
            return [r for r in runs if r["method"] == method and (label is None or r["label"] == label)]

        default = pick("adaptive-l", "high")
        if not default or float(default[0][COLUMN]) == 0.0:
            continue
        d = float(default[0][COLUMN])
        peers = {}
        cells = []
        hiz = pick("hiz", "steps112")
        if hiz:
            peers["traversal"] = float(hiz[0][COLUMN])
        cells.append(f"{peers['traversal']:.4f}" if hiz else "–")
        dda = sorted(pick("dda"), key=lambda r: float(r[COLUMN]))
        if dda:
            peers["dda " + dda[0]["label"]] = float(dda[0][COLUMN])
        cells.append(f"{float(dda[0][COLUMN]):.4f} ({dda[0]['label']})" if dda else "–")
        ffx = sorted(pick("ffx-sssr"), key=lambda r: float(r[COLUMN]))
        if ffx:
            peers["ffx " + ffx[0]["label"]] = float(ffx[0][COLUMN])
        cells.append(f"{float(ffx[0][COLUMN]):.4f} ({ffx[0]['label']}), {float(ffx[-1][COLUMN]):.4f}" if ffx else "–")
        tutorial = [r for r in pick("position-buffer") if r["default"] in ("1", "true", "True")]
        if tutorial:
            peers["tutorial"] = float(tutorial[0][COLUMN])
        cells.append(f"{peers['tutorial']:.4f}" if tutorial else "–")
        lower = [k for k, v in peers.items() if v < d * (1.0 - TIE)]
        counted += 1
        lower_somewhere += bool(lower)
        verdict = "yes" if not lower else "no: " + ", ".join(f"{k} {peers[k]:.4f}" for k in lower)
        print(f"| `{scene}` | {d:.4f} | " + " | ".join(cells) + f" | {verdict} |")
    print(f"\n{counted} scenes; the default is at most every peer's best on {counted - lower_somewhere}.")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
