// <camera calibration="calib.yml" view="N"/>: OpenCV calibration files (cv::FileStorage YAML and
// XML, read by OpenCV itself) set the intrinsics, distortion and pose exactly as the equivalent
// <intrinsics>, <distortion> and <extrinsics> elements; the rotation vector's matrix is checked
// against the properties that define it; bad files and mismatches get clear errors.

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>

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

} // namespace
} // namespace nx
