#pragma once
// Prompt exits after fatal failures. A process that ran out of memory may have OpenBLAS or
// OpenMP workers stuck in allocation; a normal exit (static destructors, library shutdown) waits
// for them and can hang, so these flush stdio and leave with std::_Exit.

#include <string_view>

namespace hermite::app {

// "environment error: out of memory ..." with what is still available and a hint, then
// std::_Exit(4). `what` names the request when known (may be empty).
[[noreturn]] void exitOutOfMemory(std::string_view what);

// std::terminate (an exception escaping a thread or an OpenMP region) prints the exception
// and exits with code 4 through the same path instead of aborting.
void installFatalHandlers();

}  // namespace hermite::app
