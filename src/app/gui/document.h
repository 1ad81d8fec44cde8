#pragma once
// The document the GUI edits (docs/design.md, Data flow): a Scene, a version counter that every change bumps
// (the fitter and the renderer compare versions and recompute only what is stale), undo / redo
// of whole-scene snapshots (exact: undo restores the previous document bit for bit), the path it
// was loaded from or saved to, and whether it has unsaved changes.
//
// Edits come in two shapes:
//   - one-shot edits (a combo, a checkbox, a deleted sample): apply(newScene, label);
//   - continuous edits (dragging a sample, a slider): begin(label) once, then update(newScene)
//     on every frame of the drag, end() when it stops — one undo step for the whole gesture.

#include <cstdint>
#include <string>
#include <vector>

#include "app/gui/concern_versions.h"
#include "core/points/hermite_samples.h"
#include "scene/scene_file.h"

namespace hermite::app {

class Document {
 public:
  explicit Document(Scene scene = {}, std::string path = {});

  const Scene& scene() const { return scene_; }
  std::uint64_t version() const { return version_; }
  // The counters of each concern (concern_versions.h): what changed since a part last looked.
  const ConcernVersions& versions() const { return versions_; }
  const std::string& path() const { return path_; }
  // The scene differs from the one last opened or saved (undo back to it clears the flag).
  bool dirty() const { return dirty_; }

  // One undo step: the current scene is pushed, `next` becomes current (no-op when equal).
  void apply(const Scene& next, const std::string& label);
  // A gesture: one undo step for any number of updates.
  void begin(const std::string& label);
  void update(const Scene& next);
  void end();
  bool inGesture() const { return gesture_; }

  bool canUndo() const { return !undo_.empty(); }
  bool canRedo() const { return !redo_.empty(); }
  std::string undoLabel() const { return undo_.empty() ? "" : undo_.back().label; }
  std::string redoLabel() const { return redo_.empty() ? "" : redo_.back().label; }
  void undo();
  void redo();

  // Replaces the whole document (open, new preset): history is cleared.
  void reset(Scene scene, std::string path);
  // Saves atomically (temporary + rename) and remembers the path; clears the dirty flag.
  void save(const std::string& path);
  // Camera moves (3D camera, 2D centre and half height): saved with the scene, not undone, and
  // not a refit (the version stays; versions().camera grows).
  void setCamera(const CameraSpec& camera, const std::array<double, 2>& center2d, double halfHeight2d);

 private:
  struct Entry {
    Scene scene;
    std::string label;
  };
  // After scene_ changed from `before`.
  void bump(const Scene& before) {
    ++version_;
    bumpChangedConcerns(versions_, before, scene_);
    updateDirty();
  }
  void updateDirty() { dirty_ = !(scene_ == saved_); }
  void restore(Scene scene);  // an undo / redo target, keeping the current camera

  Scene scene_;
  Scene saved_;  // as last opened or saved
  std::string path_;
  std::uint64_t version_ = 1;
  ConcernVersions versions_;
  bool dirty_ = false;
  bool gesture_ = false;
  bool gestureChanged_ = false;
  std::vector<Entry> undo_, redo_;
  static constexpr std::size_t kMaxHistory = 500;
};

// The window's title: "Hermite Lab — NAME" with NAME the scene file's name, else the data file's,
// else "demo scene"; " *" when the document is dirty.
std::string documentTitle(const Document& document);

// A scene whose data are inline points / normals, with the samples the scene names (preset, file
// or inline) written in: editing individual samples needs them inline. Validation warnings are
// appended; fit.reach_mask "auto" becomes true where it applied to the file. Dim is the scene's
// dimension.
template <int Dim>
Scene withInlineSamples(const Scene& scene, std::vector<std::string>& warnings);

// The samples of an inline scene (no validation: the document's own copy).
template <int Dim>
HermiteSamples<Dim> inlineSamples(const Scene& scene);
// Writes samples into the scene's inline data.
template <int Dim>
void setInlineSamples(Scene& scene, const HermiteSamples<Dim>& samples);

}  // namespace hermite::app
