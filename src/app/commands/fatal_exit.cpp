#include "app/commands/fatal_exit.h"

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <new>
#include <string>

#include "core/base/memory_check.h"

namespace hermite::app {

namespace {

[[noreturn]] void flushAndExit(int code) {
  std::fflush(nullptr);
  std::_Exit(code);
}

[[noreturn]] void onTerminate() {
  if (const std::exception_ptr e = std::current_exception()) {
    try {
      std::rethrow_exception(e);
    } catch (const std::bad_alloc&) {
      exitOutOfMemory("");
    } catch (const std::exception& x) {
      std::fprintf(stderr, "internal error: %s\n", x.what());
    } catch (...) {
      std::fprintf(stderr, "internal error: unknown exception\n");
    }
  } else {
    std::fprintf(stderr, "internal error: terminate called\n");
  }
  flushAndExit(4);
}

}  // namespace

void exitOutOfMemory(std::string_view what) {
  std::string available;
  try {  // the failed request is not held: this usually has room again
    const AvailableMemory a = availableMemory();
    if (a.bytes != kUnlimitedBytes) available = "; " + formatBytes(a.bytes) + " available (" + a.limitedBy + ")";
  } catch (...) {
  }
  std::fprintf(stderr,
               "environment error: out of memory%s%.*s%s; use a smaller job (fewer points, a lower --resolution or "
               "--size), fewer --threads, or raise the memory limit\n",
               what.empty() ? "" : " allocating ", static_cast<int>(what.size()), what.data(), available.c_str());
  flushAndExit(4);
}

void installFatalHandlers() { std::set_terminate(onTerminate); }

}  // namespace hermite::app
