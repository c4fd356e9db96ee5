#pragma once
// Camera bookmarks: views of a scene saved from the trade panel, so that a
// setting can be compared from the same places again, across runs. Kept per scene
// file in out/bookmarks/<scene name>.json.
#include <string>
#include <vector>

#include "core/result.h"
#include "render/camera.h"

namespace demo {

struct CameraBookmark {
  glm::dvec3 position{0.0};
  double yaw = 0.0, pitch = 0.0, fovyDegrees = 60.0;
};

class Bookmarks {
 public:
  // Where the bookmarks of `scenePath` are kept.
  static std::string fileFor(const std::string& scenePath);
  // Reads `file`: no file is no bookmarks; a malformed one is an error naming the
  // file and the element (`demo.json: /2/yaw: expected a number`).
  static engine::Result<Bookmarks> load(const std::string& file);
  // Writes them (the folder made as needed; the old file replaced whole).
  engine::Status save() const;

  void add(const engine::Camera& camera);
  void erase(int index);
  // Puts the camera where bookmark `index` was taken.
  void apply(int index, engine::Camera& camera) const;
  const std::vector<CameraBookmark>& all() const { return views_; }
  const std::string& file() const { return file_; }

 private:
  std::string file_;
  std::vector<CameraBookmark> views_;
};

}  // namespace demo
