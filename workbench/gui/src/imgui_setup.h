// The look shared by the window and the headless GUI: light style, plot
// colours that stand out, DejaVu Sans when installed, no imgui.ini.
#pragma once

namespace idbench::gui::internal {

// For the current ImGui context, before its renderer builds the font atlas.
void ConfigureImGui();

}  // namespace idbench::gui::internal
