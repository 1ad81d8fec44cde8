#include "scene/loaded_samples_handoff.h"

#include <filesystem>
#include <mutex>

namespace hermite {

namespace {

// What identifies one version of a file: its path, size and modification time.
struct FileStamp {
  std::string path;
  std::uintmax_t size = 0;
  std::filesystem::file_time_type modified;
  bool operator==(const FileStamp& o) const { return path == o.path && size == o.size && modified == o.modified; }
};

std::optional<FileStamp> stampOf(const std::string& path) {
  std::error_code ec;
  FileStamp s{path, std::filesystem::file_size(path, ec), {}};
  if (ec) return std::nullopt;
  s.modified = std::filesystem::last_write_time(path, ec);
  if (ec) return std::nullopt;
  return s;
}

template <int Dim>
struct Handoff {
  std::mutex mutex;  // the GUI opens files on its UI thread and fits on a worker
  std::optional<FileStamp> stamp;
  GivenNormals orient = GivenNormals::Auto;
  HermiteSamples<Dim> samples;
  std::vector<std::string> warnings;
};

template <int Dim>
Handoff<Dim>& handoff() {
  static Handoff<Dim> h;
  return h;
}

}  // namespace

template <int Dim>
void keepLoadedSamples(const std::string& path, const PointFileOptions& options, const HermiteSamples<Dim>& samples,
                       const std::vector<std::string>& warnings) {
  const std::optional<FileStamp> stamp = stampOf(path);
  Handoff<Dim>& h = handoff<Dim>();
  std::lock_guard lock(h.mutex);
  h.stamp = stamp;
  h.orient = options.orient;
  h.samples = stamp ? samples : HermiteSamples<Dim>();
  h.warnings = warnings;
}

template <int Dim>
std::optional<HermiteSamples<Dim>> takeLoadedSamples(const std::string& path, const PointFileOptions& options,
                                                     std::vector<std::string>& warnings) {
  Handoff<Dim>& h = handoff<Dim>();
  std::lock_guard lock(h.mutex);
  if (!h.stamp) return std::nullopt;
  const bool same = h.orient == options.orient && stampOf(path) == h.stamp;
  h.stamp.reset();
  if (!same) {
    h.samples = HermiteSamples<Dim>();
    return std::nullopt;
  }
  warnings.insert(warnings.end(), h.warnings.begin(), h.warnings.end());
  return std::move(h.samples);
}

template void keepLoadedSamples<2>(const std::string&, const PointFileOptions&, const HermiteSamples<2>&,
                                   const std::vector<std::string>&);
template void keepLoadedSamples<3>(const std::string&, const PointFileOptions&, const HermiteSamples<3>&,
                                   const std::vector<std::string>&);
template std::optional<HermiteSamples<2>> takeLoadedSamples<2>(const std::string&, const PointFileOptions&,
                                                               std::vector<std::string>&);
template std::optional<HermiteSamples<3>> takeLoadedSamples<3>(const std::string&, const PointFileOptions&,
                                                               std::vector<std::string>&);

}  // namespace hermite
