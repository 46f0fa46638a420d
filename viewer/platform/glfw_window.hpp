// A GLFW window with an OpenGL 4.5 core context (the interactive viewer).
// Wraps the GLFW C API; input arrives through the callbacks struct.
#pragma once

#include <cstdint>
#include <functional>
#include <string>

struct GLFWwindow;

namespace globe::viewer {

struct WindowCallbacks {
  std::function<void(int key, int mods)> on_key;  // GLFW key codes, presses
  std::function<void(int button, bool down, double x, double y)> on_button;
  std::function<void(double x, double y)> on_cursor;
  std::function<void(double dy, int mods)> on_scroll;  // mods: GLFW_MOD_SHIFT, _CONTROL held
};

// What GLFW's C callbacks reach through the window's user pointer.
struct GlfwWindowState {
  WindowCallbacks callbacks;
  uint64_t events = 0;
};

class GlfwWindow {
 public:
  // Throws std::runtime_error (no display, no 4.5 core context).
  GlfwWindow(int width, int height, const std::string& title, WindowCallbacks callbacks);
  ~GlfwWindow();
  GlfwWindow(const GlfwWindow&) = delete;
  GlfwWindow& operator=(const GlfwWindow&) = delete;

  bool should_close() const;
  void close();
  void poll();
  // Sleeps until an event arrives or `seconds` pass (the idle window draws
  // nothing and uses no CPU), then handles the events.
  void wait(double seconds);
  // Events received so far (input, resizes, exposure): a change means the
  // picture may have to be drawn again.
  uint64_t events() const { return state_.events; }
  void swap();
  void set_title(const std::string& title);
  void framebuffer_size(int& width, int& height) const;

 private:
  GLFWwindow* window_ = nullptr;
  GlfwWindowState state_;
};

}  // namespace globe::viewer
