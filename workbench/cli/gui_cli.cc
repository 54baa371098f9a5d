// `idbench gui`: the workbench window (GLFW + OpenGL 3), or drawn offscreen
// and driven by a script (--headless); its flags fill gui::GuiCommandOptions.
#include <cstdio>
#include <memory>
#include <string>

#include "cli_command.h"
#include "common_flags.h"
#include "idbench/gui/gui_command.h"

namespace idbench::cli {
namespace {

struct GuiFlags {
  gui::GuiCommandOptions options;
  std::string size = "1280x720";  // --size WxH: options.width, options.height
};

int GuiCommand(GuiFlags* flags, const CliContext& context) {
  gui::GuiCommandOptions& options = flags->options;
  if (std::sscanf(flags->size.c_str(), "%dx%d", &options.width, &options.height) != 2)
    return context.UsageError("--size: expected WxH, got '" + flags->size + "'");
  std::string why;
  if (!options.IsValid(&why)) return context.UsageError(why);
  return gui::RunGuiCommand(options);
}

}  // namespace

CliCommand AddGuiCommand(CLI::App* app, CliContext* context) {
  auto flags = std::make_shared<GuiFlags>();
  gui::GuiCommandOptions& gui = flags->options;
  CLI::App* command = app->add_subcommand(
      "gui", "The workbench window (GLFW + OpenGL 3); --headless draws it offscreen, driven by --script");
  AddRobotFlag(command, &gui.robot);
  command->add_option("--data", gui.data, "A recorded joint log, opened in the Log tab");
  command->add_option("--validate", gui.validate, "Its held-out log (Log tab)");
  AddOutFlag(command, &gui.out_dir, "Directory for logs and exports")->capture_default_str();
  command->add_flag("--headless", gui.headless, "No window: OSMesa, scripted input");
  command->add_option("--script", gui.script, "Headless: steps (click, set, wait, frames, screenshot), one a line");
  command->add_option("--screenshot", gui.screenshot, "Write the last frame as a PNG");
  command->add_option("--frames", gui.frames, "Window: close after N frames (0: when closed)");
  command->add_option("--size", flags->size, "Window size WxH [px]")->capture_default_str();
  return {command, [flags, context] { return GuiCommand(flags.get(), *context); }};
}

}  // namespace idbench::cli
