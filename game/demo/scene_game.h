#pragma once
// The demo's game: a scene file drawn by the SceneRenderer, its characters posed at
// the scene time, the camera where the file puts it (and where the window's
// controls move it). In a window it shows the trade panel (trade_panel.h): the
// render knobs changed live, another scene picked, time paused, slowed or scrubbed,
// and what each pass costs on the GPU.
#include <array>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "app/game.h"
#include "bookmarks.h"
#include "asset/scene_desc.h"
#include "reference_view.h"
#include "render/render_target.h"
#include "render/scene_renderer.h"

namespace engine {
class Scene;
}

namespace demo {

// The panel's time controls: until one is touched, scene time is the runner's.
struct TimeControl {
  bool paused = false;
  double speed = 1.0;
  bool taken = false;  // the user took over: time advances by dt * speed from here
  double time = 0.0;
};

// The panel's graph of the frame's GPU time, newest at `next` - 1.
struct GpuHistory {
  std::array<float, 120> ms{};
  int next = 0;
};

// The panel's reference view: off, the reference on the right half of the
// window, the reference alone, or the error heatmap.
enum class ReferenceMode { Off, Split, Reference, Heatmap };

struct ReferencePanel {
  ReferenceMode mode = ReferenceMode::Off;
  bool pathTraced = true;  // else the Whitted tracer
  int divisor = 2;         // the reference's size: the window's over this
  ReferenceView view;
  std::optional<ReferenceError> error;  // at the last comparison
  int comparedPasses = -1;
  std::optional<engine::RenderTarget> compareTarget;  // the raster frame at the reference's size
  glm::dvec3 lastPosition{0.0}, lastForward{0.0};
  int stillFrames = 0;
  std::string status;  // why there is no reference, for the panel
};

class SceneGame final : public engine::Game {
 public:
  SceneGame(engine::SceneDesc scene, engine::SceneRenderOptions options, bool panel = false);
  ~SceneGame() override;

  engine::Status init() override;
  void update(double time, double dt) override;
  engine::Status render(const engine::FrameInfo& frame) override;
  engine::Camera& camera() override { return camera_; }
  void shutdown() override {
    reference_.view.release();
    reference_.compareTarget.reset();
    renderer_.reset();
  }
  Counters frameCounters() override;
  engine::Result<engine::FloatImage> linearFrame() override { return renderer_->readLinear(); }
  bool wantsUi() const override { return panel_; }
  void drawUi() override;

  engine::SceneRenderer* renderer() { return renderer_.get(); }
  const engine::SceneRenderOptions& options() const { return options_; }
  const engine::Scene* scene() const { return scene_.get(); }
  TimeControl& timeControl() { return time_; }
  ReferencePanel& reference() { return reference_; }

  // Rebuilds the renderer with `options` over the same scene (nothing is
  // reloaded). On failure the current renderer stays and the error is returned.
  engine::Status applyOptions(const engine::SceneRenderOptions& options);
  // Loads another scene file; on failure the current scene stays.
  engine::Status switchScene(const std::string& path);
  // Appends the current setting's frame time and error against the reference as a
  // row of bench/tradeoff's results.csv (scene,family,setting,time_ms,psnr_db,
  // mean_abs,ssim,reference), the header first when the file is new. Needs a
  // reference compared at least once.
  engine::Status addToTable(const std::string& csvPath);
  // The knobs in effect, as one word each ("msaa4 ss1 shadow2048 pcf3 ...").
  std::string settingName() const;
  // The scene's camera bookmarks (bookmarks.h), loaded with the scene in a window
  // or with startAtBookmark. bookmarkView adds the camera's view and saves them.
  Bookmarks& bookmarks() { return bookmarks_; }
  engine::Status bookmarkView();
  engine::Status deleteBookmark(int index);
  void goToBookmark(int index) { bookmarks_.apply(index, camera_); }
  // demo --bookmark N: init starts from bookmark `index` of the scene's file, and
  // fails (naming the file) when there is no such bookmark.
  void startAtBookmark(int index) { startBookmark_ = index; }
  // One knob of the panel as "name=value" (msaa, supersample, shadow-map, pcf,
  // probe, shading, ambient, ibl-size, exposure, tonemap, output, skinning,
  // skin-blend, rotations, terrain-error, each
  // taking the values its combo offers) applied to `options`; an unknown name or
  // value is an error naming both.
  static engine::Status parseKnob(const std::string& assignment, engine::SceneRenderOptions& options);
  // demo --panel-set: the panel turns these knobs as it draws its first frame,
  // through applyOptions as a click on its combo does.
  void queueKnobs(std::vector<std::string> assignments) { pendingKnobs_ = std::move(assignments); }
  // demo --panel-no-timings: the panel shows no timing figures, which change every
  // run (the window's golden screenshot).
  void showTimings(bool show) { showTimings_ = show; }
  // What the panel reports: the last failure to apply or load, or "".
  const std::string& lastError() const { return lastError_; }

 private:
  engine::Status build(std::shared_ptr<engine::Scene> scene, const engine::SceneRenderOptions& options);
  // The reference view's part of a frame: start or keep the trace, compare, show.
  engine::Status referenceFrame(const engine::FrameInfo& frame);
  engine::Status compareWithReference();
  void showReference(const engine::FrameInfo& frame);

  engine::SceneDesc desc_;
  engine::SceneRenderOptions options_;
  bool panel_ = false;
  engine::Camera camera_;
  std::shared_ptr<engine::Scene> scene_;
  std::unique_ptr<engine::SceneRenderer> renderer_;
  engine::Status updated_ = engine::Ok{};
  TimeControl time_;
  std::string lastError_;
  GpuHistory history_;
  ReferencePanel reference_;
  std::string tableMessage_;  // the last "add to table"'s outcome
  Bookmarks bookmarks_;
  std::string bookmarkMessage_;  // the last bookmark save's failure
  int startBookmark_ = -1;
  std::vector<std::string> pendingKnobs_;
  bool showTimings_ = true;
  engine::Status loadBookmarks();
};

}  // namespace demo
