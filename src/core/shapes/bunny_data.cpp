#include "core/shapes/bunny_data.h"

#ifndef HERMITE_SOURCE_DIR
#error "HERMITE_SOURCE_DIR (the absolute source directory) must be defined for hermite_core"
#endif

// The assembler reads the file when this translation unit is compiled; the build does not
// track it as a dependency, so touch this file after regenerating bunny.xyzn.
asm("\n"
    "  .pushsection .rodata.hermite_bunny, \"a\"\n"
    "  .balign 16\n"
    "  .globl hermite_bunny_xyzn_begin\n"
    "  .hidden hermite_bunny_xyzn_begin\n"
    "hermite_bunny_xyzn_begin:\n"
    "  .incbin \"" HERMITE_SOURCE_DIR "/assets/bunny/bunny.xyzn\"\n"
    "  .globl hermite_bunny_xyzn_end\n"
    "  .hidden hermite_bunny_xyzn_end\n"
    "hermite_bunny_xyzn_end:\n"
    "  .byte 0\n"
    "  .popsection\n");

extern "C" const char hermite_bunny_xyzn_begin[];
extern "C" const char hermite_bunny_xyzn_end[];

namespace hermite {

std::string_view embeddedBunnyXyzn() {
  return {hermite_bunny_xyzn_begin, static_cast<std::size_t>(hermite_bunny_xyzn_end - hermite_bunny_xyzn_begin)};
}

}  // namespace hermite
