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

TEST_F(ReportCliTest, ReportWithoutResultsSaysWhatIsMissingAndWritesNothing) {
  const Result r = Run("report --out " + dir_.string() + "/empty");
  EXPECT_EQ(r.exit_code, 2);  // the input is missing
  EXPECT_NE(r.err.find("results.json: no such file"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "empty"));
  EXPECT_EQ(Run("report").exit_code, 2);  // --out is required
}

}  // namespace
