// LoadYamlWithoutAliases (yaml_input.h): the YAML files idbench reads (log
// descriptions, a bag's metadata.yaml) are refused at their first alias, so
// that nothing walking the document can expand an alias bomb (issue 35 item 4).
#include "yaml_input.h"

#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "engine/test_util.h"
#include "idbench/engine/puma560.h"
#include "idbench/logs/open_joint_log.h"

namespace idbench {
namespace {

namespace fs = std::filesystem;
using testing::ExpectInvalid;

TEST(YamlInputTest, AnAliasIsRefusedWithItsPlace) {
  EXPECT_EQ(ExpectInvalid([] { internal::LoadYamlWithoutAliases("a: &x [1, 2]\nb:\n  - *x\n", "f.yaml"); }),
            "f.yaml:3:5: an alias (*name): aliases are not read (each would be expanded where it stands); write the "
            "value out");
  // Without an alias: the document as yaml-cpp reads it, anchors and all.
  const YAML::Node node = internal::LoadYamlWithoutAliases("a: &x [1, 2]\nb: {c: 3}\n", "f.yaml");
  EXPECT_EQ(node["a"][1].as<int>(), 2);
  EXPECT_EQ(node["b"]["c"].as<int>(), 3);
  // A syntax error stays yaml-cpp's (the callers name the line from its mark).
  EXPECT_THROW(internal::LoadYamlWithoutAliases("a: [1, 2\n", "f.yaml"), YAML::Exception);
}

// A bag's metadata.yaml with an alias (1c4dd0f read it with YAML::LoadFile,
// aliases shared, expanded by whatever walked them): refused naming the file.
TEST(YamlInputTest, BagMetadataWithAnAliasIsRefused) {
  const fs::path bag = fs::path(::testing::TempDir()) / ("alias_bag_" + std::to_string(::getpid()));
  fs::create_directories(bag);
  std::ofstream(bag / "metadata.yaml") << "rosbag2_bagfile_information:\n  storage_identifier: &s mcap\n"
                                          "  relative_file_paths: [*s]\n";
  const std::string what =
      ExpectInvalid([&] { OpenJointLog(bag.string(), MakePuma560(), {}, TorqueColumns::kRequired); });
  EXPECT_EQ(what, (bag / "metadata.yaml").string() + ":3:25: an alias (*name): aliases are not read (each would be "
                                                     "expanded where it stands); write the value out");
  fs::remove_all(bag);
}

}  // namespace
}  // namespace idbench
