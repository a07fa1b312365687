#!/usr/bin/env python3
"""Code lines of the trace programs as the driver compiles them: the default's and FFX SSSR's.

Usage: compiled_lines.py [--render PATH] [--size WxH] [-- SSLR_RENDER_ARGS...]
       compiled_lines.py --self-test   (the counting, on a source with known answers; ctest runs it)

trace_lines.py counts the shader files a program includes; this counts what the compiler gets.
It runs sslr-render (default build/release/src/apps/sslr-render) once with the default method and
once with --method ffx-sssr, with Mesa's MESA_SHADER_DUMP_PATH set, so that the driver writes
every compute shader's source as sslr handed it over (#defines, then the included files). For
each trace program (entry comment "Pass 3"), it drops #version, #extension and #line, runs the C
preprocessor (`cpp`, which GLSL's follows) with none of its own macros, and counts:
  - after the preprocessor: the lines that remain (not blank; the comments are gone);
  - compiled: the lines of the functions reachable from main(), plus every declaration outside a
    function (structs, the uniform block, buffers, constants), which is what the compiler keeps;
    split into the declarations, the functions the other method's trace programs reach too (the
    G-buffer loads, the projection, the shading: "shared") and the program's own.
A macro that spans lines counts as one. Needs a Mesa driver (llvmpipe) and `cpp`. If sslr-render
fails, it exits 77 (ctest: skipped, as the GL tests skip without a GL context) unless
SSLR_REQUIRE_GL=1, then 1."""
import argparse, os, re, subprocess, sys, tempfile

from render_io import DEFAULT_RENDER, run_render


def dump_programs(render, args):
    """{file name: source} of the compute shaders one sslr-render run compiled (its dump and its
    images in temporary directories, removed afterwards)."""
    with tempfile.TemporaryDirectory(prefix='sslr-shaders-') as dump, \
         tempfile.TemporaryDirectory(prefix='sslr-out-') as out:
        run_render('compiled_lines.py', render, ['--out', out] + args, dict(os.environ, MESA_SHADER_DUMP_PATH=dump))
        sources = {}
        for name in sorted(os.listdir(dump)):
            if name.startswith('CS_'):
                with open(os.path.join(dump, name), encoding='utf-8') as f:
                    sources[name] = f.read()
    if not sources:
        sys.exit('compiled_lines.py: the driver wrote no shader (MESA_SHADER_DUMP_PATH needs Mesa)')
    return sources


def preprocess(source):
    kept = [l for l in source.split('\n') if not re.match(r'\s*#\s*(version|extension|line)\b', l)]
    run = subprocess.run(['cpp', '-P', '-undef', '-nostdinc', '-x', 'c', '-'], input='\n'.join(kept),
                         capture_output=True, text=True)
    if run.returncode != 0:
        sys.exit(f'compiled_lines.py: cpp failed:\n{run.stderr}')
    return [l for l in run.stdout.split('\n') if l.strip()]


def top_level_items(lines):
    """The source split into top-level items (a function, a struct, a declaration)."""
    items, current, depth = [], [], 0
    for line in lines:
        current.append(line)
        depth += line.count('{') - line.count('}')
        if depth == 0 and line.rstrip().endswith(('}', ';')):
            items.append(current)
            current = []
    if current:
        items.append(current)
    return items


DEFINITION = re.compile(r'\s*(?:[\w\[\]]+\s+)+(\w+)\s*\([^;{]*\)\s*\{', re.S)


def count(lines):
    """(lines after the preprocessor, declaration lines, {function reachable from main: its lines},
    functions defined)."""
    functions, declarations = {}, 0
    for item in top_level_items(lines):
        text = '\n'.join(item)
        m = DEFINITION.match(text)
        if m and not re.match(r'\s*(struct|layout|uniform|buffer|shared)\b', text):
            functions.setdefault(m.group(1), []).append(item)
        else:
            declarations += len(item)
    calls = {name: set(re.findall(r'\b(\w+)\s*\(', '\n'.join('\n'.join(i) for i in items))) & functions.keys()
             for name, items in functions.items()}
    reached, stack = set(), ['main']
    while stack:
        name = stack.pop()
        if name in reached or name not in functions:
            continue
        reached.add(name)
        stack.extend(calls[name])
    return len(lines), declarations, {name: sum(len(i) for i in functions[name]) for name in reached}, len(functions)


def role(source):
    defines = set(re.findall(r'#define (SSLR_\w+)', source.split('#line', 1)[0]))
    if 'SSLR_METHOD_FFX' in defines:
        return 'FFX SSSR trace'
    if 'SSLR_DEFER_TRAVERSAL' in defines:
        return 'first stage (deferred)'
    if 'SSLR_RETRACE_ROLE' in defines:
        return 'whole tracer (inline trace and retrace)'
    return 'whole tracer'


SELF_TEST_SOURCE = r"""
struct S {
  float a;
};
layout(std140, binding = 0) uniform Frame {
  S s;
} frame;
const float K = 2.0;
float unused(float x) {
  return x * K;
}
float helper(float x) { return x + 1.0; }
float twice(float x) {
  if (x > 0.0) {
    return helper(helper(x));
  }
  return 0.0;
}
float sum(float x,
          float y) {
  return x + y;
}
void main() {
  float y = twice(frame.s.a) + sum(1.0, 2.0);
}
#define CALL(x) helper(x)
float viaMacro(float x) { return CALL(x); }
"""


def self_test():
    """count() and preprocess() on SELF_TEST_SOURCE: the struct (3 lines), the block (3) and the
    constant (1) are declarations; main (3), twice (6), sum (4: its signature spans two lines) and
    helper (1) are reached; `unused` (3) and `viaMacro` (1, reached by nothing though its macro
    names helper) are not."""
    lines = preprocess('#version 450 core\n#line 1 0\n' + SELF_TEST_SOURCE)
    after, declared, reached, defined = count(lines)
    expected = (len([l for l in SELF_TEST_SOURCE.split('\n') if l.strip() and not l.startswith('#')]),
                7, {'main': 3, 'twice': 6, 'sum': 4, 'helper': 1}, 6)
    if (after, declared, reached, defined) != expected:
        sys.exit(f'compiled_lines.py --self-test: got {(after, declared, reached, defined)}, expected {expected}')
    print('compiled_lines.py --self-test: passed')


def main():
    if sys.argv[1:] == ['--self-test']:
        return self_test()
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--render', default=DEFAULT_RENDER)
    ap.add_argument('--size', default='160x90')
    ap.add_argument('extra', nargs='*', help='more sslr-render arguments (after --)')
    a = ap.parse_args()
    programs = []  # (role, lines after cpp, declaration lines, reached functions' lines, functions defined)
    for method in ([], ['--method', 'ffx-sssr']):
        for source in dump_programs(a.render, ['--size', a.size] + method + a.extra).values():
            entry = re.search(r'^//.*', source, re.M)  # the entry file's first comment
            if entry and entry.group(0).startswith('// Pass 3, the trace'):
                programs.append((role(source),) + count(preprocess(source)))
    roles = {r for r, *_ in programs}
    if 'FFX SSSR trace' not in roles or len(roles) < 2:
        sys.exit(f'compiled_lines.py: found the trace programs {sorted(roles)}; expected the default\'s and '
                 'FFX SSSR\'s (did 3_trace.comp\'s first comment change from "// Pass 3, the trace"?)')
    # "shared": in functions the other method's trace programs reach too (depth-only against FFX).
    ffx = set().union(*(reached for r, _, _, reached, _ in programs if r == 'FFX SSSR trace'))
    depth = set().union(*(reached for r, _, _, reached, _ in programs if r != 'FFX SSSR trace'))
    print(f'{"program":40s} {"after cpp":>9s} {"compiled":>8s} {"declared":>8s} {"shared":>8s} '
          f'{"own":>5s}  functions reached/defined')
    for r, after, declared, reached, defined in programs:
        other = depth if r == 'FFX SSSR trace' else ffx
        shared = sum(n for name, n in reached.items() if name in other)
        own = sum(reached.values()) - shared
        print(f'{r:40s} {after:9d} {declared + shared + own:8d} {declared:8d} {shared:8d} {own:5d}  '
              f'{len(reached)}/{defined}')


if __name__ == '__main__':
    main()
