#!/usr/bin/env python3
"""What choosing the tracer per tile could save the default: adaptive L alone on the tiles where it
holds, the default's traversal first on the others (#57, "choose the tracer per tile").

Usage: tile_choice.py [--render PATH] [--size WxH] [--jump 0.1] SCENE...
       tile_choice.py --self-test   (the tile accounting on images with known answers; ctest runs it)

For each scene it runs sslr-render (default build/release/src/apps/sslr-render) twice with
`--dump --device-profile gpu`: the default, and adaptive L alone (`--hiz-steps 0`). It reads each
run's hit.exr (uvHit, confidence, L) and iterations.exr (each pixel's dependent steps) through
`oiiotool --dumpdata`, and per 8x8 tile (the trace's work group; GL rows, bottom first; a 32-lane
group is four of its rows, x fastest) compares two choices with the default:
  - the oracle: adaptive L alone on every tile where its answer equals the default's at every
    traced pixel (both without a hit, or the same confidence within 0.05 and uvHit within a pixel);
    a bound, since nothing knows that before tracing;
  - adaptive L first: adaptive L alone on every pixel, then (after the group's vote) the default on
    the tiles where a traced pixel has no confident hit (confidence <= 0.5) or the hit lengths L
    of two neighbouring pixels differ by more than --jump of the shorter (an occluder's edge); such
    a tile pays for both, one after the other.
Each frame is priced with the H100 cost model (src/host/bench/cost_model.cpp, whose coefficients it
reads): a + b x longest chain + c x SIMT-32 work, the traversal's fit for the default's tiles and
adaptive L alone's c for the others (a and b: the traversal's, which the mixed frame still runs).
It prints the predicted time against the default's, the share of tiles adaptive L takes, and the
share of traced pixels whose answer then differs from the default's."""
import argparse
import os
import re
import statistics
import sys
import tempfile

from render_io import DEFAULT_RENDER, ROOT, read_image, run_render



def cost_model():
    """{'traversal': (a, b, c), 'alone': (a, b, c)} from cost_model.cpp."""
    path = os.path.join(ROOT, 'src', 'host', 'bench', 'cost_model.cpp')
    with open(path, encoding='utf-8') as f:
        text = f.read()
    fits = {}
    for key, name in (('traversal', 'kTraversal'), ('alone', 'kAdaptiveLAlone')):
        m = re.search(name + r'\{([^}]*)\}', text)
        if not m:
            sys.exit(f'tile_choice.py: no {name} in {path}')
        fits[key] = tuple(float(v) for v in m.group(1).split(','))
    return fits


def read_gl_rows(path):
    """(width, height, rows): rows[y][x] a tuple of the channels, GL rows (bottom first)."""
    width, height, rows = read_image(path)
    return width, height, rows[::-1]


def same_answer(a, b, width, height):
    """Whether two hit texels (uvHit, confidence, L) give the pixel the same answer."""
    if a[2] == 0.0 and b[2] == 0.0:
        return True
    return (abs(a[2] - b[2]) <= 0.05 and abs(a[0] - b[0]) * width <= 1.0 and
            abs(a[1] - b[1]) * height <= 1.0)


def adaptive_l_holds(hits, traced, jump):
    """Adaptive L first's test of a tile from its own hits: every traced pixel a confident hit, and no
    two neighbouring ones whose lengths differ by more than `jump` of the shorter."""
    if any(hits[p][2] <= 0.5 for p in traced):
        return False
    inside = set(traced)
    for (x, y) in traced:
        for n in ((x + 1, y), (x, y + 1)):
            if n in inside:
                a, b = hits[(x, y)][3], hits[n][3]
                if abs(a - b) > jump * min(a, b):
                    return False
    return True


def tile_choice(width, height, hit_default, steps_default, hit_alone, steps_alone, fits, jump):
    """The default's, the oracle's and adaptive L first's predicted frames. Images: rows[y][x], GL
    rows. Returns {choice: (ms, longest chain, share of tiles on adaptive L alone, share of traced
    pixels whose answer differs from the default's)}."""
    a, b, c = fits['traversal']
    c_alone = fits['alone'][2]
    work = {'default': [0.0, 0.0], 'oracle': [0.0, 0.0], 'first': [0.0, 0.0]}  # SIMT cost, chain
    alone_tiles = {'oracle': 0, 'first': 0}
    differ = {'oracle': 0, 'first': 0}
    tiles = traced_pixels = 0

    def at(image, p):
        return image[p[1]][p[0]]

    for ty in range(0, height, 8):
        for tx in range(0, width, 8):
            pixels = [(x, y) for y in range(ty, min(ty + 8, height)) for x in range(tx, min(tx + 8, width))]
            traced = [p for p in pixels if at(steps_default, p)[0] > 0 or at(steps_alone, p)[0] > 0 or
                      at(hit_default, p)[2] > 0]
            if not traced:
                continue
            tiles += 1
            traced_pixels += len(traced)
            halves = [[p for p in pixels if p[1] - ty in range(first, first + 4)] for first in (0, 4)]
            simt_default = sum(max(at(steps_default, p)[0] for p in h) for h in halves if h)
            simt_alone = sum(max(at(steps_alone, p)[0] for p in h) for h in halves if h)
            chain_default = max(at(steps_default, p)[0] for p in pixels)
            chain_alone = max(at(steps_alone, p)[0] for p in pixels)
            differing = sum(1 for p in traced if not same_answer(at(hit_default, p), at(hit_alone, p), width, height))

            def take(choice, cost, chain):
                work[choice][0] += cost
                work[choice][1] = max(work[choice][1], chain)

            take('default', c * simt_default, chain_default)
            if differing == 0:
                alone_tiles['oracle'] += 1
                take('oracle', c_alone * simt_alone, chain_alone)
            else:
                take('oracle', c * simt_default, chain_default)
            hits = {p: at(hit_alone, p) for p in traced}
            if adaptive_l_holds(hits, traced, jump):
                alone_tiles['first'] += 1
                differ['first'] += differing
                take('first', c_alone * simt_alone, chain_alone)
            else:  # both, with the group's barrier (its vote) between them
                take('first', c_alone * simt_alone + c * simt_default, chain_alone + chain_default)
    result = {}
    for choice, (cost, chain) in work.items():
        ms = a + b * chain + cost
        share = alone_tiles.get(choice, 0) / tiles if tiles else 0.0
        result[choice] = (ms, chain, share, differ.get(choice, 0) / traced_pixels if traced_pixels else 0.0)
    return result


def render_dumps(render, scene, size, out):
    """The default's and adaptive L alone's dump directories for one scene."""
    dirs = {}
    for name, extra in (('default', []), ('alone', ['--hiz-steps', '0'])):
        d = os.path.join(out, f'{scene}-{name}')
        run_render('tile_choice.py', render,
                   ['--scene', scene, '--size', size, '--dump', '--device-profile', 'gpu', '--out', d] + extra)
        dirs[name] = d
    return dirs


def self_test():
    """Two 8x8 tiles side by side, c = 1 and a = b = 0 for both fits so that a frame's cost is its
    SIMT-32 work. Left tile: adaptive L alone answers as the default does (2 steps against 10).
    Right tile: one pixel differs (adaptive L's hit two pixels off at row 2), and its L jumps there.
    Default: 10 + 10 per tile's two halves = 40. Oracle: left alone (2 + 2), right default (20):
    24. Adaptive L first: the left tile holds (4); the right one does not and pays both phases
    (4 + 20), 28 in all, its longest chain 2 + 10."""
    width, height = 16, 8
    steps_default = [[(10.0,)] * width for _ in range(height)]
    steps_alone = [[(2.0,)] * width for _ in range(height)]
    hit = [[((x + 0.5) / width, (y + 0.5) / height, 1.0, 5.0) for x in range(width)] for y in range(height)]
    hit_alone = [list(r) for r in hit]
    hit_alone[2][12] = (14.5 / width, 2.5 / height, 1.0, 9.0)
    fits = {'traversal': (0.0, 0.0, 1.0), 'alone': (0.0, 0.0, 1.0)}
    r = tile_choice(width, height, hit, steps_default, hit_alone, steps_alone, fits, 0.1)
    expected = {'default': (40.0, 10.0, 0.0, 0.0), 'oracle': (24.0, 10.0, 0.5, 0.0),
                'first': (28.0, 12.0, 0.5, 0.0)}
    if r != expected:
        sys.exit(f'tile_choice.py --self-test: got {r}, expected {expected}')
    # Without the jump test the right tile would pass too: its one differing pixel (of 128) is counted.
    r = tile_choice(width, height, hit, steps_default, hit_alone, steps_alone, fits, 10.0)
    if r['first'] != (8.0, 2.0, 1.0, 1.0 / 128.0):
        sys.exit(f'tile_choice.py --self-test: with --jump 10 got {r["first"]}, expected (8.0, 2.0, 1.0, 1/128)')
    print('tile_choice.py --self-test: passed')


def main():
    if sys.argv[1:] == ['--self-test']:
        return self_test()
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--render', default=DEFAULT_RENDER)
    ap.add_argument('--size', default='960x540')
    ap.add_argument('--jump', type=float, default=0.1)
    ap.add_argument('scenes', nargs='+')
    args = ap.parse_args()
    fits = cost_model()
    ratios = {'oracle': [], 'first': []}
    print(f'{"scene":24s} {"default ms":>10s}  {"oracle":>24s}  {"adaptive L first":>36s}')
    with tempfile.TemporaryDirectory(prefix='sslr-tiles-') as out:
        for scene in args.scenes:
            dirs = render_dumps(args.render, scene, args.size, out)
            images = []
            for name in ('default', 'alone'):
                w, h, hits = read_gl_rows(os.path.join(dirs[name], 'hit.exr'))
                _, _, steps = read_gl_rows(os.path.join(dirs[name], 'iterations.exr'))
                images += [hits, steps]
            if f'{w}x{h}' != args.size:
                sys.exit(f'tile_choice.py: {scene}: the dumps are {w}x{h}, not --size {args.size}')
            r = tile_choice(w, h, images[0], images[1], images[2], images[3], fits, args.jump)
            if not r['default'][1] > 0:
                sys.exit(f'tile_choice.py: {scene}: no traced pixel took a step (nothing to compare)')
            base = r['default'][0]
            for k in ratios:
                ratios[k].append(r[k][0] / base)
            print(f'{scene:24s} {base:10.3f}  {r["oracle"][0] / base:6.3f}x ({100 * r["oracle"][2]:5.1f}% of tiles)  '
                  f'{r["first"][0] / base:6.3f}x ({100 * r["first"][2]:5.1f}% of tiles, '
                  f'{100 * r["first"][3]:5.2f}% of px differ)')
    for k, name in (('oracle', 'oracle'), ('first', 'adaptive L first')):
        v = ratios[k]
        print(f'{name}: {min(v):.3f}-{max(v):.3f}x the default\'s predicted frame, median {statistics.median(v):.3f}x')


if __name__ == '__main__':
    main()
