"""What the scripts beside this one share: where sslr-render is built, running it (a failure
without a GL context is ctest's skip), and reading an image it wrote through `oiiotool`."""
import os
import re
import subprocess
import sys

ROOT = os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..')
DEFAULT_RENDER = os.path.join(ROOT, 'build', 'release', 'src', 'apps', 'sslr-render')


def run_render(script, render, args, env=None):
    """Runs `render args`; on failure prints its stderr under `script`'s name and exits: 77 (ctest's
    SKIP_RETURN_CODE, as the GL tests skip without a GL context) unless SSLR_REQUIRE_GL=1, then 1."""
    run = subprocess.run([render] + args, env=env, capture_output=True, text=True)
    if run.returncode != 0:
        print(f'{script}: {render} {" ".join(args)} failed:\n{run.stderr}', file=sys.stderr)
        sys.exit(1 if os.environ.get('SSLR_REQUIRE_GL') == '1' else 77)


def read_image(path):
    """(width, height, rows) of an image, rows[y][x] a tuple of its channels (RGBA order), the top
    row first, read through `oiiotool --dumpdata`."""
    text = subprocess.run(['oiiotool', '--dumpdata', path], check=True, capture_output=True, text=True).stdout
    m = re.search(r':\s+(\d+) x\s+(\d+)', text)
    width, height = int(m.group(1)), int(m.group(2))
    rows = [[()] * width for _ in range(height)]
    for x, y, values in re.findall(r'Pixel \((\d+), (\d+)\):([-0-9.e+ ]+)', text):
        rows[int(y)][int(x)] = tuple(float(v) for v in values.split())
    return width, height, rows
