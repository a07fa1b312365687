#!/usr/bin/env python3
"""What FidelityFX SSSR's exit at low wave occupancy would save the traversal, from a frame's steps.

Usage: occupancy_exit.py ITERATIONS.exr [--lanes 32] [--handover 0,8]
ITERATIONS.exr is `sslr-render --dump --device-profile gpu`'s per-pixel step count (walk steps,
pixel tests and adaptive-L iterations; 0 where no ray ran), read through `oiiotool --dumpdata`.
A GPU group of --lanes invocations (8 x 8 work groups, invocations x-fastest: a 32-lane group is
four rows of a tile, a 64-lane one the whole tile) costs its slowest lane's steps. The exit
(ContextDesc::occupancyExit; FidelityFX SSSR's 4 of a full 32-lane wave) stops the lanes still
walking once they are at most an eighth of the n that traced, k = floor(n / 8); they hand their
ray to adaptive L (as at the step cap), at --handover more steps each. Per group the cost becomes
min(slowest, (k+1)-th slowest + handover) where k > 0, else the slowest.
Prints, per handover, the groups' summed cost against today's (the SIMT work the cost model
counts), the longest chain before and after, and the share of lanes the exit would stop."""
import sys

from render_io import read_image


def steps_of(path):
    width, height, rows = read_image(path)
    return width, height, [[v[0] if v else 0.0 for v in row] for row in rows]


def groups(width, height, rows, lanes):
    """Each group's lanes that traced (steps > 0); images are top row first, GL rows bottom first."""
    group_rows = lanes // 8
    for tile_y in range(0, height, 8):
        for tile_x in range(0, width, 8):
            for first in range(0, 8, group_rows):
                g = [rows[height - 1 - y][x]
                     for y in range(tile_y + first, min(tile_y + first + group_rows, height))
                     for x in range(tile_x, min(tile_x + 8, width))]
                g = [s for s in g if s > 0]
                if g:
                    yield sorted(g, reverse=True)


def main(argv):
    if not argv or argv[0].startswith('--'):
        sys.exit(__doc__)
    opt = {'--lanes': '32', '--handover': '0,8'}
    for i, a in enumerate(argv[1:]):
        if a in opt:
            opt[a] = argv[i + 2]
    lanes = int(opt['--lanes'])
    width, height, rows = steps_of(argv[0])
    gs = list(groups(width, height, rows, lanes))
    today = sum(g[0] for g in gs)
    chain = max((g[0] for g in gs), default=0)
    traced = sum(len(g) for g in gs)
    for handover in (float(h) for h in opt['--handover'].split(',')):
        cost = [min(g[0], g[len(g) // 8] + handover) if len(g) >= 8 else g[0] for g in gs]
        stopped = sum(sum(1 for s in g[:len(g) // 8] if s > g[len(g) // 8]) for g in gs if len(g) >= 8)
        print(f'{argv[0]}: {lanes}-lane groups {len(gs)}, exit at an eighth, handover {handover:g} steps: '
              f'SIMT work {sum(cost) / today if today else 1:.3f}x today\'s ({today:.0f}), '
              f'longest chain {chain:.0f} -> {max(cost, default=0):.0f}, '
              f'lanes stopped {stopped} of {traced} ({100.0 * stopped / max(traced, 1):.1f}%)')


if __name__ == '__main__':
    main(sys.argv[1:])
