// RecentFiles in imgui.ini: an ImGui settings handler ("[idbench][RecentFiles]",
// recent_files.h) in the current ImGui context. ImGui reads the section when
// it loads the ini (the first NewFrame, or LoadIniSettingsFromMemory) and
// writes it with the layout; with io.IniFilename null (headless) nothing is
// read or written.
#pragma once

#include "idbench/gui/recent_files.h"

namespace idbench::gui {

// Adds the handler to the current context, reading into and writing from
// *files (which must outlive it, or be unregistered first). A second call
// points the handler at the new *files.
void RegisterRecentFilesSettings(RecentFiles* files);
// Removes the handler from the current context (no-op when absent).
void UnregisterRecentFilesSettings();
// Tells ImGui the section changed (it saves the ini a few seconds later).
void MarkRecentFilesChanged();

}  // namespace idbench::gui
