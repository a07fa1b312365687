#!/usr/bin/env python3
"""Writes a .gltf whose external buffers and images are embedded as data: URIs, so the fuzzer's
single-file inputs load like the original with its .bin and image files beside it.

Usage: tests/fuzz/embed_external.py IN.gltf OUT.gltf   (exit 1: not JSON, or a file is missing)
"""
import base64
import json
import os
import sys
import urllib.parse


def main(src, dst):
    with open(src, "rb") as f:
        doc = json.loads(f.read())
    folder = os.path.dirname(os.path.abspath(src))
    for key, mime in (("buffers", "application/octet-stream"), ("images", "image/png")):
        for item in doc.get(key, []):
            uri = item.get("uri")
            if not isinstance(uri, str) or uri.startswith("data:"):
                continue
            path = os.path.join(folder, urllib.parse.unquote(uri))
            with open(path, "rb") as f:
                data = f.read()
            if key == "images" and data[:3] == b"\xff\xd8\xff":
                mime = "image/jpeg"
            item["uri"] = "data:%s;base64,%s" % (mime, base64.b64encode(data).decode())
    with open(dst, "w") as f:
        json.dump(doc, f, separators=(",", ":"))


if __name__ == "__main__":
    try:
        main(sys.argv[1], sys.argv[2])
    except (OSError, ValueError, KeyError, TypeError):
        sys.exit(1)
