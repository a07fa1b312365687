// sslr-view: fly around a scene with sslr in a window (GLFW + Dear ImGui); see viewer.hpp.
#include <cxxopts.hpp>

#include <algorithm>
#include <iostream>
#include <sstream>
#include <string>

#include "sslr_host/scene.hpp"
#include "sslr_host/image_io.hpp"
#include "sslr_host/viewer.hpp"

int main(int argc, char** argv) {
  using namespace sslr::host;
  removeTemporariesOnSignal();  // a screenshot being written when the viewer is interrupted
  auto joined = [](const std::vector<std::string>& names) {
    std::string out;
    for (const std::string& n : names) out += (out.empty() ? "" : ", ") + n;
    return out;
  };
  cxxopts::Options options("sslr-view", "Interactive viewer: sslr in a GLFW window with a Dear ImGui panel.");
  options.add_options()
      ("scene", "built-in scene or a .gltf/.glb file (files can also be dropped on the window)",
       cxxopts::value<std::string>()->default_value("mirror-room"))
      ("mirror-floor", "add a mirror floor under the scene (most models have nothing to reflect in)")
      ("size", "window size WxH", cxxopts::value<std::string>()->default_value("1280x720"))
      ("view", "initial view: " + joined(viewerViewNames()),
       cxxopts::value<std::string>()->default_value("final"))
      ("split", "compare against this method on the right half: " + joined(viewerMethodNames()),
       cxxopts::value<std::string>())
      ("stereo", "start in stereo: two eyes 0.064 apart traced by one context of two views, the window wiping "
                 "from the left eye to the right at its middle")
      ("frames", "render this many frames, then exit (0: until the window is closed)",
       cxxopts::value<int>()->default_value("0"))
      ("orbit", "scripted camera: degrees the camera orbits per frame", cxxopts::value<double>()->default_value("0"))
      ("screenshot", "after --frames, write the window to this PNG", cxxopts::value<std::string>())
      ("hide-ui", "no panel: the window shows the 3D view alone")
      ("h,help", "show this help");
  ViewerOptions vo;
  try {
    auto args = options.parse(argc, argv);
    if (args.count("help")) {
      std::cout << options.help() << "\nMouse: left drag orbits (fly: turns), wheel zooms. Keys: F orbit/fly, "
                                     "WASD QE fly, P screenshot + buffers into sslr-view-N/.\n";
      return 0;
    }
    vo.scene = args["scene"].as<std::string>();
    vo.mirrorFloor = args.count("mirror-floor") > 0;
    std::istringstream size(args["size"].as<std::string>());
    char x = 0;
    if (!(size >> vo.width >> x >> vo.height) || x != 'x' || !size.eof() || vo.width < 16 || vo.height < 16 ||
        vo.width > 8192 || vo.height > 8192)
      throw std::runtime_error("--size expects WxH with 16..8192 each (got '" + args["size"].as<std::string>() + "')");
    vo.debugView = args["view"].as<std::string>();
    const auto& views = viewerViewNames();
    if (std::find(views.begin(), views.end(), vo.debugView) == views.end())
      throw std::runtime_error("--view: unknown view '" + vo.debugView + "'");
    if (args.count("split")) {
      vo.split = args["split"].as<std::string>();
      const auto& methods = viewerMethodNames();
      if (std::find(methods.begin(), methods.end(), vo.split) == methods.end())
        throw std::runtime_error("--split: unknown method '" + vo.split + "'");
    }
    vo.frames = args["frames"].as<int>();
    if (vo.frames < 0) throw std::runtime_error("--frames must be >= 0");
    vo.orbitDegrees = args["orbit"].as<double>();
    if (args.count("screenshot")) {
      vo.screenshot = args["screenshot"].as<std::string>();
      if (vo.frames == 0) throw std::runtime_error("--screenshot needs --frames N (the frame to capture)");
      if (!vo.screenshot.ends_with(".png")) throw std::runtime_error("--screenshot " + vo.screenshot + ": name a .png file");
      if (sslr::Status st = checkOutputFile(vo.screenshot); !st) throw std::runtime_error("--screenshot " + st.message());
    }
    vo.hideUi = args.count("hide-ui") > 0;
    vo.stereo = args.count("stereo") > 0;
    if (vo.stereo && args.count("split")) throw std::runtime_error("--stereo and --split exclude each other");
    if (vo.stereo && vo.debugView != "final")  // the window shows the eyes' final images only
      throw std::runtime_error("--stereo shows the eyes' final images: --view " + vo.debugView + " needs one view");
  } catch (const std::exception& e) {
    std::cerr << "sslr-view: " << e.what() << "\nTry 'sslr-view --help'.\n";
    return 2;
  }
  return runViewer(vo);
}
