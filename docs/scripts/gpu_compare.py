#!/usr/bin/env python3
"""The lean trace's GPU targets (#57) from gpu_compare.sh's log, as Markdown tables.

Usage: gpu_compare.py [gpu-out/compare.log]
- prepare() with the driver's shader caches off: each commit's default and FidelityFX SSSR
  (median of the rounds); target: the new default at most 2 s.
- Per scene and size: the frame (the sum of the passes' GL_TIMESTAMP medians) of the new default,
  FidelityFX SSSR at thickness 0.5, the baseline's default, the new half resolution and the new
  default with ContextDesc::occupancyExit; targets: default <= FFX SSSR's frame, half resolution
  <= 0.5x full (the exit: whether it wins, results/ray-work.md).
- A step: the trace pass's time per 10^5 SIMT steps (the 32-lane groups' slowest lane summed, as
  --stats counts them: walk steps, pixel tests and adaptive-L iterations alike) of the default
  against FFX SSSR's; target: at most 1.3x.
A figure the log lacks (a run out of time, a tool that failed) shows as a dash."""
import re
import statistics
import sys

PASSES = re.compile(r'pass times \(GL_TIMESTAMP, median[^)]*\): (.*)')
WORK = re.compile(r"ray work \([^)]*\): (.*)")
PREPARE = re.compile(r'prepare\(\) ([0-9.]+) ms')


def parse(path):
    commits, cold, frames, renderer = {}, {}, {}, None
    key = None
    for line in open(path, encoding='utf-8'):
        line = line.rstrip('\n')
        m = re.match(r'commit (\w+): (\S*)', line)
        if m:
            commits[m.group(1)] = m.group(2)
            continue
        m = re.match(r'== cold (\w+) (\S+) round', line)
        if m:
            key = ('cold', m.group(1), m.group(2))
            continue
        m = re.match(r'== frame (\w+) (\w+) (\S+) (\S+)', line)
        if m:
            key = ('frame', m.group(1), m.group(2), m.group(3), m.group(4))
            frames[key[1:]] = {}
            continue
        if line.startswith('=='):
            key = None
            continue
        if 'GL_RENDERER' in line and renderer is None:
            renderer = line.strip().split(' | ')[0]
        if key is None:
            continue
        if key[0] == 'cold':
            m = PREPARE.search(line)
            if m:
                cold.setdefault(key[1:], []).append(float(m.group(1)))
            continue
        rec = frames[key[1:]]
        m = PASSES.search(line)
        if m:
            ms = {name: float(v) for name, v in re.findall(r'(\w+) ([0-9.]+) ms', m.group(1))}
            rec['frame'] = sum(ms.values())
            rec['trace'] = ms.get('trace')
        m = WORK.search(line)
        if m:  # "trace a / b / c / d, ..., frame a / b / c / d (...)": the frame's 32-lane figure
            parts = dict((name.strip(), [int(x) for x in nums.split(' / ')])
                         for name, nums in re.findall(r'([a-z ]+?) ([0-9]+(?: / [0-9]+){3})', m.group(1)))
            if 'frame' in parts:
                rec['simt32'] = parts['frame'][1]
    return commits, cold, frames, renderer


def fmt(x, digits=3):
    return '–' if x is None else f'{x:.{digits}f}'


def ratio(a, b):
    return a / b if a is not None and b else None


def main(argv):
    path = argv[0] if argv else 'gpu-out/compare.log'
    commits, cold, frames, renderer = parse(path)
    print(f'{renderer or "renderer unknown"}; new {commits.get("new", "?")}, baseline {commits.get("base", "?")}\n')
    med = {k: statistics.median(v) for k, v in cold.items()}
    print('| prepare(), caches off (ms, median) | default | FidelityFX SSSR | default ÷ FFX |')
    print('|---|---|---|---|')
    for which in ('new', 'base'):
        d, f = med.get((which, 'default')), med.get((which, 'ffx-sssr'))
        print(f'| {which} | {fmt(d, 0)} | {fmt(f, 0)} | {fmt(ratio(d, f), 2)} |')
    d = med.get(('new', 'default'))
    verdict = '–' if d is None else ('met' if d <= 2000.0 else 'missed')
    print(f'\nTarget: the new default\'s cold prepare() at most 2 s: **{verdict}** ({fmt(d, 0)} ms).\n')

    print('| size | scene | default ms | FFX t0.5 ms | default ÷ FFX | baseline ms | new ÷ baseline '
          '| half ms | half ÷ full | occupancy exit ÷ default | step: default / FFX (ms per 10^5) | step ratio |')
    print('|---|---|---|---|---|---|---|---|---|---|---|---|')
    seen = []
    for (which, variant, scene, size) in frames:
        if (size, scene) not in seen:
            seen.append((size, scene))
    counts = {'frame': [0, 0], 'half': [0, 0], 'step': [0, 0]}
    for size, scene in seen:
        def get(which, variant, field):
            return frames.get((which, variant, scene, size), {}).get(field)
        new, ffx, base, half, exit_ = (get('new', 'default', 'frame'), get('new', 'ffx', 'frame'),
                                       get('base', 'default', 'frame'), get('new', 'half', 'frame'),
                                       get('new', 'exit', 'frame'))
        step_d = ratio(get('new', 'default', 'trace'), get('new', 'default', 'simt32'))
        step_f = ratio(get('new', 'ffx', 'trace'), get('new', 'ffx', 'simt32'))
        step_d = None if step_d is None else step_d * 1e5
        step_f = None if step_f is None else step_f * 1e5
        r_ffx, r_half, r_step = ratio(new, ffx), ratio(half, new), ratio(step_d, step_f)
        for name, r, limit in (('frame', r_ffx, 1.0), ('half', r_half, 0.5), ('step', r_step, 1.3)):
            if r is not None:
                counts[name][0 if r <= limit else 1] += 1
        print(f'| {size} | `{scene}` | {fmt(new)} | {fmt(ffx)} | {fmt(r_ffx, 2)} | {fmt(base)} | '
              f'{fmt(ratio(new, base), 2)} | {fmt(half)} | {fmt(r_half, 2)} | {fmt(ratio(exit_, new), 2)} | '
              f'{fmt(step_d)} / {fmt(step_f)} | '
              f'{fmt(r_step, 2)} |')
    print()
    for name, text in (('frame', 'the default at most FFX SSSR t0.5\'s frame'),
                       ('half', 'half resolution at most 0.5x full'),
                       ('step', 'a step at most 1.3x FFX SSSR\'s')):
        met, missed = counts[name]
        print(f'- Target: {text}: met on {met}, missed on {missed} of the runs above.')


if __name__ == '__main__':
    main(sys.argv[1:])
