#pragma once
// The message of the InputError that `action` throws, or "<no error>": how tests read refusals.

#include <string>

#include "core/base/errors.h"

namespace hermite::testing {

template <class Action>
std::string inputErrorOf(Action action) {
  try {
    action();
  } catch (const InputError& e) {
    return e.what();
  }
  return "<no error>";
}

}  // namespace hermite::testing
