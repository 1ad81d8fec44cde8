#include "app/gui/frame_log.h"

#include <cerrno>
#include <cstring>

#include "core/base/errors.h"

namespace hermite::app {

namespace {

void writeInts(std::FILE* f, const std::vector<int>& v) {
  std::fputc('[', f);
  for (std::size_t i = 0; i < v.size(); ++i) std::fprintf(f, "%s%d", i ? ", " : "", v[i]);
  std::fputc(']', f);
}

}  // namespace

FrameLog::FrameLog(const std::string& path) : file_(std::fopen(path.c_str(), "a")) {
  if (!file_) throw EnvironmentError("HERMITE_GUI_LOG: cannot open " + path + ": " + std::strerror(errno));
}

FrameLog::~FrameLog() {
  if (file_) std::fclose(file_);
}

void FrameLog::frame(const Frame& f) {
  std::fprintf(file_, "{\"frame\": %lld, \"time\": %.4f, \"ms\": %.2f, \"input_wait_ms\": %.2f, \"keys\": ", frames_++,
               f.time, f.ms, f.inputWaitMs);
  writeInts(file_, f.keysPressed);
  std::fputs(", \"buttons\": ", file_);
  writeInts(file_, f.buttonsPressed);
  std::fprintf(file_, ", \"fits\": %d, \"version\": %llu, \"fit_running\": %s, \"view_pending\": %s, \"selected\": %d, \"phases\": {",
               f.fits, static_cast<unsigned long long>(f.version), f.fitRunning ? "true" : "false",
               f.viewPending ? "true" : "false", f.selected);
  for (std::size_t k = 0; k < kFramePhaseNames.size(); ++k)
    std::fprintf(file_, "%s\"%s\": %.2f", k ? ", " : "", kFramePhaseNames[k].data(), f.phases.ms[k]);
  std::fprintf(file_, "}, \"draw_vertices\": %d, \"draw_commands\": %d}\n", f.drawVertices, f.drawCommands);
  std::fflush(file_);
}

void FrameLog::widgets(const Widgets& rects) {
  if (rects == lastWidgets_) return;
  lastWidgets_ = rects;
  std::fputs("{\"widgets\": {", file_);
  bool first = true;
  for (const auto& [name, r] : rects) {
    // Widget names are identifiers ("view.bounds_box"): nothing to escape.
    std::fprintf(file_, "%s\"%s\": [%.1f, %.1f, %.1f, %.1f]", first ? "" : ", ", name.c_str(), r[0], r[1], r[2], r[3]);
    first = false;
  }
  std::fputs("}}\n", file_);
  std::fflush(file_);
}

}  // namespace hermite::app
