#pragma once
// Camera calibrations as OpenCV writes them (cv::FileStorage YAML or XML): what
// <camera calibration="calib.yml" view="N"/> reads.

#include <array>
#include <optional>
#include <string>

namespace nx {

/// A calibration's intrinsics, distortion, image size and (when it holds one) pose.
struct OpenCvCalibration {
  std::array<double, 4> intrinsics{};               ///< fx, fy, cx, cy (pixels)
  std::array<double, 5> distortion{};               ///< k1, k2, p1, p2, k3 (0 where absent)
  std::optional<std::array<int, 2>> imageSize;      ///< width, height, if the file gives it
  std::optional<std::array<double, 12>> extrinsics; ///< r11 .. r33, t1, t2, t3 (x_cam = R x + t)
  int views = 0;                                    ///< poses the file holds (rvecs / tvecs)
};

/// Reads a cv::FileStorage text (`bytes` of the file `path`, YAML or XML, found by its first
/// line): the camera matrix (camera_matrix, cameraMatrix or K: 3 x 3), the distortion
/// coefficients (distortion_coefficients, dist_coeffs, distCoeffs or D: 4, 5 or more, the first
/// five kept; beyond them must be 0), the image size (image_width and image_height, or
/// image_size), and the pose: view `view` of rvecs / tvecs (N x 3, or a sequence of 3 x 1) or
/// extrinsic_parameters (N x 6, OpenCV's calibration sample), or R (3 x 3, or a 3 x 1 rotation
/// vector) and T (3 x 1). Throws nx::Error "path: expected ..., found ..." for anything else.
/// Text holding a NUL byte is refused before OpenCV sees it, and OpenCV reads in a helper
/// process killed after `seconds` (OpenCV 4.6 loops forever on some malformed files: an
/// nx::Error says so; the largest file read, 16 MB, takes a fraction of the default 5 s).
OpenCvCalibration parseOpenCvCalibration(const std::string& bytes, const std::string& path,
                                         std::optional<int> view, double seconds = 5);

/// The helper program that reads calibration files for parseOpenCvCalibration
/// (apps/nx_calibration_reader.cpp, io/isolated_call.h).
inline constexpr const char* kCalibrationReaderProgram = "nx-calibration-reader";

/// The helper's work: a request (the view or -1, the path's length and the path, then the
/// file's bytes) read by readOpenCvCalibrationHere, its result as exact text.
std::string calibrationReaderWork(const std::string& request);

/// The same read in this process, without the NUL check or the child (the fuzzer's way to see
/// its coverage, after parseOpenCvCalibration found the input safe): hangs where OpenCV hangs.
OpenCvCalibration readOpenCvCalibrationHere(const std::string& bytes, const std::string& path,
                                            std::optional<int> view);

} // namespace nx
