// <camera calibration="calib.yml" view="N"/>: OpenCV calibration files (cv::FileStorage YAML and
// XML, read by OpenCV itself) set the intrinsics, distortion and pose exactly as the equivalent
// <intrinsics>, <distortion> and <extrinsics> elements; the rotation vector's matrix is checked
// against the properties that define it; bad files and mismatches get clear errors.

#include <gtest/gtest.h>

#include <unistd.h>

#include <atomic>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>
#include <thread>
#include <utility>
#include <vector>

#include "integrators/scene_reader.h"
#include "io/isolated_call.h"
#include "io/opencv_calibration.h"
#include "io/scene_desc.h"
#include "support/errors.h"

namespace nx {
namespace {

const char* kYaml = R"(%YAML:1.0
---
image_width: 64
image_height: 48
camera_matrix: !!opencv-matrix
   rows: 3
   cols: 3
   dt: d
   data: [ 70., 0., 31.5, 0., 72., 23.5, 0., 0., 1. ]
distortion_coefficients: !!opencv-matrix
   rows: 1
   cols: 5
   dt: d
   data: [ -0.1, 0.01, 0.001, -0.002, 0.003 ]
rvecs: !!opencv-matrix
   rows: 2
   cols: 3
   dt: d
   data: [ 0.1, -0.2, 0.3, 0., 0., 0. ]
tvecs: !!opencv-matrix
   rows: 2
   cols: 3
   dt: d
   data: [ 0.5, -0.25, 4., 0., 0., 5. ]
)";

const char* kXml = R"(<?xml version="1.0"?>
<opencv_storage>
<image_size>64 48</image_size>
<K type_id="opencv-matrix"><rows>3</rows><cols>3</cols><dt>d</dt>
  <data>70. 0. 31.5 0. 72. 23.5 0. 0. 1.</data></K>
<D type_id="opencv-matrix"><rows>1</rows><cols>4</cols><dt>d</dt>
  <data>-0.1 0.01 0.001 -0.002</data></D>
<R type_id="opencv-matrix"><rows>3</rows><cols>1</cols><dt>d</dt><data>0.1 -0.2 0.3</data></R>
<T type_id="opencv-matrix"><rows>3</rows><cols>1</cols><dt>d</dt><data>0.5 -0.25 4.</data></T>
</opencv_storage>
)";

std::string written(const std::string& name, const std::string& text) {
  const std::string path = ::testing::TempDir() + "/" + name;
  std::ofstream(path) << text;
  return path;
}

std::string scene(const std::string& camera, int w = 64, int h = 48) {
  return "<scene><settings><xres>" + std::to_string(w) + "</xres><yres>" + std::to_string(h) +
         "</yres><mode>spectral_mcpt</mode></settings>" + camera + "</scene>";
}

TEST(OpenCvCalibration, RotationVectorsBecomeRotations) {
  const OpenCvCalibration c = parseOpenCvCalibration(kYaml, "calib.yml", 0);
  ASSERT_TRUE(c.extrinsics);
  const auto& e = *c.extrinsics;
  const double r[3] = {0.1, -0.2, 0.3}, angle = std::sqrt(0.14);
  // Orthonormal with determinant 1, the axis r fixed, the angle |r| (trace 1 + 2 cos |r|).
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      double dotij = 0;
      for (int k = 0; k < 3; ++k) dotij += e[3 * k + i] * e[3 * k + j];
      EXPECT_NEAR(dotij, i == j ? 1 : 0, 1e-12);
    }
  for (int i = 0; i < 3; ++i)
    EXPECT_NEAR(e[3 * i] * r[0] + e[3 * i + 1] * r[1] + e[3 * i + 2] * r[2], r[i], 1e-12);
  EXPECT_NEAR(e[0] + e[4] + e[8], 1 + 2 * std::cos(angle), 1e-12);
  EXPECT_EQ(e[9], 0.5);
  EXPECT_EQ(e[11], 4.0);
  EXPECT_EQ(c.views, 2);
  ASSERT_TRUE(c.imageSize);
  EXPECT_EQ((*c.imageSize)[0], 64);
  EXPECT_EQ(c.intrinsics, (std::array<double, 4>{70, 72, 31.5, 23.5}));
  EXPECT_EQ(c.distortion[4], 0.003);
}

// OpenCV reads in a helper program started by posix_spawn, not in a fork of this process (a
// fork of a multi-threaded process can deadlock on a lock another thread held): this
// process's children are that program. Reads from several threads at once, while others keep
// allocating, all answer.
TEST(OpenCvCalibration, TheReaderIsAHelperProgramNotAFork) {
  (void)parseOpenCvCalibration(kYaml, "calib.yml", 0);
  std::vector<std::string> children;
  for (const auto& task : std::filesystem::directory_iterator("/proc/self/task")) {
    std::ifstream in(task.path() / "children");
    for (long pid; in >> pid;) {
      std::error_code ec;
      const auto exe = std::filesystem::read_symlink("/proc/" + std::to_string(pid) + "/exe", ec);
      if (!ec) children.push_back(exe.filename().string());
    }
  }
  ASSERT_FALSE(children.empty()) << "no reader process";
  for (const std::string& c : children) EXPECT_EQ(c, kCalibrationReaderProgram);
  EXPECT_NE(helperProgramPath(kCalibrationReaderProgram), "");
  EXPECT_EQ(helperProgramPath("no-such-helper"), "");
  std::atomic<bool> stop{false};
  std::thread busy([&] { // keeps the allocator's locks busy
    volatile double sink = 0;
    while (!stop) {
      std::vector<double> v(1000, 1.0);
      sink = sink + v[999];
    }
  });
  std::vector<std::thread> readers;
  std::atomic<int> ok{0};
  for (int t = 0; t < 4; ++t)
    readers.emplace_back([&] {
      for (int k = 0; k < 5; ++k)
        if (parseOpenCvCalibration(kYaml, "calib.yml", 0).intrinsics[0] > 0) ++ok;
    });
  for (std::thread& r : readers) r.join();
  stop = true;
  busy.join();
  EXPECT_EQ(ok, 20);
}

TEST(OpenCvCalibration, YamlAndXmlSetTheCameraAsItsElementsWould) {
  const std::string yml = written("calib.yml", kYaml), xml = written("calib.xml", kXml);
  const OpenCvCalibration c = parseOpenCvCalibration(kYaml, "calib.yml", 0);
  std::string ex;
  for (double v : *c.extrinsics) ex += (ex.empty() ? "" : ", ") + exactNumberText(v);
  const SceneDesc byElements = parseScene(
      scene("<camera><intrinsics>70, 72, 31.5, 23.5</intrinsics><distortion>-0.1, 0.01, 0.001, "
            "-0.002, 0.003</distortion><extrinsics>" +
            ex + "</extrinsics></camera>"),
      "t.scn");
  const SceneDesc byYaml =
      parseScene(scene("<camera calibration=\"" + yml + "\" view=\"0\"/>"), "t.scn");
  EXPECT_EQ(byYaml.camera.intrinsics, byElements.camera.intrinsics);
  EXPECT_EQ(byYaml.camera.distortion, byElements.camera.distortion);
  EXPECT_EQ(byYaml.camera.extrinsics, byElements.camera.extrinsics);
  // The XML form (K, D of 4, R as a rotation vector, T) gives the same pose and k3 = 0.
  const SceneDesc byXml = parseScene(scene("<camera calibration=\"" + xml + "\"/>"), "t.scn");
  EXPECT_EQ(byXml.camera.intrinsics, byElements.camera.intrinsics);
  EXPECT_EQ(byXml.camera.extrinsics, byElements.camera.extrinsics);
  EXPECT_EQ(byXml.camera.distortion[4], 0.0);
  // View 1 is the other pose; the file's bytes are in the render key.
  const SceneDesc view1 =
      parseScene(scene("<camera calibration=\"" + yml + "\" view=\"1\"/>"), "t.scn");
  EXPECT_EQ((*view1.camera.extrinsics)[11], 5.0);
  EXPECT_NE(view1.textDigest,
            parseScene(scene("<camera calibration=\"" + xml + "\"/>"), "t.scn").textDigest);
}

TEST(OpenCvCalibration, BadFilesAndMismatchesAreRefused) {
  const std::string yml = written("calib2.yml", kYaml);
  auto error = [](const std::string& text) {
    return test::errorMessage([&] { parseScene(text, "t.scn"); });
  };
  const std::string cam = "<camera calibration=\"" + yml + "\"";
  EXPECT_NE(
      error(scene(cam + "/>")).find("expected view=\"N\" on <camera> (the file holds 2 views)"),
      std::string::npos);
  EXPECT_NE(error(scene(cam + " view=\"2\"/>")).find("expected a view from 0 to 1, found 2"),
            std::string::npos);
  EXPECT_NE(error(scene(cam + " view=\"0\"/>", 640, 480))
                .find("expected <xres>, <yres> of the calibration's image (64x48"),
            std::string::npos);
  EXPECT_NE(error(scene(cam + " view=\"0\"><fov>40</fov></camera>"))
                .find("either calibration=\"...\" or <fov> on <camera>"),
            std::string::npos);
  EXPECT_NE(error(scene(cam + " view=\"0\"><position>0,0,0</position></camera>"))
                .find("no <position> with a calibration file that gives the pose"),
            std::string::npos);
  EXPECT_NE(error(scene("<camera view=\"0\"/>")).find("view=\"N\" only with calibration"),
            std::string::npos);
  const std::string noK = written("nok.yml", "%YAML:1.0\n---\nimage_width: 64\n");
  EXPECT_NE(error(scene("<camera calibration=\"" + noK + "\"/>"))
                .find("expected a camera matrix (camera_matrix, cameraMatrix or K), found none"),
            std::string::npos);
  const std::string garbage = written("garbage.yml", "%YAML:1.0\n---\n: : [ {\n");
  EXPECT_NE(error(scene("<camera calibration=\"" + garbage + "\"/>")).find("t.scn:1: "),
            std::string::npos);
  const std::string rational =
      written("rational.yml", "%YAML:1.0\n---\nK: [70., 0., 31.5, 0., 72., 23.5, 0., 0., 1.]\n"
                              "D: [0.1, 0., 0., 0., 0., 0.5, 0., 0.]\n");
  EXPECT_NE(error(scene("<camera calibration=\"" + rational +
                        "\"><position>0,0,-5</position>"
                        "<look_at>0,0,0</look_at></camera>"))
                .find("at most 5 non-zero distortion coefficients"),
            std::string::npos);
  EXPECT_NE(
      error(scene("<camera calibration=\"/nonexistent/calib.yml\"/>")).find("calibration file"),
      std::string::npos);
}

// A calibration file's text: an image size and camera matrix, then `rest`.
std::string calibration(const std::string& rest,
                        const std::string& size = "image_width: 64\nimage_height: 48\n") {
  return "%YAML:1.0\n---\n" + size + "K: [70., 0., 31.5, 0., 72., 23.5, 0., 0., 1.]\n" + rest;
}

std::string calibrationError(const std::string& text, std::optional<int> view = 1) {
  return test::errorMessage([&] { parseOpenCvCalibration(text, "c.yml", view); });
}

// Ragged rows were read past their heap block (view 1 of [[0.1, 0.2], [0, 0, 0, -0.5, -0.5, 3]]
// read 4 doubles beyond 8; valgrind: invalid read) or gave a view another's numbers: every
// table's rows must be as long as its first, named by file and row.
TEST(OpenCvCalibration, RaggedRowsAreRefusedWithTheRow) {
  EXPECT_EQ(calibrationError(calibration("extrinsic_parameters: [[0.1, 0.2], [0, 0, 0, -0.5, "
                                         "-0.5, 3]]\n")),
            "c.yml: expected every row of extrinsic_parameters to hold 2 numbers (as row 1 does), "
            "found 6 in row 2");
  EXPECT_EQ(calibrationError(calibration("extrinsic_parameters: [[0, 0, 0, 0, 0, 5, 0, 0, 0], [0, "
                                         "0, 0, -0.5, -0.5, 3]]\n")),
            "c.yml: expected every row of extrinsic_parameters to hold 9 numbers (as row 1 does), "
            "found 6 in row 2");
  EXPECT_EQ(calibrationError(calibration("rvecs: [[0.1, 0.2, 0.3, 0.4], [0.5, 0.6]]\n"
                                         "tvecs: [[0, 0, 5], [0, 0, 6]]\n")),
            "c.yml: expected every row of rvecs to hold 4 numbers (as row 1 does), found 2 in row "
            "2");
  EXPECT_EQ(calibrationError("%YAML:1.0\n---\nimage_width: 64\nimage_height: 48\nK: [[70., 0., "
                             "31.5], [0., 72., 23.5, 0.], [0., 1.]]\n",
                             std::nullopt),
            "c.yml: expected every row of the camera matrix to hold 3 numbers (as row 1 does), "
            "found 4 in row 2");
  // An opencv-matrix is allocated by OpenCV as declared before its data are read (a fuzzed
  // file asked for 48 GB): the declaration must match its data and stay small.
  EXPECT_EQ(calibrationError(calibration("D: !!opencv-matrix\n   rows: 100000\n   cols: 100000\n"
                                         "   dt: d\n   data: [ 0.1, 0.2, 0.0, 0.0 ]\n"),
                             std::nullopt),
            "c.yml: expected the distortion coefficients as an opencv-matrix of rows x cols "
            "numbers (at most 6000000), found 100000 x 100000 declared and 4 numbers given");
  EXPECT_NE(calibrationError(calibration("D: !!opencv-matrix\n   rows: x\n   cols: 4\n   dt: d\n"
                                         "   data: [ 0.1, 0.2, 0.0, 0.0 ]\n"),
                             std::nullopt)
                .find("with whole rows and cols and a data sequence"),
            std::string::npos);
  // Fuzzed files on which OpenCV's reader threw std::length_error or crashed: NUL bytes in
  // their text, refused before OpenCV reads them.
  {
    std::ifstream in(std::string(NX_SOURCE_DIR) +
                         "/tests/fuzz/seeds/calibration/finding_length_error.yml",
                     std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), {});
    ASSERT_GT(bytes.size(), 100u);
    const std::string m = calibrationError(bytes.substr(1), std::nullopt);
    EXPECT_EQ(m.rfind("c.yml:", 0), 0u) << m;
    EXPECT_NE(m.find(": expected text (YAML or XML), found a NUL byte"), std::string::npos) << m;
  }
  // A NUL byte made OpenCV's XML reader read past its text (a segmentation fault): refused.
  EXPECT_EQ(calibrationError(std::string("<?xml version=\"1.0\"?>\n<opencv_storage>\n\0<K>", 41),
                             std::nullopt),
            "c.yml:3: expected text (YAML or XML), found a NUL byte (a binary file?)");
  // OpenCV 4.6's reader loops forever on some malformed YAML (a fuzzed file: a line "e---"):
  // it reads in a child process, killed after 5 s, and the file is refused.
  const auto start = std::chrono::steady_clock::now();
  EXPECT_EQ(calibrationError("%YAML:1.0\n---\n [70., 0., 1.]\ne---\n [1.]\n", std::nullopt),
            "c.yml: OpenCV's calibration reader: did not finish within 5 s (the library loops on "
            "some malformed input; check the file)");
  EXPECT_LT(std::chrono::steady_clock::now() - start, std::chrono::seconds(30));
  // Whole tables still read: a sequence of rows and one of 3 x 1 matrices.
  const OpenCvCalibration c = parseOpenCvCalibration(
      calibration("extrinsic_parameters: [[0, 0, 0, 0, 0, 5], [0, 0, 0, -0.5, -0.5, 3]]\n"),
      "c.yml", 1);
  EXPECT_EQ(c.views, 2);
  EXPECT_EQ((*c.extrinsics)[9], -0.5);
  EXPECT_EQ((*c.extrinsics)[11], 3.0);
}

// What the file says is checked like the scene's own elements: its image size is required
// (its camera matrix is in that image's pixels), whole and positive as written; a view beyond
// a single R/T pose, a name given twice or under two aliases, and a distortion <distortion>
// refuses are refused.
TEST(OpenCvCalibration, EverythingTheFileSaysIsChecked) {
  // Tables are rows of numbers: a row holding rows is refused before it is walked (a fuzzed
  // file nested sequences thousands deep: the walk overflowed the stack).
  EXPECT_EQ(calibrationError(calibration("extrinsic_parameters: [[[0, 0, 0, 0, 0, 5]]]\n")),
            "c.yml: expected numbers or rows of numbers in extrinsic_parameters, found a row "
            "holding rows");
  EXPECT_EQ(calibrationError(calibration("", ""), std::nullopt),
            "c.yml: expected the calibrated image's size (image_width and image_height, or "
            "image_size: the camera matrix is in its pixels), found none");
  EXPECT_EQ(calibrationError(calibration("", "image_width: 64\n"), std::nullopt),
            "c.yml: expected image_width and image_height together, found only image_width");
  for (const auto& [written, shown] : std::vector<std::pair<std::string, std::string>>{
           {"abc", "'abc'"}, {"1e20", "1e+20"}, {"8.7", "8.7"}, {"-640", "-640"}, {"0", "0"}})
    EXPECT_EQ(calibrationError(calibration("", "image_width: " + written + "\nimage_height: 48\n"),
                               std::nullopt),
              "c.yml: expected image_width as a whole number of pixels from 1 to 1000000, found " +
                  shown)
        << written;
  EXPECT_EQ(calibrationError(calibration("", "image_size: [64, 48.5]\n"), std::nullopt),
            "c.yml: expected image_size's height as a whole number of pixels from 1 to 1000000, "
            "found 48.5");
  EXPECT_EQ(
      (*parseOpenCvCalibration(calibration("", "image_size: [64, 48]\n"), "c.yml", std::nullopt)
            .imageSize)[1],
      48);
  // One R/T pose: view 0 or none.
  const std::string rt = calibration("R: [0., 0., 0.]\nT: [0., 0., 5.]\n");
  EXPECT_EQ(calibrationError(rt, 5),
            "c.yml: expected view=\"0\" or none (the file holds one pose, R and T), found 5");
  EXPECT_EQ(parseOpenCvCalibration(rt, "c.yml", 0).views, 1);
  EXPECT_EQ(calibrationError(calibration("K: [70., 0., 31.5, 0., 72., 23.5, 0., 0., 1.]\n"),
                             std::nullopt),
            "c.yml: expected each name once, found K twice");
  EXPECT_EQ(calibrationError(calibration("camera_matrix: [70., 0., 31.5, 0., 72., 23.5, 0., 0., "
                                         "1.]\n"),
                             std::nullopt),
            "c.yml: expected one of camera_matrix and K (two names for the same quantity), found "
            "both");
  EXPECT_EQ(calibrationError(calibration("D: [1e5, 0., 0., 0.]\n"), std::nullopt),
            "c.yml: expected distortion coefficients within [-10000, 10000] (as <distortion>), "
            "found 100000 as coefficient 1");
  // A render at another resolution than the file's is refused (it was used at any resolution
  // when the file gave no size).
  const std::string path = written("sized.yml", calibration(""));
  EXPECT_NE(test::errorMessage([&] {
              parseScene(scene("<camera calibration=\"" + path +
                                   "\"><position>0,0,-5</position><look_at>0,0,0</look_at>"
                                   "</camera>",
                               8, 6),
                         "t.scn");
            }).find("expected <xres>, <yres> of the calibration's image (64x48"),
            std::string::npos);
}

} // namespace
} // namespace nx
