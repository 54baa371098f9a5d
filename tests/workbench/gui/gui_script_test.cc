// Script parsing, the background job and the widget registry: no GL.
#include "idbench/gui/gui_script.h"

#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <thread>

#include "idbench/gui/background_job.h"
#include "idbench/gui/widget_registry.h"

namespace idbench::gui {
namespace {

TEST(GuiScriptTest, ParsesSteps) {
  const std::vector<ScriptStep> steps = ParseGuiScript(
      "# comment\n\nclick design.run   # trailing comment\nset robot.urdf /tmp/a b.urdf\nwait design\n"
      "wait compare 30\nframes 3\nscreenshot out.png\n",
      "s");
  ASSERT_EQ(steps.size(), 6u);
  EXPECT_EQ(steps[0].kind, ScriptStep::Kind::kClick);
  EXPECT_EQ(steps[0].target, "design.run");
  EXPECT_EQ(steps[0].line, 3);
  EXPECT_EQ(steps[1].kind, ScriptStep::Kind::kSet);
  EXPECT_EQ(steps[1].value, "/tmp/a b.urdf");
  EXPECT_EQ(steps[2].kind, ScriptStep::Kind::kWait);
  EXPECT_EQ(steps[2].value, "600");
  EXPECT_EQ(steps[3].value, "30");
  EXPECT_EQ(steps[4].kind, ScriptStep::Kind::kFrames);
  EXPECT_EQ(steps[4].value, "3");
  EXPECT_EQ(steps[5].kind, ScriptStep::Kind::kScreenshot);
  EXPECT_EQ(steps[5].target, "out.png");
}

TEST(GuiScriptTest, RejectsBadStepsNamingTheLine) {
  auto message = [](const std::string& text) {
    try {
      ParseGuiScript(text, "s.txt");
    } catch (const std::invalid_argument& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(message("frames 1\njump x\n"), "s.txt:2: unknown step 'jump' (click, set, wait, frames, screenshot, drop, shift-drop, drag)");
  EXPECT_EQ(message("set design.f0\n"), "s.txt:1: expected 'set WIDGET VALUE'");
  EXPECT_EQ(message("click\n"), "s.txt:1: expected 'click WIDGET'");
  EXPECT_NE(message("wait dinner\n").find("s.txt:1: expected 'wait JOB [SECONDS]'"), std::string::npos);
  EXPECT_EQ(message("wait design -1\n"), "s.txt:1: wait: timeout: expected seconds > 0, got '-1'");
  EXPECT_EQ(message("frames many\n"), "s.txt:1: frames: expected an integer in [1, 100000], got 'many'");
  EXPECT_EQ(message("drop\n"), "s.txt:1: expected 'drop PATH'");
  for (const char* bad : {"drag log.overview 0.2\n", "drag log.overview 1 0.5\n", "drag log.overview 0.2 1.5\n",
                          "drag log.overview a b\n", "drag log.overview 0.1 0.2 0.3\n"})
    EXPECT_NE(message(bad).find("expected 'drag WIDGET X0 X1'"), std::string::npos) << bad;
}

TEST(GuiScriptTest, ParsesDropAndDrag) {
  const std::vector<ScriptStep> steps =
      ParseGuiScript("drop /data/run 1.csv\nshift-drop /data/b.csv  # held out\ndrag log.overview 0.25 1\n", "s");
  ASSERT_EQ(steps.size(), 3u);
  EXPECT_EQ(steps[0].kind, ScriptStep::Kind::kDrop);
  EXPECT_EQ(steps[0].target, "/data/run 1.csv");
  EXPECT_FALSE(steps[0].held_out);
  EXPECT_EQ(steps[1].kind, ScriptStep::Kind::kDrop);
  EXPECT_EQ(steps[1].target, "/data/b.csv");
  EXPECT_TRUE(steps[1].held_out);
  EXPECT_EQ(steps[2].kind, ScriptStep::Kind::kDrag);
  EXPECT_EQ(steps[2].target, "log.overview");
  EXPECT_EQ(steps[2].value, "0.25 1");
}

// Issue 35 item 23: a '#' inside a word is part of it (run#3.csv), one at
// the start of a line or after a blank starts a comment.
TEST(GuiScriptTest, AHashInsideAPathIsNotAComment) {
  const std::vector<ScriptStep> steps = ParseGuiScript(
      "# a comment line\ndrop /data/run#3.csv # the third run\nset log.data /d/a#b.csv\t# tab before\n  #indented\n", "s");
  ASSERT_EQ(steps.size(), 2u);
  EXPECT_EQ(steps[0].target, "/data/run#3.csv");
  EXPECT_EQ(steps[1].target, "log.data");
  EXPECT_EQ(steps[1].value, "/d/a#b.csv");
}

TEST(BackgroundJobTest, HandsResultsBackOnCollect) {
  BackgroundJob job;
  int applied = 0;
  ASSERT_TRUE(job.Start([&](const std::atomic<bool>&) { return std::function<void()>([&] { applied = 42; }); }));
  EXPECT_FALSE(job.Start([](const std::atomic<bool>&) { return std::function<void()>(); }));  // busy
  std::function<void()> apply;
  std::string error;
  ASSERT_TRUE(job.Wait(&apply, &error));
  EXPECT_EQ(applied, 0);  // nothing touched until the UI thread applies it
  apply();
  EXPECT_EQ(applied, 42);
  EXPECT_TRUE(error.empty());
  EXPECT_FALSE(job.running());
}

TEST(BackgroundJobTest, ReportsFailureAndStops) {
  BackgroundJob job;
  job.Start([](const std::atomic<bool>&) -> std::function<void()> { throw std::runtime_error("no feasible start"); });
  std::function<void()> apply;
  std::string error;
  ASSERT_TRUE(job.Wait(&apply, &error));
  EXPECT_EQ(error, "no feasible start");
  EXPECT_FALSE(apply);
  // A job that runs until asked to stop.
  job.Start([](const std::atomic<bool>& stop) {
    while (!stop) std::this_thread::yield();
    return std::function<void()>();
  });
  EXPECT_TRUE(job.running());
  job.RequestStop();
  ASSERT_TRUE(job.Wait(&apply, &error));
  EXPECT_TRUE(error.empty());
}

TEST(WidgetRegistryTest, KeepsTheLastCompleteFrame) {
  WidgetRegistry registry;
  double value = 0.0;
  registry.BeginFrame();
  registry.Record("a", {10, 20, 30, 40}, true, [&](const std::string& text, std::string*) {
    value = std::stod(text);
    return true;
  });
  EXPECT_EQ(registry.Find("a"), nullptr);  // frame not complete yet
  registry.EndFrame();
  const WidgetEntry* a = registry.Find("a");
  ASSERT_NE(a, nullptr);
  EXPECT_FLOAT_EQ(a->rect.center_x(), 20.0f);
  EXPECT_FLOAT_EQ(a->rect.center_y(), 30.0f);
  std::string why;
  EXPECT_TRUE(a->setter("2.5", &why));
  EXPECT_EQ(value, 2.5);
  registry.BeginFrame();
  registry.Record("b", {}, false);
  registry.EndFrame();
  EXPECT_EQ(registry.Find("a"), nullptr);
  EXPECT_EQ(registry.Names(), std::vector<std::string>{"b"});
}

}  // namespace
}  // namespace idbench::gui
