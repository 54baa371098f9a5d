// Reports (`run --report`, `identify --report`, `idbench report`), run as a
// user would: every file the HTML names exists, the PDF is a PDF.
#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <regex>
#include <set>
#include <string>

#include "workbench/cli/rendering_cli_fixture.h"

namespace {

namespace fs = std::filesystem;
using idbench::testing::Result;
using idbench::testing::Slurp;

class ReportCliTest : public idbench::testing::RenderingCliFixture {
 protected:

  // The files an HTML page refers to (src and href), relative to its directory.
  static std::set<std::string> References(const std::string& html) {
    std::set<std::string> files;
    const std::regex attribute(R"re((src|href)="([^"]*)")re");
    for (auto it = std::sregex_iterator(html.begin(), html.end(), attribute); it != std::sregex_iterator(); ++it) {
      files.insert((*it)[2].str());
    }
    return files;
  }

  // Every reference is a local file that exists (self-contained), and the PDF
  // is one: pdfinfo when installed, else its header and trailer.
  void ExpectCompleteReport(const fs::path& dir, const std::set<std::string>& must_reference) {
    const std::string html = Slurp(dir / "report.html");
    ASSERT_FALSE(html.empty());
    const std::set<std::string> refs = References(html);
    for (const std::string& ref : refs) {
      EXPECT_EQ(ref.find("://"), std::string::npos) << ref;
      EXPECT_TRUE(fs::is_regular_file(dir / ref)) << ref;
      EXPECT_GT(fs::file_size(dir / ref), 100u) << ref;
    }
    for (const std::string& ref : must_reference) EXPECT_TRUE(refs.count(ref)) << ref;
    const std::string pdf = Slurp(dir / "report.pdf");
    ASSERT_GT(pdf.size(), 1000u);
    EXPECT_EQ(pdf.rfind("%PDF-", 0), 0u);
    EXPECT_NE(pdf.find("%%EOF", pdf.size() - 16), std::string::npos);
    if (std::system("command -v pdfinfo >/dev/null 2>&1") == 0) {
      EXPECT_EQ(std::system(("pdfinfo " + (dir / "report.pdf").string() + " >/dev/null 2>&1").c_str()), 0);
    }
  }

  // Every word of the PDF, as `pdftotext -bbox` boxes it, lies inside the
  // page's 40 pt margins (the report's layout); returns the words, or
  // nothing when poppler-utils is not installed.
  std::vector<std::string> ExpectTextInsideMargins(const fs::path& pdf) {
    if (std::system("command -v pdftotext >/dev/null 2>&1") != 0) {
      ADD_FAILURE() << "pdftotext (poppler-utils) is not installed";
      return {};
    }
    const fs::path boxes = dir_ / "boxes.html";
    EXPECT_EQ(std::system(("pdftotext -bbox " + pdf.string() + " " + boxes.string()).c_str()), 0);
    const std::string html = Slurp(boxes);
    constexpr double kMargin = 40.0, kSlack = 1.0;  // [pt]; glyph boxes may reach a little past the advance
    const std::regex page(R"re(<page width="([\d.]+)" height="([\d.]+)">)re");
    const std::regex word(R"re(xMin="([-\d.]+)" yMin="([-\d.]+)" xMax="([-\d.]+)" yMax="([-\d.]+)">([^<]*)</word>)re");
    std::vector<std::string> words;
    double width = 0.0, height = 0.0;
    int pages = 0;
    // Pages and words in document order.
    const std::regex either(R"re(<page width="[^>]*>|<word [^>]*>[^<]*</word>)re");
    for (auto it = std::sregex_iterator(html.begin(), html.end(), either); it != std::sregex_iterator(); ++it) {
      const std::string item = it->str();
      std::smatch m;
      if (std::regex_search(item, m, page)) {
        width = std::stod(m[1]), height = std::stod(m[2]);
        ++pages;
        continue;
      }
      if (!std::regex_search(item, m, word)) continue;
      const double x0 = std::stod(m[1]), y0 = std::stod(m[2]), x1 = std::stod(m[3]), y1 = std::stod(m[4]);
      words.push_back(m[5]);
      EXPECT_GE(x0, kMargin - kSlack) << "page " << pages << ": '" << m[5] << "'";
      EXPECT_LE(x1, width - kMargin + kSlack) << "page " << pages << ": '" << m[5] << "'";
      EXPECT_GE(y0, 0.0) << "page " << pages << ": '" << m[5] << "'";
      EXPECT_LE(y1, height) << "page " << pages << ": '" << m[5] << "'";
    }
    EXPECT_GT(pages, 1);
    EXPECT_GT(words.size(), 200u);
    return words;
  }

  // "truth" or "true" as a word (not inside the test's own directory name).
  static bool ContainsTruth(const std::string& text) {
    return std::regex_search(text, std::regex(R"(\b(truth|true)\b)", std::regex::icase));
  }
};

TEST_F(ReportCliTest, RunReportHasCommandTablesFigureAndPlots) {
  const fs::path out = dir_ / "run";
  const Result r = Run("run --report --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ExpectCompleteReport(out, {"figure.png", "report.pdf", "plot_joints.svg", "plot_parameters.svg",
                             "plot_spectrum.svg", "plot_motions.svg"});
  const std::string html = Slurp(out / "report.html");
  // The exact command, the tables with the truth, the flagged parameters.
  EXPECT_NE(html.find("idbench run --report --out " + out.string()), std::string::npos);
  EXPECT_NE(html.find("<td>6402.601"), std::string::npos);  // B1's mass, paper Table 1
  EXPECT_NE(html.find("NOT IDENTIFIABLE"), std::string::npos);
  // A simulation's report may speak of the truth; its text stays inside the page.
  EXPECT_TRUE(ContainsTruth(html));
  ExpectTextInsideMargins(out / "report.pdf");
  // `idbench report` on the same directory writes the same page again.
  const std::string before = html;
  const Result again = Run("report --out " + out.string());
  ASSERT_EQ(again.exit_code, 0) << again.err;
  EXPECT_EQ(Slurp(out / "report.html"), before);
}

TEST_F(ReportCliTest, IdentifyReport) {
  ASSERT_EQ(Run("simulate --duration 3 --out " + (dir_ / "log.csv").string()).exit_code, 0);
  const fs::path out = dir_ / "id";
  const Result r = Run("identify --data " + (dir_ / "log.csv").string() + " --report --out " +
                       out.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ExpectCompleteReport(out, {"figure.png", "plot_joints.svg", "plot_parameters.svg", "plot_spectrum.svg",
                             "plot_torques.svg", "plot_torques.png", "plot_torques.pdf"});
  EXPECT_NE(Slurp(out / "report.html").find("Base parameters"), std::string::npos);
  EXPECT_FALSE(fs::exists(out / "plot_validation_torques.svg"));  // no --validate
}

// With --validate, measured against predicted torque on the held-out log as
// well; here a log without qd, qdd, so it is predicted on its parallel-filtered rows.
TEST_F(ReportCliTest, IdentifyReportWithValidationPlotsTheHeldOutTorques) {
  ASSERT_EQ(Run("simulate --duration 3 --out " + (dir_ / "log.csv").string()).exit_code, 0);
  ASSERT_EQ(Run("simulate --duration 3 --trajectory general-reversed --no-derivatives --out " +
                (dir_ / "held.csv").string()).exit_code, 0);
  const fs::path out = dir_ / "id";
  const Result r = Run("identify --data " + (dir_ / "log.csv").string() + " --validate " +
                       (dir_ / "held.csv").string() + " --report --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ExpectCompleteReport(out, {"plot_torques.svg", "plot_torques.png", "plot_torques.pdf", "plot_validation_torques.svg",
                             "plot_validation_torques.png", "plot_validation_torques.pdf"});
  const std::string html = Slurp(out / "report.html");
  EXPECT_NE(html.find("Measured and predicted joint torque on the held-out log " + (dir_ / "held.csv").string()),
            std::string::npos);
  EXPECT_NE(html.find("both parallel-filtered"), std::string::npos);
}

// A report of a log the command line reads (recorded, as far as it can
// know): under a long path, so the title and the captions need several
// lines; every word of the PDF inside the margins, and no "truth" (the robot
// file's values are a reference here), but "measured" torques.
TEST_F(ReportCliTest, RecordedLogReportStaysInsideThePageAndClaimsNoTruth) {
  const fs::path deep = dir_ / "a_directory_with_a_rather_long_name_for_the_recordings_of_the_robot_in_cell_7" /
                        "session_2026_11_26_morning_excitation_runs";
  fs::create_directories(deep);
  const fs::path log = deep / "recorded_joint_log_with_a_long_descriptive_file_name.csv";
  ASSERT_EQ(Run("simulate --duration 3 --no-derivatives --out " + log.string()).exit_code, 0);
  const fs::path out = dir_ / "id";
  const Result r = Run("identify --estimator ols --data " + log.string() + " --validate " + log.string() +
                       " --report --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<std::string> words = ExpectTextInsideMargins(out / "report.pdf");
  std::string text;
  for (const std::string& w : words) text += w + " ";
  EXPECT_FALSE(ContainsTruth(text));
  EXPECT_FALSE(ContainsTruth(Slurp(out / "report.html")));
  EXPECT_NE(text.find("recorded log"), std::string::npos);
  EXPECT_NE(text.find("measured"), std::string::npos);
  // The joints by the robot's names (puma560: joint1 … joint6) in the torque plots.
  EXPECT_NE(text.find("joint6, identification log"), std::string::npos);
}

// The KUKA LWR4+ identification of the issue (../shared/data/kuka_lwr4, not
// part of the project): measurements_1 with viscous, Coulomb and offset,
// validated on measurements_3; its report inside the margins, no "truth".
TEST_F(ReportCliTest, KukaReportStaysInsideThePageAndClaimsNoTruth) {
  const fs::path data = fs::path(IDBENCH_SOURCE_DIR) / ".." / "shared" / "data" / "kuka_lwr4";
  if (!fs::exists(data / "logs" / "measurements_1.csv")) {
    GTEST_SKIP() << data << " is absent (../shared/data/kuka_lwr4 beside the checkout; not part of the project)";
  }
  const fs::path out = dir_ / "kuka";
  const Result r = Run("identify --robot " + (data / "lwr_description" / "urdf" / "kuka_lwr4.urdf").string() +
                       " --data " + (data / "logs" / "measurements_1.csv").string() + " --validate " +
                       (data / "logs" / "measurements_3.csv").string() +
                       " --friction viscous,coulomb,offset --estimator ols --report --out " + out.string());
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::vector<std::string> words = ExpectTextInsideMargins(out / "report.pdf");
  std::string text;
  for (const std::string& w : words) text += w + " ";
  EXPECT_FALSE(ContainsTruth(text));
  EXPECT_FALSE(ContainsTruth(Slurp(out / "report.html")));
  EXPECT_NE(text.find("lwr_6_joint"), std::string::npos);  // joints by their URDF names
}

TEST_F(ReportCliTest, ReportWithoutResultsSaysWhatIsMissingAndWritesNothing) {
  const Result r = Run("report --out " + dir_.string() + "/empty");
  EXPECT_EQ(r.exit_code, 2);  // the input is missing
  EXPECT_NE(r.err.find("results.json: no such file"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "empty"));
  EXPECT_EQ(Run("report").exit_code, 2);  // --out is required
}

}  // namespace
