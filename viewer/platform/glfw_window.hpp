// A GLFW window with an OpenGL 4.5 core context (the interactive viewer).
// Wraps the GLFW C API; input arrives through the callbacks struct.
#pragma once

#include <functional>
#include <string>

struct GLFWwindow;

namespace globe::viewer {

struct WindowCallbacks {
  std::function<void(int key, int mods)> on_key;  // GLFW key codes, presses
  std::function<void(int button, bool down, double x, double y)> on_button;
  std::function<void(double x, double y)> on_cursor;
  std::function<void(double dy)> on_scroll;
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
  void swap();
  void set_title(const std::string& title);
  void framebuffer_size(int& width, int& height) const;

 private:
  GLFWwindow* window_ = nullptr;
  WindowCallbacks callbacks_;
};

}  // namespace globe::viewer
