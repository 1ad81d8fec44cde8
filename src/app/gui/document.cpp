#include "app/gui/document.h"

#include <filesystem>

#include "scene/data_reach_mask.h"
#include "scene/scene_fit.h"

namespace hermite::app {

Document::Document(Scene scene, std::string path) : scene_(std::move(scene)), saved_(scene_), path_(std::move(path)) {}

std::string documentTitle(const Document& document) {
  const std::string& file = !document.path().empty() ? document.path() : document.scene().data.file;
  const std::string name = file.empty() ? "demo scene" : std::filesystem::path(file).filename().string();
  return "Hermite Lab — " + name + (document.dirty() ? " *" : "");
}

void Document::apply(const Scene& next, const std::string& label) {
  if (gesture_) end();
  if (next == scene_) return;
  undo_.push_back({scene_, label});
  if (undo_.size() > kMaxHistory) undo_.erase(undo_.begin());
  redo_.clear();
  const Scene before = std::move(scene_);
  scene_ = next;
  bump(before);
}

void Document::begin(const std::string& label) {
  if (gesture_) end();
  undo_.push_back({scene_, label});
  gesture_ = true;
  gestureChanged_ = false;
}

void Document::update(const Scene& next) {
  if (!gesture_) {
    apply(next, "edit");
    return;
  }
  if (next == scene_) return;
  const Scene before = std::move(scene_);
  scene_ = next;
  gestureChanged_ = true;
  bump(before);
}

void Document::end() {
  if (!gesture_) return;
  gesture_ = false;
  if (!gestureChanged_) {
    undo_.pop_back();  // a click without a move: nothing to undo
    return;
  }
  redo_.clear();
  if (undo_.size() > kMaxHistory) undo_.erase(undo_.begin());
}

void Document::undo() {
  if (gesture_) end();
  if (undo_.empty()) return;
  Entry e = std::move(undo_.back());
  undo_.pop_back();
  redo_.push_back({scene_, e.label});
  restore(std::move(e.scene));
}

void Document::redo() {
  if (gesture_) end();
  if (redo_.empty()) return;
  Entry e = std::move(redo_.back());
  redo_.pop_back();
  undo_.push_back({scene_, e.label});
  restore(std::move(e.scene));
}

void Document::restore(Scene scene) {
  // The camera is not part of the history: the view stays where the user put it.
  scene.view.camera = scene_.view.camera;
  scene.view.center2d = scene_.view.center2d;
  scene.view.halfHeight2d = scene_.view.halfHeight2d;
  const Scene before = std::move(scene_);
  scene_ = std::move(scene);
  bump(before);
}

void Document::reset(Scene scene, std::string path) {
  scene_ = std::move(scene);
  path_ = std::move(path);
  undo_.clear();
  redo_.clear();
  gesture_ = false;
  ++version_;
  bumpAllConcerns(versions_);
  saved_ = scene_;
  dirty_ = false;
}

void Document::save(const std::string& path) {
  saveSceneFile(scene_, path);
  path_ = path;
  saved_ = scene_;
  dirty_ = false;
}

void Document::setCamera(const CameraSpec& camera, const std::array<double, 2>& center2d, double halfHeight2d) {
  ViewSpec& v = scene_.view;
  if (v.camera == camera && v.center2d == center2d && v.halfHeight2d == halfHeight2d) return;
  v.camera = camera;
  v.center2d = center2d;
  v.halfHeight2d = halfHeight2d;
  ++versions_.camera;
  updateDirty();  // saved with the scene, but no refit: the version stays
}

template <int Dim>
Scene withInlineSamples(const Scene& scene, std::vector<std::string>& warnings) {
  if (scene.data.isInline()) return scene;
  const HermiteSamples<Dim> samples = sceneSamples<Dim>(scene, warnings);
  Scene s = scene;
  // A data file's reach stays when its samples become inline (the edited scan is still a scan).
  if (s.fit.reachMask == AutoSwitch::Auto && reachMaskAuto(scene.data, samples.size()))
    s.fit.reachMask = AutoSwitch::On;
  s.data = DataSpec{};
  setInlineSamples<Dim>(s, samples);
  return s;
}

template <int Dim>
HermiteSamples<Dim> inlineSamples(const Scene& scene) {
  const auto& P = scene.data.points;
  const auto& N = scene.data.normals;
  HermiteSamples<Dim> s;
  s.points.resize(Dim, Eigen::Index(P.size()));
  s.normals.resize(Dim, Eigen::Index(P.size()));
  for (std::size_t i = 0; i < P.size(); ++i)
    for (int k = 0; k < Dim; ++k) {
      s.points(k, Eigen::Index(i)) = P[i][k];
      s.normals(k, Eigen::Index(i)) = N[i][k];
    }
  return s;
}

template <int Dim>
void setInlineSamples(Scene& scene, const HermiteSamples<Dim>& samples) {
  scene.data = DataSpec{};
  const int n = samples.size();
  scene.data.points.assign(n, std::vector<double>(Dim));
  scene.data.normals.assign(n, std::vector<double>(Dim));
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < Dim; ++k) {
      scene.data.points[i][k] = samples.points(k, i);
      scene.data.normals[i][k] = samples.normals(k, i);
    }
}

template Scene withInlineSamples<2>(const Scene&, std::vector<std::string>&);
template Scene withInlineSamples<3>(const Scene&, std::vector<std::string>&);
template HermiteSamples<2> inlineSamples<2>(const Scene&);
template HermiteSamples<3> inlineSamples<3>(const Scene&);
template void setInlineSamples<2>(Scene&, const HermiteSamples<2>&);
template void setInlineSamples<3>(Scene&, const HermiteSamples<3>&);

}  // namespace hermite::app
