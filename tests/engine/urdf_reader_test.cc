#include "idbench/engine/urdf.h"

#include <gtest/gtest.h>

#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "engine/urdf_test_util.h"
#include "idbench/engine/paper6r.h"

namespace idbench {
namespace {

using namespace urdf_testing;

// ---- Round trips ----

TEST(UrdfTest, ShippedPaper6rUrdfEqualsMakePaper6r) {
  const std::string path = std::string(IDBENCH_SOURCE_DIR) + "/engine/robots/paper6r.urdf";
  const UrdfLoadResult loaded = LoadUrdfFile(path);
  EXPECT_TRUE(loaded.warnings.empty());
  ExpectModelsNear(loaded.model, MakePaper6r(), 1e-12);
}

// ---- Rejections, each naming the culprit ----

TEST(UrdfTest, RejectsWhatUrdfdomCannotParse) {
  ExpectRejected("this is not xml", {"broken.urdf: not a valid URDF"}, "broken.urdf");
  ExpectRejected("<robot name=\"r\"><link name=\"a\"/><joint name=\"j\" type=\"revolute\">", {"not a valid URDF"});
  // A joint whose child link does not exist.
  ExpectRejected(Robot(BareLink("base") + Joint("j1", "revolute", "base", "ghost")), {"not a valid URDF"});
  // A revolute joint without <limit> (URDF requires it).
  ExpectRejected(Robot(BareLink("base") + MassLink("a") + Joint("j1", "revolute", "base", "a", "")),
                 {"not a valid URDF"});
}

TEST(UrdfTest, RejectsUnreadableFilesNamingThePath) {
  for (const std::string& path : {std::string("/nonexistent/dir/robot.urdf"), std::string(IDBENCH_SOURCE_DIR)}) {
    try {
      LoadUrdfFile(path);
      ADD_FAILURE() << "expected std::invalid_argument for " << path;
    } catch (const std::invalid_argument& e) {
      EXPECT_NE(std::string(e.what()).find(path), std::string::npos) << e.what();
    }
  }
}

// ---- Hostile and broken files (issue 14) ----

// Input files that are not regular files are refused before reading: a FIFO
// would block (hang) the reader, /dev/zero never ends.
TEST(UrdfTest, NonRegularFilesAreRefusedNamingWhatTheyAre) {
  namespace fs = std::filesystem;
  const fs::path fifo = fs::temp_directory_path() / ("idbench_urdf_fifo_" + std::to_string(::getpid()));
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  for (const auto& [path, kind] : std::vector<std::pair<std::string, std::string>>{
           {fifo.string(), "is a FIFO"}, {"/dev/zero", "is a character device"}, {"/tmp", "is a directory"}}) {
    try {
      LoadUrdfFile(path);
      ADD_FAILURE() << "expected std::invalid_argument for " << path;
    } catch (const std::invalid_argument& e) {
      EXPECT_EQ(std::string(e.what()).rfind(path + ": " + kind, 0), 0u) << e.what();
    }
  }
  fs::remove(fifo);
}

}  // namespace
}  // namespace idbench
