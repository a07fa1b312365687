// Headless OpenGL 4.5 core context through EGL, without any window system.
#pragma once

#include <atomic>
#include <memory>
#include <string>

#include "sslr/sslr.hpp"

namespace sslr::host {

struct EglOptions {
  // "auto" (hardware device, else Mesa's software device, else surfaceless), "hardware",
  // "software", "surfaceless", or a device index "0", "1", ... Default: $SSLR_EGL_DEVICE or auto.
  std::string device;
  bool debug = true;          // debug context; KHR_debug messages go to the log
  bool quiet = false;         // do not print the chosen device / renderer
};

class HeadlessContext {
 public:
  static Expected<std::unique_ptr<HeadlessContext>> create(const EglOptions& options = {});
  // Whether `device` (EglOptions::device; "" reads $SSLR_EGL_DEVICE) names a choice create() can
  // make: a tool checks it with its other options, before any GL work.
  static Status checkDevice(const std::string& device);
  ~HeadlessContext();
  HeadlessContext(const HeadlessContext&) = delete;
  HeadlessContext& operator=(const HeadlessContext&) = delete;

  const std::string& renderer() const { return renderer_; }  // GL_RENDERER
  const std::string& version() const { return version_; }    // GL_VERSION
  const std::string& deviceDescription() const { return deviceDescription_; }
  bool isSoftware() const;  // llvmpipe / softpipe: time with the CPU clock, not timer queries

  // GL errors (KHR_debug type ERROR) seen since creation; tests assert this stays 0.
  int glErrorCount() const { return errors_.load(); }
  void resetGlErrorCount() { errors_ = 0; highSeverity_ = 0; }
  // KHR_debug messages of GL_DEBUG_SEVERITY_HIGH since creation (errors and, on some drivers,
  // shader compiler warnings): an engine that stops on them would stop; tests assert none.
  int highSeverityCount() const { return highSeverity_.load(); }

  static sslr::GetProcAddress getProcAddress();

 private:
  HeadlessContext() = default;
  void* display_ = nullptr;
  void* context_ = nullptr;
  std::string renderer_, version_, deviceDescription_;
  std::atomic<int> errors_{0}, highSeverity_{0};
  friend struct EglAccess;
};

}  // namespace sslr::host
