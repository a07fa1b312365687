// The host tools' GL loader: glad 2 (global symbols), generated at build time by Debian's
// python3-glad. The sslr library does not use it: it loads a private table of its own, which
// is exactly what a host with its own loader sees.
#pragma once
#include <glad/gl.h>
