#include "sslr_host/egl_context.hpp"

#include <EGL/egl.h>
#include <EGL/eglext.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

#include "sslr_host/gl.hpp"

namespace sslr::host {

struct EglAccess {
  static void onDebugMessage(GLenum source, GLenum type, GLuint id, GLenum severity, GLsizei,
                             const GLchar* message, const void* user) {
    auto* self = static_cast<HeadlessContext*>(const_cast<void*>(user));
    if (type == GL_DEBUG_TYPE_ERROR) ++self->errors_;
    if (severity == GL_DEBUG_SEVERITY_HIGH) ++self->highSeverity_;
    if (severity == GL_DEBUG_SEVERITY_NOTIFICATION) return;
    // Push/pop group markers are informational.
    if (type == GL_DEBUG_TYPE_PUSH_GROUP || type == GL_DEBUG_TYPE_POP_GROUP) return;
    std::fprintf(stderr, "[GL %s] source 0x%x id %u: %s\n",
                 type == GL_DEBUG_TYPE_ERROR ? "error" : "debug", source, id, message);
  }
};

namespace {

bool hasExtension(const char* list, const char* name) {
  if (list == nullptr) return false;
  const size_t n = std::strlen(name);
  for (const char* p = list; (p = std::strstr(p, name)) != nullptr; p += n)
    if ((p == list || p[-1] == ' ') && (p[n] == ' ' || p[n] == '\0')) return true;
  return false;
}

std::string eglErrorText(const char* what) {
  char buf[128];
  std::snprintf(buf, sizeof buf, "%s failed (EGL error 0x%x)", what, eglGetError());
  return buf;
}

}  // namespace

sslr::GetProcAddress HeadlessContext::getProcAddress() {
  return reinterpret_cast<sslr::GetProcAddress>(&eglGetProcAddress);
}

bool HeadlessContext::isSoftware() const {
  return renderer_.find("llvmpipe") != std::string::npos ||
         renderer_.find("softpipe") != std::string::npos ||
         deviceDescription_.find("software") != std::string::npos;
}

namespace {
std::string deviceChoice(const std::string& device) {
  if (!device.empty()) return device;
  const char* env = std::getenv("SSLR_EGL_DEVICE");
  return env != nullptr && *env != '\0' ? env : "auto";
}
}  // namespace

Status HeadlessContext::checkDevice(const std::string& device) {
  const std::string choice = deviceChoice(device);
  const std::string from = device.empty() ? " ($SSLR_EGL_DEVICE)" : "";
  if (choice == "auto" || choice == "hardware" || choice == "software" || choice == "surfaceless") return {};
  if (choice.empty() || choice.size() > 3 || choice.find_first_not_of("0123456789") != std::string::npos)
    return Status::error("EGL device '" + choice + "'" + from +
                         " is not one of auto, hardware, software, surfaceless or an index");
  // An index: counted without creating a display or a context.
  auto queryDevices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
  EGLint count = 0;
  if (queryDevices == nullptr || !queryDevices(0, nullptr, &count))
    return Status::error("EGL device index " + choice + from + ": this EGL cannot list devices (no EGL_EXT_device_enumeration)");
  if (std::stoi(choice) >= count)
    return Status::error("EGL device index " + choice + from + " is out of range (" + std::to_string(count) + " devices)");
  return {};
}

namespace {

// The EGL display for the device choice (an index, hardware, software, surfaceless or auto), with
// a description of what it is.
struct OpenedDisplay {
  EGLDisplay display = EGL_NO_DISPLAY;
  std::string description;
};
Expected<OpenedDisplay> openDisplay(const std::string& choice) {
  const char* clientExts = eglQueryString(EGL_NO_DISPLAY, EGL_EXTENSIONS);
  // The EXT entry point: EGL 1.5's eglGetPlatformDisplay trips libepoxy-style wrappers.
  auto getPlatformDisplay = reinterpret_cast<PFNEGLGETPLATFORMDISPLAYEXTPROC>(
      eglGetProcAddress("eglGetPlatformDisplayEXT"));
  auto queryDevices = reinterpret_cast<PFNEGLQUERYDEVICESEXTPROC>(eglGetProcAddress("eglQueryDevicesEXT"));
  auto queryDeviceString =
      reinterpret_cast<PFNEGLQUERYDEVICESTRINGEXTPROC>(eglGetProcAddress("eglQueryDeviceStringEXT"));
  if (getPlatformDisplay == nullptr)
    return Status::error("EGL: eglGetPlatformDisplayEXT is missing (no EGL_EXT_platform_base)");

  EGLDisplay display = EGL_NO_DISPLAY;
  std::string description;
  const bool devicePlatform = hasExtension(clientExts, "EGL_EXT_platform_device") &&
                              queryDevices != nullptr && queryDeviceString != nullptr;
  if (devicePlatform && choice != "surfaceless") {
    EGLint count = 0;
    queryDevices(0, nullptr, &count);
    std::vector<EGLDeviceEXT> devices(static_cast<size_t>(std::max(count, 0)));
    if (count > 0) queryDevices(count, devices.data(), &count);
    // Order of preference: the requested index, else hardware devices, else software ones.
    std::vector<int> order;
    if (choice.find_first_not_of("0123456789") == std::string::npos) {
      const int index = std::atoi(choice.c_str());
      if (index >= count)
        return Status::error("EGL device index " + choice + " is out of range (" +
                             std::to_string(count) + " devices)");
      order.push_back(index);
    } else {
      for (int pass = 0; pass < 2; ++pass)
        for (int i = 0; i < count; ++i) {
          const bool software =
              hasExtension(queryDeviceString(devices[i], EGL_EXTENSIONS), "EGL_MESA_device_software");
          const bool wanted = pass == 0 ? !software && choice != "software"
                                        : software && choice != "hardware";
          if (wanted) order.push_back(i);
        }
    }
    for (int i : order) {
      EGLDisplay d = getPlatformDisplay(EGL_PLATFORM_DEVICE_EXT, devices[i], nullptr);
      if (d == EGL_NO_DISPLAY || !eglInitialize(d, nullptr, nullptr)) continue;
      const char* exts = queryDeviceString(devices[i], EGL_EXTENSIONS);
      description = "EGL device " + std::to_string(i) +
                    (hasExtension(exts, "EGL_MESA_device_software") ? " (software)" : " (hardware)");
      display = d;
      break;
    }
  }
  if (display == EGL_NO_DISPLAY && (choice == "auto" || choice == "surfaceless") &&
      hasExtension(clientExts, "EGL_MESA_platform_surfaceless")) {
    EGLDisplay d = getPlatformDisplay(EGL_PLATFORM_SURFACELESS_MESA, EGL_DEFAULT_DISPLAY, nullptr);
    if (d != EGL_NO_DISPLAY && eglInitialize(d, nullptr, nullptr)) {
      display = d;
      description = "EGL Mesa surfaceless platform";
    }
  }
  if (display == EGL_NO_DISPLAY)
    return Status::error("EGL: no usable display for device choice '" + choice +
                         "' (is libegl-mesa0 or an NVIDIA EGL driver installed?)");
  return OpenedDisplay{display, description};
}

}  // namespace

Expected<std::unique_ptr<HeadlessContext>> HeadlessContext::create(const EglOptions& options) {
  const std::string choice = deviceChoice(options.device);
  if (Status s = checkDevice(options.device); !s) return Status::error(s.message());

  auto opened = openDisplay(choice);
  if (!opened) return Status::error(opened.error());
  EGLDisplay display = opened.value().display;
  const std::string description = opened.value().description;

  if (!eglBindAPI(EGL_OPENGL_API)) return Status::error(eglErrorText("eglBindAPI(EGL_OPENGL_API)"));
  const EGLint attribs[] = {EGL_CONTEXT_MAJOR_VERSION, 4, EGL_CONTEXT_MINOR_VERSION, 5,
                            EGL_CONTEXT_OPENGL_PROFILE_MASK, EGL_CONTEXT_OPENGL_CORE_PROFILE_BIT,
                            EGL_CONTEXT_OPENGL_DEBUG, options.debug ? EGL_TRUE : EGL_FALSE, EGL_NONE};
  EGLContext context = eglCreateContext(display, EGL_NO_CONFIG_KHR, EGL_NO_CONTEXT, attribs);
  if (context == EGL_NO_CONTEXT) {
    std::string err = eglErrorText("eglCreateContext(OpenGL 4.5 core, no config)");
    eglTerminate(display);
    return Status::error("EGL: " + err);
  }
  if (!eglMakeCurrent(display, EGL_NO_SURFACE, EGL_NO_SURFACE, context)) {
    std::string err = eglErrorText("eglMakeCurrent(no surface)");
    eglDestroyContext(display, context);
    eglTerminate(display);
    return Status::error("EGL: " + err);
  }
  auto self = std::unique_ptr<HeadlessContext>(new HeadlessContext());
  self->display_ = display;
  self->context_ = context;
  if (gladLoadGL(reinterpret_cast<GLADloadfunc>(&eglGetProcAddress)) == 0)
    return Status::error("GL: glad could not load OpenGL entry points through eglGetProcAddress");
  self->renderer_ = reinterpret_cast<const char*>(glGetString(GL_RENDERER));
  self->version_ = reinterpret_cast<const char*>(glGetString(GL_VERSION));
  self->deviceDescription_ = description;
  GLint major = 0, minor = 0;
  glGetIntegerv(GL_MAJOR_VERSION, &major);
  glGetIntegerv(GL_MINOR_VERSION, &minor);
  if (major * 10 + minor < 45)
    return Status::error("GL: context is " + std::to_string(major) + "." + std::to_string(minor) +
                         ", OpenGL 4.5 core is required (" + self->renderer_ + ")");
  if (options.debug && GLAD_GL_KHR_debug) {
    glEnable(GL_DEBUG_OUTPUT);
    glEnable(GL_DEBUG_OUTPUT_SYNCHRONOUS);
    glDebugMessageCallback(&EglAccess::onDebugMessage, self.get());
  }
  if (!options.quiet)
    std::fprintf(stderr, "GL_RENDERER: %s | GL_VERSION: %s | %s\n", self->renderer_.c_str(),
                 self->version_.c_str(), description.c_str());
  return self;
}

HeadlessContext::~HeadlessContext() {
  if (display_ == nullptr) return;
  if (glDebugMessageCallback != nullptr) glDebugMessageCallback(nullptr, nullptr);
  eglMakeCurrent(display_, EGL_NO_SURFACE, EGL_NO_SURFACE, EGL_NO_CONTEXT);
  eglDestroyContext(display_, context_);
  eglTerminate(display_);
}

}  // namespace sslr::host
