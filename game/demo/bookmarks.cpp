#include "bookmarks.h"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

namespace demo {

std::string Bookmarks::fileFor(const std::string& scenePath) {
  return "out/bookmarks/" + std::filesystem::path(scenePath).stem().string() + ".json";
}

namespace {

engine::Result<double> number(const nlohmann::json& view, const std::string& where, const char* key) {
  if (!view.contains(key) || !view[key].is_number() || !std::isfinite(view[key].get<double>()))
    return engine::makeError(where + "/" + key + ": expected a finite number");
  return view[key].get<double>();
}

engine::Result<CameraBookmark> parseView(const nlohmann::json& view, const std::string& where) {
  if (!view.is_object()) return engine::makeError(where + ": expected an object");
  CameraBookmark b;
  const char* axes[3] = {"x", "y", "z"};
  for (int k = 0; k < 3; ++k) {
    auto v = number(view, where, axes[k]);
    if (!v) return v.error();
    b.position[k] = *v;
  }
  auto yaw = number(view, where, "yaw");
  if (!yaw) return yaw.error();
  auto pitch = number(view, where, "pitch");
  if (!pitch) return pitch.error();
  auto fovy = number(view, where, "fovy");
  if (!fovy) return fovy.error();
  if (*fovy <= 0.0 || *fovy >= 180.0) return engine::makeError(where + "/fovy: expected degrees in (0, 180)");
  b.yaw = *yaw;
  b.pitch = *pitch;
  b.fovyDegrees = *fovy;
  return b;
}

}  // namespace

engine::Result<Bookmarks> Bookmarks::load(const std::string& file) {
  Bookmarks bookmarks;
  bookmarks.file_ = file;
  std::ifstream in(file);
  if (!in) return bookmarks;
  const std::string name = std::filesystem::path(file).filename().string();
  const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
  if (j.is_discarded() || !j.is_array()) return engine::makeError(file + ": /: expected a JSON array of views");
  for (size_t i = 0; i < j.size(); ++i) {
    auto view = parseView(j[i], file + ": /" + std::to_string(i));
    if (!view) return view.error();
    bookmarks.views_.push_back(*view);
  }
  return bookmarks;
}

engine::Status Bookmarks::save() const {
  nlohmann::json j = nlohmann::json::array();
  for (const CameraBookmark& b : views_) {
    j.push_back({{"x", b.position.x}, {"y", b.position.y}, {"z", b.position.z}, {"yaw", b.yaw},
                 {"pitch", b.pitch}, {"fovy", b.fovyDegrees}});
  }
  std::error_code ec;
  std::filesystem::create_directories(std::filesystem::path(file_).parent_path(), ec);
  const std::string tmp = file_ + ".tmp";
  {
    std::ofstream out(tmp);
    out << j.dump(2) << "\n";
    if (!out) return engine::makeError(file_ + ": cannot write the bookmarks");
  }
  if (std::rename(tmp.c_str(), file_.c_str()) != 0) return engine::makeError(file_ + ": cannot write the bookmarks");
  return engine::Ok{};
}

void Bookmarks::add(const engine::Camera& camera) {
  views_.push_back({camera.position, camera.yaw, camera.pitch, camera.fovyDegrees});
}

void Bookmarks::erase(int index) {
  if (index >= 0 && index < int(views_.size())) views_.erase(views_.begin() + index);
}

void Bookmarks::apply(int index, engine::Camera& camera) const {
  if (index < 0 || index >= int(views_.size())) return;
  const CameraBookmark& b = views_[size_t(index)];
  camera.position = b.position;
  camera.yaw = b.yaw;
  camera.pitch = b.pitch;
  camera.fovyDegrees = b.fovyDegrees;
}

}  // namespace demo
