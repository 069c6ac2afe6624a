#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>

#include "core/file_text.h"
#include "support/errors.h"

namespace nx {
namespace {

TEST(FileText, ReadsARegularFileWhole) {
  const std::string path = ::testing::TempDir() + "nx_file_text.txt";
  std::ofstream(path, std::ios::binary) << std::string("a\0b\nc", 5);
  EXPECT_EQ(readRegularFile(path, 1024, "table"), std::string("a\0b\nc", 5));
  std::filesystem::remove(path);
}

// Nothing that is not a regular file is opened: a FIFO would block the reader forever, a
// device (/dev/zero) never ends.
TEST(FileText, RefusesDirectoriesFifosAndDevicesWithoutReading) {
  const std::string fifo = ::testing::TempDir() + "nx_file_text.fifo";
  std::filesystem::remove(fifo);
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  EXPECT_EQ(test::errorMessage([&] { readRegularFile(fifo, 1024, "scene file"); }),
            fifo + ": expected a scene file (a regular file), found a FIFO, socket or device");
  std::filesystem::remove(fifo);
  EXPECT_EQ(test::errorMessage([] { readRegularFile("/dev/zero", 1024, "table"); }),
            "/dev/zero: expected a table (a regular file), found a FIFO, socket or device");
  EXPECT_EQ(test::errorMessage([] { readRegularFile("/", 1024, "table"); }),
            "/: expected a table, found a directory");
  EXPECT_EQ(test::errorMessage([] { readRegularFile("/nonexistent/x", 1024, "table"); }),
            "/nonexistent/x: cannot open the table");
}

// A sparse file of 1 GiB is refused from its size, before any of it is read.
TEST(FileText, RefusesAnOversizedFileBeforeReadingIt) {
  const std::string path = ::testing::TempDir() + "nx_file_text_sparse.bin";
  { std::ofstream f(path, std::ios::binary); }
  std::filesystem::resize_file(path, 1ull << 30);
  EXPECT_EQ(test::errorMessage([&] { readRegularFile(path, 64u << 20, "scene file"); }),
            path + ": expected a scene file of at most 64 MiB");
  std::filesystem::remove(path);
}

} // namespace
} // namespace nx
