#!/usr/bin/env python3
"""Code and comment lines of a shader program with everything it includes (shaders/).

Usage: trace_lines.py [ENTRY] [--exclude NAME ...] [--per-function]
ENTRY defaults to shaders/3_trace.comp; the comparison tracers (sslr_trace_dda.h, sslr_trace_ffx.h,
sslr_trace_position.h) and the GGX lobe (ggx.h, GlossyMode::Stochastic's) are left out by default,
as the default program compiles none of their code; so is what only C++ sees (the lines, and the
includes, under #ifdef __cplusplus).
A code line is a non-blank line that is not only a // comment. --per-function also lists each
SSLR_FN function's code lines (for the rule ledger)."""
import os, re, sys

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', 'shaders')
COMPARISON = {'sslr_trace_dda.h', 'sslr_trace_ffx.h', 'sslr_trace_position.h', 'ggx.h'}


def glsl_lines(path):
    """The lines of `path` that GLSL sees: those outside a C++-only branch (#ifdef __cplusplus and
    its kin; an #else of one is GLSL's), preprocessor directives included."""
    cpp_only = []  # per open #if: whether its branch is C++'s alone
    for line in open(path, encoding='utf-8'):
        d = re.match(r'\s*#\s*(ifdef|ifndef|if|elif|else|endif)\b(.*)', line)
        if d:
            kind, rest = d.group(1), d.group(2)
            inside = any(cpp_only)
            if kind in ('ifdef', 'if'):
                cpp_only.append('__cplusplus' in rest and '!' not in rest)
            elif kind == 'ifndef':
                cpp_only.append(False)
            elif kind in ('else', 'elif') and cpp_only:
                cpp_only[-1] = False
            elif kind == 'endif' and cpp_only:
                cpp_only.pop()
            if not inside and not any(cpp_only):
                yield line
            continue
        if not any(cpp_only):
            yield line


def files_of(entry, exclude):
    seen, order = set(), []

    def visit(path):
        path = os.path.normpath(path)
        if path in seen or os.path.basename(path) in exclude:
            return
        seen.add(path)
        order.append(path)
        for line in glsl_lines(path):
            m = re.match(r'\s*#\s*include\s+"([^"]+)"', line)
            if m:  # relative to the including file, else to shaders/
                near = os.path.join(os.path.dirname(path), m.group(1))
                visit(near if os.path.exists(near) else os.path.join(ROOT, m.group(1)))

    visit(entry)
    return order


def count(path):
    code = comment = 0
    for line in glsl_lines(path):
        s = line.strip()
        if not s:
            continue
        if s.startswith('//'):
            comment += 1
        else:
            code += 1
    return code, comment


def functions(path):
    """(name, code lines) of each SSLR_FN function, by brace matching from its signature."""
    lines = open(path, encoding='utf-8').read().split('\n')
    out, i = [], 0
    while i < len(lines):
        m = re.match(r'SSLR_FN\s+\S+\s+(\w+)\(', lines[i])
        if not m:
            i += 1
            continue
        depth, n, j, opened = 0, 0, i, False
        while j < len(lines):
            s = lines[j].strip()
            if s and not s.startswith('//'):
                n += 1
            depth += lines[j].count('{') - lines[j].count('}')
            opened = opened or '{' in lines[j]
            j += 1
            if opened and depth == 0:
                break
        out.append((m.group(1), n))
        i = j
    return out


def main(argv):
    args = [a for a in argv if not a.startswith('--')]
    exclude = set(COMPARISON)
    if '--exclude' in argv:
        exclude |= set(argv[argv.index('--exclude') + 1:])
        args = args[:1]
    entry = args[0] if args else os.path.join(ROOT, '3_trace.comp')
    total_code = total_comment = 0
    paths = files_of(entry, exclude)
    for path in paths:
        code, comment = count(path)
        total_code += code
        total_comment += comment
        print(f'{code:5d} {comment:5d}  {os.path.relpath(path, ROOT)}')
        if '--per-function' in argv:
            for name, n in functions(path):
                print(f'{"":12s}{n:5d}  {name}')
    print(f'{total_code:5d} {total_comment:5d}  total: {len(paths)} files (code lines, comment lines)')


if __name__ == '__main__':
    main(sys.argv[1:])
