#include <doctest/doctest.h>

#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "support/temp_dir.h"
#include "io/atomic_file.h"

namespace fs = std::filesystem;

namespace {

using hermite::testing::TempDir;

std::string contents(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

int entries(const fs::path& dir) {
  int n = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir)) ++n;
  return n;
}

}  // namespace

TEST_CASE("an overwritten file keeps its permission bits") {
  const TempDir dir("hermite_atomic_mode");
  const fs::path file = dir.path / "secret.txt";
  std::ofstream(file) << "old";
  REQUIRE(::chmod(file.c_str(), 0600) == 0);
  hermite::writeFileAtomically(file.string(), "new");
  CHECK(contents(file) == "new");
  struct stat st {};
  REQUIRE(::stat(file.c_str(), &st) == 0);
  CHECK((st.st_mode & 07777) == 0600);
  CHECK(entries(dir.path) == 1);  // no temporary left behind
}

TEST_CASE("writing through a symbolic link replaces the target and keeps the link") {
  const TempDir dir("hermite_atomic_link");
  fs::create_directories(dir.path / "real");
  const fs::path target = dir.path / "real" / "out.txt";
  std::ofstream(target) << "old";
  const fs::path link = dir.path / "link.txt";
  fs::create_symlink(fs::path("real") / "out.txt", link);  // relative link
  hermite::writeFileAtomically(link.string(), "through the link");
  CHECK(fs::is_symlink(fs::symlink_status(link)));
  CHECK(contents(target) == "through the link");
  CHECK(entries(dir.path / "real") == 1);
  CHECK(entries(dir.path) == 2);

  // A dangling link: the file it names is created, the link stays.
  const fs::path dangling = dir.path / "dangling.txt";
  fs::create_symlink(fs::path("real") / "new.txt", dangling);
  hermite::writeFileAtomically(dangling.string(), "created");
  CHECK(fs::is_symlink(fs::symlink_status(dangling)));
  CHECK(contents(dir.path / "real" / "new.txt") == "created");
}

TEST_CASE("SIGTERM or SIGINT during a write removes the temporary file") {
  for (const int signal : {SIGTERM, SIGINT}) {
    CAPTURE(signal);
    const TempDir dir("hermite_atomic_signal");
    const fs::path file = dir.path / "out.bin";
    std::ofstream(file) << "previous";
    const pid_t child = ::fork();
    REQUIRE(child >= 0);
    if (child == 0) {
      ::signal(signal, SIG_DFL);  // the test runner's own handler would otherwise be kept
      hermite::AtomicFileWriter writer(file.string());
      writer.write(std::string(3 << 20, 'x'));  // flushed to the temporary: it exists on disk
      ::raise(signal);
      ::_exit(0);  // not reached: the handler re-raises with the default action
    }
    int status = 0;
    REQUIRE(::waitpid(child, &status, 0) == child);
    CHECK(WIFSIGNALED(status));
    CHECK(WTERMSIG(status) == signal);
    CHECK(entries(dir.path) == 1);  // the temporary is gone
    CHECK(contents(file) == "previous");
  }
}
