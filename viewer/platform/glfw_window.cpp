// GLFW window (see glfw_window.hpp).
#define GLFW_INCLUDE_NONE
#include "platform/glfw_window.hpp"

#include <GLFW/glfw3.h>

#include <stdexcept>

#include "platform/gl.hpp"

namespace globe::viewer {

namespace {
GlfwWindowState& state_of(GLFWwindow* w) {
  return *static_cast<GlfwWindowState*>(glfwGetWindowUserPointer(w));
}
WindowCallbacks& callbacks_of(GLFWwindow* w) {
  return state_of(w).callbacks;
}
}  // namespace

GlfwWindow::GlfwWindow(int width, int height, const std::string& title, WindowCallbacks callbacks)
    : state_{std::move(callbacks), 0} {
  if (!glfwInit()) throw std::runtime_error("GLFW cannot open the display");
  glfwWindowHint(GLFW_CONTEXT_VERSION_MAJOR, 4);
  glfwWindowHint(GLFW_CONTEXT_VERSION_MINOR, 5);
  glfwWindowHint(GLFW_OPENGL_PROFILE, GLFW_OPENGL_CORE_PROFILE);
  glfwWindowHint(GLFW_OPENGL_FORWARD_COMPAT, GLFW_TRUE);
  window_ = glfwCreateWindow(width, height, title.c_str(), nullptr, nullptr);
  if (!window_) {
    glfwTerminate();
    throw std::runtime_error("GLFW: cannot open a window with an OpenGL 4.5 core context");
  }
  glfwMakeContextCurrent(window_);
  glfwSwapInterval(1);
  gl::load([](const char* name) { return reinterpret_cast<void*>(glfwGetProcAddress(name)); });
  glfwSetWindowUserPointer(window_, &state_);
  glfwSetKeyCallback(window_, [](GLFWwindow* w, int key, int, int action, int mods) {
    ++state_of(w).events;
    if (action != GLFW_RELEASE && callbacks_of(w).on_key) callbacks_of(w).on_key(key, mods);
  });
  glfwSetMouseButtonCallback(window_, [](GLFWwindow* w, int button, int action, int) {
    ++state_of(w).events;
    double x = 0, y = 0;
    glfwGetCursorPos(w, &x, &y);
    if (callbacks_of(w).on_button) callbacks_of(w).on_button(button, action == GLFW_PRESS, x, y);
  });
  glfwSetCursorPosCallback(window_, [](GLFWwindow* w, double x, double y) {
    ++state_of(w).events;
    if (callbacks_of(w).on_cursor) callbacks_of(w).on_cursor(x, y);
  });
  glfwSetScrollCallback(window_, [](GLFWwindow* w, double, double dy) {
    ++state_of(w).events;
    const int mods = (glfwGetKey(w, GLFW_KEY_LEFT_SHIFT) == GLFW_PRESS ||
                              glfwGetKey(w, GLFW_KEY_RIGHT_SHIFT) == GLFW_PRESS
                          ? GLFW_MOD_SHIFT
                          : 0) |
                     (glfwGetKey(w, GLFW_KEY_LEFT_CONTROL) == GLFW_PRESS ||
                              glfwGetKey(w, GLFW_KEY_RIGHT_CONTROL) == GLFW_PRESS
                          ? GLFW_MOD_CONTROL
                          : 0);
    if (callbacks_of(w).on_scroll) callbacks_of(w).on_scroll(dy, mods);
  });
  // Resized, uncovered, focused: draw again.
  glfwSetFramebufferSizeCallback(window_, [](GLFWwindow* w, int, int) { ++state_of(w).events; });
  glfwSetWindowRefreshCallback(window_, [](GLFWwindow* w) { ++state_of(w).events; });
}

GlfwWindow::~GlfwWindow() {
  glfwDestroyWindow(window_);
  glfwTerminate();
}

bool GlfwWindow::should_close() const {
  return glfwWindowShouldClose(window_);
}
void GlfwWindow::close() {
  glfwSetWindowShouldClose(window_, GLFW_TRUE);
}
void GlfwWindow::poll() {
  glfwPollEvents();
}
void GlfwWindow::wait(double seconds) {
  glfwWaitEventsTimeout(seconds);
}
void GlfwWindow::swap() {
  glfwSwapBuffers(window_);
}
void GlfwWindow::set_title(const std::string& title) {
  glfwSetWindowTitle(window_, title.c_str());
}
void GlfwWindow::framebuffer_size(int& width, int& height) const {
  glfwGetFramebufferSize(window_, &width, &height);
}

}  // namespace globe::viewer
