// The messages panel (bottom right): the session's messages, errors in red,
// scrolled to the newest.
#include <imgui.h>

#include "gui_app_impl.h"
#include "gui_helpers.h"

namespace idbench::gui {

void GuiApp::Impl::DrawMessages() {
  const ImGuiIO& io = ImGui::GetIO();
  const float W = io.DisplaySize.x, H = io.DisplaySize.y;
  const float x = W * layout.left_fraction;
  ImGui::SetNextWindowPos(ImVec2(x, H - layout.messages_height));
  ImGui::SetNextWindowSize(ImVec2(W - x, layout.messages_height));
  ImGui::Begin("Messages", nullptr, kPanelFlags);
  const auto& messages = session.messages();
  for (const SessionMessage& m : messages) {
    const bool error = m.level == SessionMessage::Level::kError;
    if (error) ImGui::PushStyleColor(ImGuiCol_Text, kErrorColor);
    ImGui::TextWrapped("%s", m.text.c_str());
    if (error) ImGui::PopStyleColor();
  }
  if (messages.size() != shown_messages) ImGui::SetScrollHereY(1.0f);
  shown_messages = messages.size();
  ImGui::End();
}

}  // namespace idbench::gui
