#pragma once
// Text wrapped to a width and cut after a number of lines: the cut text ends in "…" and shows
// its full wording in a tooltip while hovered (status bar, Diagnostics warnings), so a long
// message never pushes the layout around and is still readable in full. Needs a current ImGui
// frame.

#include <imgui.h>

#include <string>
#include <vector>

namespace hermite::app {

// The lines `text` wraps into at `width` pixels in the current font (explicit newlines kept).
std::vector<std::string> wrapLines(const std::string& text, float width);

// Draws at most `maxLines` lines of `text` wrapped at `width` pixels in `colour`; returns true
// when it had to cut (then hovering shows the whole text).
bool clippedText(const std::string& text, float width, int maxLines, const ImVec4& colour);

}  // namespace hermite::app
