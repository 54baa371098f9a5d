// Hostile and broken input through every front end (issue 14): nothing a file
// or option says crashes idbench, hangs it, exhausts the machine, or writes
// anything but the outputs it names; one exit-code rule (README "Exit codes").
// The crash and hang cases run under `timeout` (and the CTest timeout), so on
// a build without the fixes they fail instead of stalling.
#include <sys/stat.h>
#include <unistd.h>

#include <climits>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include "workbench/cli/cli_fixture.h"

namespace idbench::testing {
namespace {

namespace fs = std::filesystem;

const std::string kTimeout = "timeout 30 ";  // a hang exits 124, a crash 128 + signal

// A two-link URDF; `extra` goes inside <robot>.
std::string Urdf(const std::string& extra = "", const std::string& mass = "1") {
  const std::string inertial = "<inertial><mass value=\"" + mass +
                               "\"/><inertia ixx=\"0.1\" ixy=\"0\" ixz=\"0\" iyy=\"0.1\" iyz=\"0\" izz=\"0.1\"/>"
                               "</inertial>";
  const std::string limit = "<axis xyz=\"0 0 1\"/><limit lower=\"-1\" upper=\"1\" effort=\"10\" velocity=\"2\"/>";
  return "<robot name=\"r\">\n<link name=\"base\"/>\n<link name=\"a\">" + inertial + "</link>\n<link name=\"b\">" +
         inertial + "</link>\n<joint name=\"j1\" type=\"revolute\"><parent link=\"base\"/><child link=\"a\"/>" + limit +
         "</joint>\n<joint name=\"j2\" type=\"revolute\"><parent link=\"a\"/><child link=\"b\"/>" + limit +
         "</joint>\n" + extra + "</robot>\n";
}

class HostileInputCliTest : public CliFixture {
 protected:
  fs::path Write(const std::string& name, const std::string& text) {
    std::ofstream(dir_ / name, std::ios::binary) << text;
    return dir_ / name;
  }
  fs::path Fifo(const std::string& name) {
    EXPECT_EQ(::mkfifo((dir_ / name).c_str(), 0600), 0);
    return dir_ / name;
  }
  // A noise-free PUMA 560 log of 0.5 s at 100 Hz.
  fs::path Log() {
    const fs::path log = dir_ / "log.csv";
    EXPECT_EQ(Run("simulate --robot puma560 --duration 0.5 --rate 100 --out " + log.string()).exit_code, 0);
    return log;
  }
};

// Item 1: a loop of joints was a stack overflow (SIGSEGV) in every command.
TEST_F(HostileInputCliTest, ALoopOfJointsIsRefusedNotACrash) {
  const fs::path urdf = Write("loop.urdf", Urdf("<joint name=\"j3\" type=\"revolute\"><parent link=\"b\"/><child "
                                                "link=\"a\"/><axis xyz=\"0 0 1\"/><limit lower=\"-1\" upper=\"1\" "
                                                "effort=\"1\" velocity=\"1\"/></joint>\n"));
  const Result r = Run("simulate --robot " + urdf.string() + " --out " + (dir_ / "x.csv").string(), kTimeout);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find(urdf.string() + ":7: joint 'j3': its child link 'a' already hangs from joint 'j1' (line 5)"),
            std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "x.csv"));
}

// Item 2: outputs that are not regular files are refused (a FIFO stands in
// for /dev/full, which root replaced by a regular file), and nothing else is
// written.
TEST_F(HostileInputCliTest, OutputsThatAreNotFilesAreRefusedAndKept) {
  const fs::path fifo = Fifo("out.fifo");
  for (const std::string command : {"simulate --robot puma560 --duration 0.5", "render --robot puma560"}) {
    const Result r = Run(command + " --out " + fifo.string(), kTimeout);
    EXPECT_EQ(r.exit_code, 2) << command << ": " << r.err;
    EXPECT_NE(r.err.find("--out: '" + fifo.string() + "' is a FIFO (named pipe), not a regular file"),
              std::string::npos) << r.err;
    EXPECT_TRUE(fs::is_fifo(fifo)) << command;
  }
  // A dangling link is refused too.
  fs::create_symlink(dir_ / "nowhere" / "x.csv", dir_ / "dangling.csv");
  const Result r = Run("simulate --robot puma560 --duration 0.5 --out " + (dir_ / "dangling.csv").string());
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("is a symbolic link to '" + (dir_ / "nowhere" / "x.csv").string() + "', which does not exist"),
            std::string::npos) << r.err;
  EXPECT_TRUE(fs::is_symlink(dir_ / "dangling.csv"));
  EXPECT_FALSE(fs::exists(dir_ / "nowhere"));
}

// Issue 35 item 7: `simulate --transmission … --out X.csv` writes its
// description X.json: never over its own inputs — a design's trajectory.json
// beside the log, the transmission file — nor a CSV over its trajectory;
// each is refused before the run (exit 2) and left byte for byte.
TEST_F(HostileInputCliTest, SimulateNeverWritesOverItsOwnInputs) {
  const Result design = Run("simulate --robot puma560 --duration 0.5 --rate 100 --out " + (dir_ / "motion.csv").string());
  ASSERT_EQ(design.exit_code, 0) << design.err;
  const std::string motion_csv = Slurp(dir_ / "motion.csv");
  // A trajectory file as JSON: the CSV's samples are a trajectory too; here the description would replace it.
  const fs::path trajectory = Write("run.json", "{}");  // contents unread: the check comes first
  const fs::path transmission = Write("gear.json", R"({"reduction": [100, 100, 100, 50, 50, 50]})");
  struct Case { std::string args, message; fs::path kept; std::string kept_text; };
  const Case cases[] = {
      {"--trajectory " + trajectory.string() + " --transmission " + transmission.string() + " --out " +
           (dir_ / "run.csv").string(),
       "--out: its description '" + (dir_ / "run.json").string() + "' would overwrite the trajectory file '" +
           trajectory.string() + "'",
       trajectory, "{}"},
      {"--transmission " + transmission.string() + " --out " + (dir_ / "." / "gear.csv").string(),
       "--out: its description '" + (dir_ / "." / "gear.json").string() + "' would overwrite the transmission file '" +
           transmission.string() + "'",
       transmission, R"({"reduction": [100, 100, 100, 50, 50, 50]})"},
      {"--trajectory " + (dir_ / "motion.csv").string() + " --out " + (dir_ / "motion.csv").string(),
       "--out: '" + (dir_ / "motion.csv").string() + "' would overwrite the trajectory file '" +
           (dir_ / "motion.csv").string() + "'",
       dir_ / "motion.csv", motion_csv},
  };
  for (const Case& c : cases) {
    const Result r = Run("simulate --robot puma560 --duration 0.5 --rate 100 " + c.args);
    EXPECT_EQ(r.exit_code, 2) << c.args << ": " << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << r.err;
    EXPECT_EQ(Slurp(c.kept), c.kept_text) << c.kept;
  }
  EXPECT_FALSE(fs::exists(dir_ / "run.csv"));
}

// Item 2: a symlink is written through (the link stays, its file gets the
// log), and a file's mode is kept.
TEST_F(HostileInputCliTest, SymlinksAreWrittenThroughAndModesKept) {
  const fs::path target = Write("target.csv", "old"), link = dir_ / "link.csv";
  fs::create_symlink(target, link);
  ASSERT_EQ(::chmod(target.c_str(), 0640), 0);
  ASSERT_EQ(Run("simulate --robot puma560 --duration 0.5 --out " + link.string()).exit_code, 0);
  EXPECT_TRUE(fs::is_symlink(link));
  EXPECT_EQ(Slurp(target).rfind("t,q1,", 0), 0u) << Slurp(target).substr(0, 40);
  struct stat status;
  ASSERT_EQ(::stat(target.c_str(), &status), 0);
  EXPECT_EQ(status.st_mode & 0777, 0640u);
  // Only the target and the link (no temporary file left).
  int entries = 0;
  for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir_)) ++entries;
  EXPECT_EQ(entries, 4);  // target.csv, link.csv, stdout, stderr
}

// Item 3: FIFOs and devices as input are refused at once (a FIFO hung the
// reader; /dev/zero was read until memory ran out).
TEST_F(HostileInputCliTest, FifosAndDevicesAsInputAreRefusedAtOnce) {
  const fs::path fifo = Fifo("in.fifo");
  const std::string out = " --out " + (dir_ / "o").string();
  struct Case {
    std::string args, expected;
  };
  const Case cases[] = {
      {"identify --robot puma560 --data " + fifo.string() + out, fifo.string() + ": is a FIFO (named pipe)"},
      {"identify --robot puma560 --data /dev/zero" + out, "/dev/zero: is a character device, not a regular file"},
      {"identify --robot " + fifo.string() + " --data x.csv" + out, fifo.string() + ": is a FIFO"},
      {"design --robot puma560 --limits /dev/zero" + out, "/dev/zero: is a character device"},
      {"simulate --robot puma560 --trajectory " + fifo.string() + ".json" + out, "cannot read the file"},
  };
  for (const Case& c : cases) {
    const Result r = Run(c.args, kTimeout);
    EXPECT_EQ(r.exit_code, 2) << c.args << ": " << r.err;
    EXPECT_NE(r.err.find(c.expected), std::string::npos) << c.args << ": " << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "o")) << c.args;
  }
}

// Items 3 and 5: a line over the limit is refused naming the limit and how to
// raise it, and binary text is echoed escaped and cut (it was echoed whole as
// a "column name").
TEST_F(HostileInputCliTest, LongAndBinaryLinesAreRefusedWithAShortMessage) {
  const fs::path log = Log();
  const std::string text = Slurp(log);
  const fs::path long_line = Write("long.csv", text.substr(0, text.find('\n')) + "," + std::string(2000, '7') + "\n");
  Result r = Run("identify --robot puma560 --data " + long_line.string() + " --out " + (dir_ / "o").string(),
                 "IDBENCH_MAX_LINE_KB=1 ");
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find(long_line.string() + ":1: the line is "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("longer than the limit for a line, 1 KB (IDBENCH_MAX_LINE_KB sets it; IDBENCH_MAX_LINE_KB=N "
                       "raises it to N KB)"),
            std::string::npos) << r.err;

  std::string binary(20000, '\0');
  for (size_t k = 0; k < binary.size(); ++k) binary[k] = static_cast<char>(k * 7 % 251 + 1);
  for (char& c : binary) c = (c == '\n' || c == ',') ? 'x' : c;
  const fs::path bin = Write("binary.csv", binary + "\n1,2\n");
  r = Run("identify --robot puma560 --data " + bin.string() + " --out " + (dir_ / "o").string());
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_LT(r.err.size(), 600u) << r.err;
  EXPECT_NE(r.err.find("column 1 ('\\x01\\x08\\x0f"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("… (20000 bytes)')"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "o"));
}

// Item 5: a UTF-8 byte order mark (as spreadsheets write it) is not part of
// the first column's name ("unknown column 't'" before, the BOM invisible).
TEST_F(HostileInputCliTest, AByteOrderMarkBeforeTheHeaderIsIgnored) {
  const fs::path log = Log();
  const fs::path bom = Write("bom.csv", "\xef\xbb\xbf" + Slurp(log));
  // (With the default friction: without it the PUMA's friction torques make
  // the plausible fit no robot model, and identify exits 1; issue 20.)
  const Result r = Run("identify --robot puma560 --data " + bom.string() + " --out " + (dir_ / "o").string());
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(fs::is_regular_file(dir_ / "o" / "identified.json"));
}

// Item 3: counts and rates beyond what the machine holds are refused before
// any work, with the largest value it takes (a quarter of its memory).
TEST_F(HostileInputCliTest, CountsAndRatesBeyondTheMachineAreRefusedAtOnce) {
  const fs::path limits = Write("limits.json", R"({"joints": [{"qd_max": 1.5, "qdd_max": 4}, {"qd_max": 1.5, "qdd_max": 4},
      {"qd_max": 1.5, "qdd_max": 4}, {"qd_max": 3, "qdd_max": 8}, {"qd_max": 3, "qdd_max": 8},
      {"qd_max": 3, "qdd_max": 8}]})");
  const std::string design =
      "design --robot puma560 --quiet --limits " + limits.string() + " --out " + (dir_ / "d").string();
  Result r = Run(design + " --samples 1000000000", kTimeout);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--samples: 1000000000 samples would need "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("more than a quarter of this machine's memory"), std::string::npos) << r.err;
  r = Run(design + " --starts 1000000000", kTimeout);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--starts: 1000000000 starts would need"), std::string::npos) << r.err;
  r = Run(design + " --threads 1000000", kTimeout);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--threads: must be in 1.."), std::string::npos) << r.err;
  // --rate: rows of trajectory.csv over the default 10 s design (f0 = 0.1 Hz),
  // each (25 + 8)·(1 + 3·6) = 627 bytes; the bound computed here from
  // sysconf, independently of idbench's code.
  const double budget = static_cast<double>(sysconf(_SC_PHYS_PAGES)) * sysconf(_SC_PAGESIZE) / 4;
  const long long max_rows = static_cast<long long>(std::min(std::floor(budget / 627.0), double{INT_MAX}));
  r = Run(design + " --rate 1e12", kTimeout);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--rate 1e+12: 10000000000001 rows of trajectory.csv would need"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("at most " + std::to_string(max_rows) + " rows of trajectory.csv on this machine"),
            std::string::npos) << r.err;
  r = Run("montecarlo --robot puma560 --samples 2000000000", kTimeout);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find("--samples: 2000000000 samples would need"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "d"));
}

// Items 3 and 4: a trajectory file with 200 000 harmonics, or f0 = 1e-300
// (which gave q ≈ -1.6e297 rad and exit 0), is refused.
TEST_F(HostileInputCliTest, TrajectoryFilesOutsideWhatCanBeFollowedAreRefused) {
  const auto fourier = [](double f0, int harmonics) {
    std::string row = "[";
    for (int k = 0; k < harmonics; ++k) row += (k ? ",0.01" : "0.01");
    row += "]";
    std::string rows = "[";
    for (int j = 0; j < 6; ++j) rows += (j ? "," : "") + row;
    rows += "]";
    char f0_text[32];
    std::snprintf(f0_text, sizeof(f0_text), "%.17g", f0);
    return std::string(R"({"family": "fourier", "f0": )") + f0_text +
           R"(, "duration": 1, "q0": [0,0,0,0,0,0], "a": )" + rows + R"(, "b": )" + rows + "}";
  };
  const fs::path many = Write("many.json", fourier(0.1, 200000));
  const std::string out = " --duration 1 --out " + (dir_ / "x.csv").string();
  Result r = Run("simulate --robot puma560 --trajectory " + many.string() + out, kTimeout);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find(many.string() + ": key 'a': 200000 harmonics, at most 50"), std::string::npos) << r.err;
  const fs::path slow = Write("slow.json", fourier(1e-300, 2));
  r = Run("simulate --robot puma560 --trajectory " + slow.string() + out, kTimeout);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find(slow.string() + ": at t = 0 s joint 1 has q = "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("expected finite values and |q| <= 1e6 rad"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(dir_ / "x.csv"));
}

// Item 5: every command says the same for an --out that is an existing file
// (exit 2 from identify/design/run but 1 from montecarlo/compare before).
TEST_F(HostileInputCliTest, AnOutDirectoryThatIsAFileIsOneMessageForEveryCommand) {
  const fs::path file = Write("file.txt", "mine");
  const std::string out = " --out " + file.string();
  for (const std::string command :
       {"run", "identify --robot puma560 --data x.csv", "design --robot puma560", "montecarlo --robot puma560",
        "compare general", "gains --data x.csv --loaded y.csv --payload-mass 1"}) {
    const Result r = Run(command + out);
    EXPECT_EQ(r.exit_code, 2) << command << ": " << r.err;
    EXPECT_EQ(r.err, "idbench: error: --out: '" + file.string() + "' exists and is not a directory\n") << command;
    EXPECT_EQ(Slurp(file), "mine");
  }
}

// Items 1, 3 and 5 in the GUI: a failed job exits 1 (it exited 0), a bad
// script 2 (nothing ran), and a FIFO as the robot does not freeze it.
TEST_F(HostileInputCliTest, GuiScriptExitCodesFollowTheRule) {
  const std::string gui = "LP_NUM_THREADS=1 " + kTimeout + exe_ + " gui --headless --size 640x400 --out " +
                          (dir_ / "out").string();
  const auto run = [&](const std::string& args) {
    const int status = std::system((gui + " " + args + " >" + (dir_ / "stdout").string() + " 2>" +
                                    (dir_ / "stderr").string()).c_str());
    return WEXITSTATUS(status);
  };
  // paper6r has no velocity limits: the design job fails.
  const fs::path failing = Write("design.txt", "click tab.design\nclick design.run\nwait design 60\n");
  EXPECT_EQ(run("--robot paper6r --script " + failing.string()), 1) << Slurp(dir_ / "stderr");
  EXPECT_NE(Slurp(dir_ / "stderr").find("1 error in the Messages panel"), std::string::npos) << Slurp(dir_ / "stderr");
  const fs::path bad = Write("bad.txt", "frames 1\njump design\n");
  EXPECT_EQ(run("--script " + bad.string()), 2) << Slurp(dir_ / "stderr");
  EXPECT_NE(Slurp(dir_ / "stderr").find(bad.string() + ":2: unknown step 'jump'"), std::string::npos);
  const fs::path fifo = Fifo("robot.fifo");
  const fs::path frames = Write("frames.txt", "frames 2\n");
  EXPECT_EQ(run("--robot " + fifo.string() + " --script " + frames.string()), 1) << Slurp(dir_ / "stderr");
  EXPECT_NE(Slurp(dir_ / "stdout").find(fifo.string() + ": is a FIFO"), std::string::npos) << Slurp(dir_ / "stdout");
}

}  // namespace
}  // namespace idbench::testing
