// The look shared by the window and the headless GUI: light style, plot
// colours that stand out, DejaVu Sans when installed, no imgui.ini (the
// window sets one: ImGuiIniPath).
#pragma once

#include <string>

namespace idbench::gui::internal {

// For the current ImGui context, before its renderer builds the font atlas.
void ConfigureImGui();

// Where the window keeps imgui.ini (the recent files): $XDG_CONFIG_HOME/idbench/,
// else ~/.config/idbench/, created; "" when neither is set or creatable.
std::string ImGuiIniPath();

}  // namespace idbench::gui::internal
