#include <gtest/gtest.h>

#define STB_IMAGE_IMPLEMENTATION
#include <stb/stb_image.h>

#include <filesystem>
#include <fstream>
#include <iterator>

#include "core/error.h"
#include "io/atomic_file.h"
#include "io/preview_image.h"

namespace nx {
namespace {

std::vector<uint8_t> gradient(int w, int h) {
  std::vector<uint8_t> px;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x)
      for (int c = 0; c < 3; ++c) px.push_back(static_cast<uint8_t>(x * 40 + y * 7 + c * 3));
  return px;
}

TEST(PreviewImage, PngRoundTrip) {
  const auto px = gradient(7, 5);
  const std::string path = ::testing::TempDir() + "p.png";
  writePreview(path, 7, 5, px);
  int w, h, n;
  uint8_t* data = stbi_load(path.c_str(), &w, &h, &n, 3);
  ASSERT_NE(data, nullptr);
  EXPECT_EQ(w, 7);
  EXPECT_EQ(h, 5);
  EXPECT_TRUE(std::equal(px.begin(), px.end(), data));
  stbi_image_free(data);
}

// A 3-pixel-wide BMP has 9 bytes of pixels per row, padded to 12; rows are stored bottom-up
// in BGR order after a 54-byte header.
TEST(PreviewImage, BmpRowsArePadded) {
  const int w = 3, h = 2;
  const auto px = gradient(w, h);
  const std::string path = ::testing::TempDir() + "p.bmp";
  writePreview(path, w, h, px);
  std::ifstream f(path, std::ios::binary);
  const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(f)), {});
  ASSERT_EQ(bytes.size(), 54u + 12u * h);
  EXPECT_EQ(bytes[0], 'B');
  EXPECT_EQ(bytes[1], 'M');
  auto le32 = [&](size_t o) {
    return bytes[o] | bytes[o + 1] << 8 | bytes[o + 2] << 16 | bytes[o + 3] << 24;
  };
  EXPECT_EQ(le32(2), static_cast<int>(bytes.size()));
  EXPECT_EQ(le32(18), w);
  EXPECT_EQ(le32(22), h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const size_t fileRow = static_cast<size_t>(h - 1 - y);
      const size_t o = 54 + fileRow * 12 + static_cast<size_t>(x) * 3;
      const size_t p = (static_cast<size_t>(y) * w + x) * 3;
      EXPECT_EQ(bytes[o + 0], px[p + 2]);
      EXPECT_EQ(bytes[o + 1], px[p + 1]);
      EXPECT_EQ(bytes[o + 2], px[p + 0]);
    }
  int rw, rh, n;
  uint8_t* data = stbi_load(path.c_str(), &rw, &rh, &n, 3);
  ASSERT_NE(data, nullptr);
  EXPECT_TRUE(std::equal(px.begin(), px.end(), data));
  stbi_image_free(data);
}

TEST(PreviewImage, Errors) {
  EXPECT_THROW(writePreview(::testing::TempDir() + "p.jpg", 1, 1, {0, 0, 0}), Error);
  EXPECT_THROW(writePreview(::testing::TempDir() + "p.png", 2, 1, {0, 0, 0}), Error);
  EXPECT_THROW(writePreview("/nonexistent-dir/p.png", 1, 1, {0, 0, 0}), Error);
  EXPECT_TRUE(isPreviewPath("a/b.BMP"));
  EXPECT_FALSE(isPreviewPath("a.b/c"));
}

TEST(AtomicFile, CheckWritable) {
  EXPECT_NO_THROW(checkWritable(::testing::TempDir() + "out.exr"));
  EXPECT_THROW(checkWritable("/nonexistent-dir/out.exr"), Error);
  EXPECT_THROW(checkWritable(::testing::TempDir()), Error);
}

TEST(AtomicFile, CheckFreeSpace) {
  EXPECT_NO_THROW(checkFreeSpace(::testing::TempDir() + "out.exr", 1.0));
  try {
    checkFreeSpace(::testing::TempDir() + "out.exr", 1e18);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("out.exr: needs about 1000000000000 MB but only"),
              std::string::npos)
        << e.what();
  }
}

TEST(AtomicFile, FailedWriteLeavesNoFile) {
  const std::string path = ::testing::TempDir() + "atomic.txt";
  std::filesystem::remove(path);
  EXPECT_THROW(writeAtomically(path,
                               [](const std::string& temp) {
                                 std::ofstream(temp) << "half";
                                 throw std::runtime_error("disk full");
                               }),
               Error);
  EXPECT_FALSE(std::filesystem::exists(path));
  EXPECT_FALSE(std::filesystem::exists(atomicTempName(path, ::getpid())));
}

// A name of 250 bytes is written (the temporary name is short whatever the target's).
TEST(AtomicFile, LongNamesAreWritten) {
  const std::string path = ::testing::TempDir() + std::string(246, 'n') + ".exr";
  writeAtomically(path, [](const std::string& temp) { std::ofstream(temp) << "x"; });
  EXPECT_TRUE(std::filesystem::exists(path));
  std::filesystem::remove(path);
}

// Temporary files of a process killed while writing (SIGKILL) are removed by the next check of
// the same target; those of a live process are kept.
TEST(AtomicFile, StaleTemporariesAreRemoved) {
  const std::string path = ::testing::TempDir() + "stale.exr";
  const std::string dead = atomicTempName(path, 0x7ffffff0),
                    alive = atomicTempName(path, ::getpid());
  std::ofstream(dead) << "left by a killed process";
  std::ofstream(alive) << "being written";
  checkWritable(path);
  EXPECT_FALSE(std::filesystem::exists(dead));
  EXPECT_TRUE(std::filesystem::exists(alive));
  std::filesystem::remove(alive);
}

// Writing through a symlink replaces the file it points to and keeps the link.
TEST(AtomicFile, SymlinkTargetIsReplacedNotTheLink) {
  const std::string dir = ::testing::TempDir();
  std::filesystem::remove(dir + "link.exr");
  std::ofstream(dir + "real.exr") << "old";
  std::filesystem::create_symlink(dir + "real.exr", dir + "link.exr");
  checkWritable(dir + "link.exr");
  writeAtomically(dir + "link.exr", [](const std::string& temp) { std::ofstream(temp) << "new"; });
  EXPECT_TRUE(std::filesystem::is_symlink(dir + "link.exr"));
  std::ifstream in(dir + "real.exr");
  std::string text;
  in >> text;
  EXPECT_EQ(text, "new");
  std::filesystem::remove(dir + "link.exr");
  std::filesystem::remove(dir + "real.exr");
}

} // namespace

namespace {
std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}
void writeText(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}
} // namespace

// An EXR and its preview are replaced as one group: both or neither.
TEST(AtomicFile, GroupsReplaceTheirFilesTogether) {
  const std::string exr = ::testing::TempDir() + "pair.exr",
                    png = ::testing::TempDir() + "pair.png";
  writeText(exr, "old exr");
  writeText(png, "old png");
  const auto writeBoth = [&](bool commit) {
    AtomicFileGroup group;
    writeAtomically(exr, [](const std::string& t) { writeText(t, "new exr"); });
    writeAtomically(png, [](const std::string& t) { writeText(t, "new png"); });
    EXPECT_EQ(slurp(exr), "old exr"); // nothing replaced before the commit
    EXPECT_EQ(slurp(png), "old png");
    if (commit) group.commit();
  };
  writeBoth(false); // e.g. an exception before the commit: the old pair stays, no temporaries
  EXPECT_EQ(slurp(exr), "old exr");
  EXPECT_EQ(slurp(png), "old png");
  EXPECT_FALSE(std::filesystem::exists(atomicTempName(exr, ::getpid())));
  writeBoth(true);
  EXPECT_EQ(slurp(exr), "new exr");
  EXPECT_EQ(slurp(png), "new png");
  EXPECT_FALSE(std::filesystem::exists(atomicTempName(exr, ::getpid()) + ".group"));
}

// What a process killed between a group's two renames leaves (its journal, the EXR replaced,
// the preview still under its temporary name) is completed by the next check of the output:
// the new EXR is never left beside the old preview.
TEST(AtomicFile, AGroupCutByAKillIsCompletedByTheNextCheck) {
  const std::string exr = ::testing::TempDir() + "killed.exr",
                    png = ::testing::TempDir() + "killed.png";
  const long dead = 0x7ffffff0;
  const std::string pngTemp = atomicTempName(png, dead), exrTemp = atomicTempName(exr, dead);
  writeText(exr, "new exr"); // renamed before the kill
  writeText(png, "old png");
  writeText(pngTemp, "new png");
  writeText(atomicTempName(exr, dead) + ".group",
            exrTemp + "\t" + exr + "\n" + pngTemp + "\t" + png + "\n");
  checkWritable(exr);
  EXPECT_EQ(slurp(exr), "new exr");
  EXPECT_EQ(slurp(png), "new png");
  EXPECT_FALSE(std::filesystem::exists(pngTemp));
  EXPECT_FALSE(std::filesystem::exists(atomicTempName(exr, dead) + ".group"));
  // Killed before the journal: the temporaries are stale, the old pair stays.
  writeText(exrTemp, "newer exr");
  writeText(pngTemp, "newer png");
  checkWritable(exr);
  checkWritable(png);
  EXPECT_EQ(slurp(exr), "new exr");
  EXPECT_EQ(slurp(png), "new png");
  EXPECT_FALSE(std::filesystem::exists(exrTemp));
  EXPECT_FALSE(std::filesystem::exists(pngTemp));
}

} // namespace nx
