// Hostile ROS 2 bags through the command line (issue 35 items 6, 13, 17, 21):
// each is refused at once with exit 2 (the input is wrong, nothing ran) and
// one line naming the file and what is wrong. Run under `timeout`, so a
// reader blocked on a FIFO fails (exit 124) instead of stalling the tests.
#include <sys/stat.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "logs/rosbag2/bag_fixtures.h"
#include "workbench/cli/cli_fixture.h"

namespace idbench::testing {
namespace {

namespace fs = std::filesystem;

const std::string kBagReadTimeout = "timeout 30 ";

class HostileBagsCliTest : public CliFixture {
 protected:
  fs::path Write(const std::string& name, const std::string& text) {
    fs::create_directories((dir_ / name).parent_path());
    std::ofstream(dir_ / name, std::ios::binary) << text;
    return dir_ / name;
  }
  // `identify` of `data`: exit 2 and `expected` in its one-line error.
  void ExpectRefused(const fs::path& data, const std::string& expected) {
    const Result r = Run("identify --robot puma560 --data " + data.string() + " --out " + (dir_ / "o").string(),
                         kBagReadTimeout);
    EXPECT_EQ(r.exit_code, 2) << data << ": " << r.err;
    EXPECT_NE(r.err.find("idbench: error: " + expected), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "o")) << data;
  }
};

TEST_F(HostileBagsCliTest, FifosAreRefusedAtOnce) {
  for (const std::string name : {"run.mcap", "run_0.db3", "bag/metadata.yaml"}) {
    fs::create_directories((dir_ / name).parent_path());
    ASSERT_EQ(::mkfifo((dir_ / name).c_str(), 0600), 0);
    ExpectRefused(dir_ / name, (dir_ / name).string() + ": is a FIFO (named pipe), not a regular file");
  }
  ExpectRefused(dir_ / "bag", (dir_ / "bag/metadata.yaml").string() + ": is a FIFO (named pipe)");
}

TEST_F(HostileBagsCliTest, MetadataFieldsAreNamed) {
  const fs::path metadata =
      Write("bag/metadata.yaml", "rosbag2_bagfile_information:\n  storage_identifier: {a: 1}\n"
                                 "  relative_file_paths: [bag_0.mcap]\n");
  ExpectRefused(dir_ / "bag", metadata.string() + ": storage_identifier: expected a string, got a map");
  Write("bag/metadata.yaml", "rosbag2_bagfile_information:\n  storage_identifier: mcap\n"
                             "  relative_file_paths: [[bag_0.mcap]]\n");
  ExpectRefused(dir_ / "bag", metadata.string() + ": relative_file_paths[0]: expected a string, got a list");
}

TEST_F(HostileBagsCliTest, FoldersAndDirectoriesAreNamedAsSuch) {
  fs::create_directories(dir_ / "rosbag2_run");
  fs::copy_file(kBags / "joint_states_zstd.mcap", dir_ / "rosbag2_run" / "run_0.mcap");
  ExpectRefused(dir_ / "rosbag2_run", (dir_ / "rosbag2_run").string() +
                                          ": a directory without metadata.yaml, so not a rosbag2 bag folder (it "
                                          "holds run_0.mcap: pass one of those files to read it alone)");
  fs::create_directories(dir_ / "bag_0.mcap");
  ExpectRefused(dir_ / "bag_0.mcap", (dir_ / "bag_0.mcap").string() + ": is a directory, not a regular file");
}

// AddressSanitizer reserves terabytes of shadow address space at start-up,
// so no address-space cap can be set under it (the sanitizer stage checks
// the message; the Release suite the cap too).
#if defined(__SANITIZE_ADDRESS__)
constexpr bool kUnderAddressSanitizer = true;
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
constexpr bool kUnderAddressSanitizer = true;
#else
constexpr bool kUnderAddressSanitizer = false;
#endif
#else
constexpr bool kUnderAddressSanitizer = false;
#endif

// The zstd fixture's chunk #2 (offset 4642) saying uncompressed_size 2^31 - 1:
// refused before 2 GB are allocated (under a 1 GB address-space limit the old
// reader failed with std::bad_alloc, exit 1).
TEST_F(HostileBagsCliTest, AChunkSizeTheRecordsCannotGiveIsNamed) {
  std::ifstream in(kBags / "joint_states_zstd.mcap", std::ios::binary);
  std::vector<char> data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const std::uint64_t size = (std::uint64_t{1} << 31) - 1;
  for (int i = 0; i < 8; ++i) data.at(4642 + 25 + static_cast<std::size_t>(i)) = static_cast<char>(size >> (8 * i));
  const fs::path bag = dir_ / "huge_chunk.mcap";
  std::ofstream(bag, std::ios::binary).write(data.data(), static_cast<std::streamsize>(data.size()));
  const Result r = Run("identify --robot puma560 --data " + bag.string() + " --out " + (dir_ / "o").string(),
                       std::string(kUnderAddressSanitizer ? "" : "ulimit -v 1000000; ") + kBagReadTimeout);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_NE(r.err.find(bag.string() + ": message 22: Chunk record at offset 4642: uncompressed_size 2147483647 bytes, "
                                      "but 2001 bytes of zstd records give at most 65568768"),
            std::string::npos)
      << r.err;
}

}  // namespace
}  // namespace idbench::testing
