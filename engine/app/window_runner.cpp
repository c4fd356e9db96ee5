#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>

#include <chrono>
#include <cstdio>
#include <glm/glm.hpp>

#include "app/camera_controller.h"
#include "app/clock.h"
#include "app/frame_stats.h"
#include "app/imgui_layer.h"
#include "app/runner_common.h"

namespace engine {
namespace {

struct WindowState {
  CameraController controller;
  bool vsync = true;
};

void onKey(GLFWwindow* window, int key, int, int action, int) {
  if (action != GLFW_PRESS) return;
  auto* state = static_cast<WindowState*>(glfwGetWindowUserPointer(window));
  if (key == GLFW_KEY_ESCAPE) glfwSetWindowShouldClose(window, GLFW_TRUE);
  if (key == GLFW_KEY_V) {
    state->vsync = !state->vsync;
    glfwSwapInterval(state->vsync ? 1 : 0);
  }
  if (key == GLFW_KEY_F) state->controller.toggleMode();
}

void onScroll(GLFWwindow* window, double, double y) {
  static_cast<WindowState*>(glfwGetWindowUserPointer(window))->controller.onScroll(y);
}

void showFrameTime(GLFWwindow* window, double frameMs, const WindowState& state) {
  char title[160];
  std::snprintf(title, sizeof title, "demo | %.2f ms (%.0f fps) | vsync %s [V] | %s camera [F]",
                frameMs, frameMs > 0 ? 1000.0 / frameMs : 0.0, state.vsync ? "on" : "off",
                state.controller.mode() == CameraController::Mode::Orbit ? "orbit" : "fly");
  glfwSetWindowTitle(window, title);
}

// The window's back buffer as it will be shown (the frame and the UI over it),
// top row first.
Image readWindow(int width, int height) {
  Image image(width, height);
  glBindFramebuffer(GL_READ_FRAMEBUFFER, 0);
  glReadBuffer(GL_BACK);
  glPixelStorei(GL_PACK_ALIGNMENT, 1);
  glReadPixels(0, 0, width, height, GL_RGBA, GL_UNSIGNED_BYTE, image.pixels.data());
  flipVertically(image);
  for (std::size_t i = 3; i < image.pixels.size(); i += 4) image.pixels[i] = 255;  // the window has no alpha to keep
  return image;
}

}  // namespace

Status runWindow(Game& game, const RunOptions& options) {
  auto setup = startRun(Backend::Window, game, options);
  if (!setup) return setup.error();
  GLFWwindow* window = setup->context->window();
  WindowState state;
  state.vsync = options.vsync;
  state.controller.attach(game.camera(), glm::length(game.camera().position));
  glfwSetWindowUserPointer(window, &state);
  glfwSetKeyCallback(window, onKey);
  glfwSetScrollCallback(window, onScroll);
  std::unique_ptr<ImGuiLayer> ui;
  if (game.wantsUi()) ui = std::make_unique<ImGuiLayer>(window);

  FixedStepClock clock(options.dt, options.time.value_or(0.0));
  const bool scripted = options.frames > 0;
  using Clock = std::chrono::steady_clock;
  auto last = Clock::now();
  double titleTimer = 0.0;
  std::vector<double> frameMs;
  Image lastFrame;
  for (int frame = 0; !glfwWindowShouldClose(window) && !game.finished(); ++frame) {
    if (options.frames > 0 && frame >= options.frames) break;
    glfwPollEvents();
    const auto now = Clock::now();
    const double elapsed = std::chrono::duration<double>(now - last).count();
    last = now;

    double time = clock.time();
    if (scripted) {
      // A fixed number of frames is a recording: each frame at the headless
      // schedule's time, so the window shows exactly what --offscreen renders.
      time = headlessFrameTime(options, frame);
      game.update(time, options.dt);
    } else {
      // Fixed-step simulation, variable-rate drawing.
      for (int steps = clock.advance(elapsed); steps > 0; --steps) {
        clock.step();
        game.update(clock.time(), clock.dt());
      }
      time = clock.time();
    }
    if (!scripted && !(ui && ui->wantsMouse())) {
      state.controller.update(window, game.camera(), elapsed);
    }

    int width = 0, height = 0;
    glfwGetFramebufferSize(window, &width, &height);
    if (width == 0 || height == 0) continue;  // minimised
    if (width != setup->target.width() || height != setup->target.height()) {
      auto resized = RenderTarget::create(width, height, options.targetSamples > 0 ? options.targetSamples : options.msaa);
      if (!resized) return resized.error();
      setup->target = std::move(resized).value();
    }
    setup->target.bind();
    if (auto s = game.render({time, width, height}); !s) return s;
    setup->target.resolve();
    setup->target.blitToDefault(width, height);
    if (ui) {
      ui->beginFrame();
      game.drawUi();
      ui->endFrame(width, height);
    }
    if (options.screenshotWindow && scripted && frame == options.frames - 1) lastFrame = readWindow(width, height);
    setup->context->swapBuffers();
    noteFrameFinished();

    frameMs.push_back(elapsed * 1000.0);
    titleTimer += elapsed;
    if (titleTimer > 0.5) {
      showFrameTime(window, elapsed * 1000.0, state);
      titleTimer = 0.0;
    }
  }
  if (!options.screenshot.empty() && lastFrame.empty()) lastFrame = setup->target.readPixels();
  // The first interval includes start-up; leave it out of the statistics.
  if (!frameMs.empty()) frameMs.erase(frameMs.begin());
  return finishRun(*setup->context, options, game, std::move(frameMs), lastFrame.empty() ? nullptr : &lastFrame);
}

}  // namespace engine
