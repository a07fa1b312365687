// sslr-view: the module dropped into a GLFW window. A small deferred renderer (the tools'
// FrameRenderer: G-buffer pass with lighting and fallback specular, sslr dispatch, composite over
// the fallback) presented to the window, with a Dear ImGui panel for every setting, debug views,
// a split screen comparing two settings, per-pass timings, an error view of the hits against
// Embree and an image-error view of the composite against the ray-traced reference.
#pragma once

#include <string>
#include <vector>

namespace sslr::host {

struct ViewerOptions {
  std::string scene = "mirror-room";  // built-in name or .gltf/.glb path (files can be dropped on the window)
  bool mirrorFloor = false;           // add a mirror floor under the scene (models rarely have one)
  int width = 1280, height = 720;     // window (and G-buffer) size
  // Scripted runs (tests, CI): render `frames` frames (0 = until closed), orbiting the camera by
  // `orbitDegrees` per frame, then write the window to `screenshot` (PNG) and exit.
  int frames = 0;
  double orbitDegrees = 0.0;
  std::string screenshot;
  bool hideUi = false;      // no panel (the window shows the 3D view alone)
  std::string split;        // "" or a method name: compare it on the right half from the start
  std::string debugView;    // "" (final) or a debug view name, see viewer.cpp kViews
  bool stereo = false;      // two eyes through one context of two views (ContextDesc::views) from the start
};

// The names --view and --split accept (in the panel's order).
const std::vector<std::string>& viewerViewNames();
const std::vector<std::string>& viewerMethodNames();

// Runs the viewer; returns the process exit code (0, 1 on a GL/window failure with a message on
// stderr, 2 on a bad scene).
int runViewer(const ViewerOptions& options);

}  // namespace sslr::host
