#include "io/opencv_calibration.h"

#include <opencv2/core.hpp>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <vector>

#include "core/error.h"
#include "core/number_text.h"
#include "io/camera_checks.h"
#include "io/isolated_call.h"

namespace nx {
namespace {

// OpenCV's message without its trailing line break.
std::string messageOf(const cv::Exception& e) {
  std::string m = e.msg;
  while (!m.empty() && (m.back() == '\n' || m.back() == ' ')) m.pop_back();
  return m;
}

// The first of `names` present in the file, or an empty node.
cv::FileNode firstOf(const cv::FileStorage& fs, std::initializer_list<const char*> names) {
  for (const char* n : names) {
    cv::FileNode node = fs[n];
    if (!node.empty()) return node;
  }
  return {};
}

// Most numbers a table of a calibration file may hold (a million views' poses).
constexpr double kMaxCalibrationNumbers = 6e6;

// A node's numbers, row by row: an opencv-matrix, a sequence (of numbers or of sequences), or
// one number; `rows`/`cols` get its shape (a sequence of sequences: its length and the first's).
// `depth`: how deep inside a table the node is; a row's items are numbers (a fuzzed file
// nested sequences thousands deep and overflowed the stack here).
std::vector<double> numbersOf(const cv::FileNode& node, const std::string& what,
                              const std::string& path, int& rows, int& cols, int depth = 0) {
  std::vector<double> out;
  rows = cols = 0;
  if (depth >= 2 && (node.isSeq() || node.isMap()))
    throw Error(path + ": expected numbers or rows of numbers in " + what +
                ", found a row holding rows");
  if (node.isMap()) {
    // OpenCV allocates the rows x cols the file declares before it reads the data (a fuzzed
    // file asked for 48 GB): the declaration must be small, whole and match its data first.
    const cv::FileNode rowsNode = node["rows"], colsNode = node["cols"], data = node["data"];
    if (!rowsNode.isInt() || !colsNode.isInt() || !data.isSeq())
      throw Error(path + ": expected " + what +
                  " as an opencv-matrix with whole rows and cols and a data sequence, found "
                  "another map");
    const int declaredRows = static_cast<int>(rowsNode), declaredCols = static_cast<int>(colsNode);
    const double declared = static_cast<double>(declaredRows) * declaredCols;
    if (!(declaredRows >= 1 && declaredCols >= 1 && declared <= kMaxCalibrationNumbers &&
          declared == static_cast<double>(data.size())))
      throw Error(path + ": expected " + what + " as an opencv-matrix of rows x cols numbers (at " +
                  "most " + numberText(kMaxCalibrationNumbers) + "), found " +
                  std::to_string(declaredRows) + " x " + std::to_string(declaredCols) +
                  " declared and " + std::to_string(data.size()) + " numbers given");
    cv::Mat m;
    node >> m;
    if (m.empty() || m.channels() != 1)
      throw Error(path + ": expected " + what +
                  " as a one-channel opencv-matrix, found another map");
    cv::Mat d;
    m.convertTo(d, CV_64F);
    rows = d.rows, cols = d.cols;
    for (int r = 0; r < d.rows; ++r)
      for (int c = 0; c < d.cols; ++c) out.push_back(d.at<double>(r, c));
  } else if (node.isSeq()) {
    rows = static_cast<int>(node.size());
    int row = 0;
    for (const cv::FileNode& item : node) {
      ++row;
      int length = 1;
      if (item.isSeq() || item.isMap()) {
        int r = 0, c = 0;
        const std::vector<double> inner = numbersOf(item, what, path, r, c, depth + 1);
        length = static_cast<int>(inner.size());
        out.insert(out.end(), inner.begin(), inner.end());
      } else if (item.isReal() || item.isInt()) {
        out.push_back(static_cast<double>(item));
      } else {
        throw Error(path + ": expected numbers in " + what + ", found text");
      }
      // Every row as long as the first: a ragged table was read past its end by the view.
      if (row == 1)
        cols = length;
      else if (length != cols)
        throw Error(path + ": expected every row of " + what + " to hold " + std::to_string(cols) +
                    " numbers (as row 1 does), found " + std::to_string(length) + " in row " +
                    std::to_string(row));
    }
  } else if (node.isReal() || node.isInt()) {
    out.push_back(static_cast<double>(node));
    rows = cols = 1;
  } else {
    throw Error(path + ": expected numbers in " + what + ", found text");
  }
  for (double v : out)
    if (!std::isfinite(v))
      throw Error(path + ": expected finite numbers in " + what + ", found " + numberText(v));
  return out;
}

std::vector<double> numbersOf(const cv::FileNode& node, const std::string& what,
                              const std::string& path) {
  int r = 0, c = 0;
  return numbersOf(node, what, path, r, c);
}

// A size in pixels: a whole number from 1 to 1e6 (a text, 8.7 or 1e20 is no size).
int pixelsOf(const cv::FileNode& node, const std::string& what, const std::string& path) {
  const double v = node.isInt() || node.isReal() ? static_cast<double>(node) : NAN;
  if (!(v >= 1 && v <= 1e6 && v == std::floor(v)))
    throw Error(path + ": expected " + what + " as a whole number of pixels from 1 to 1000000, " +
                "found " +
                (node.isString()    ? "'" + static_cast<std::string>(node) + "'"
                 : std::isfinite(v) ? numberText(v)
                                    : std::string("no number")));
  return static_cast<int>(v);
}

// The file's top-level names, each at most once, and at most one of each group of names for
// the same quantity (a second camera_matrix was ignored).
void requireOneOfEach(const cv::FileStorage& fs, const std::string& path) {
  const std::initializer_list<std::initializer_list<const char*>> aliases = {
      {"camera_matrix", "cameraMatrix", "K", "Camera_Matrix"},
      {"distortion_coefficients", "dist_coeffs", "distCoeffs", "D", "Distortion_Coefficients"},
      {"R", "rotation", "rotation_matrix"},
      {"T", "translation", "translation_vector"}};
  std::vector<std::string> names;
  const cv::FileNode root = fs.root();
  for (auto it = root.begin(); it != root.end(); ++it) {
    const std::string name = (*it).name();
    if (std::find(names.begin(), names.end(), name) != names.end())
      throw Error(path + ": expected each name once, found " + name + " twice");
    names.push_back(name);
  }
  for (const auto& group : aliases) {
    std::string first;
    for (const char* a : group)
      if (std::find(names.begin(), names.end(), a) != names.end()) {
        if (!first.empty())
          throw Error(path + ": expected one of " + first + " and " + a +
                      " (two names for the same quantity), found both");
        first = a;
      }
  }
}

// R from a rotation vector (Rodrigues' formula: R = cos t I + sin t [k]x + (1 - cos t) k k^T,
// t = |r|, k = r / t).
std::array<double, 9> rotationFromVector(const std::vector<double>& r) {
  const double t = std::sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
  if (t == 0) return {1, 0, 0, 0, 1, 0, 0, 0, 1};
  const double x = r[0] / t, y = r[1] / t, z = r[2] / t, c = std::cos(t), s = std::sin(t),
               v = 1 - c;
  return {c + x * x * v,     x * y * v - z * s, x * z * v + y * s, y * x * v + z * s, c + y * y * v,
          y * z * v - x * s, z * x * v - y * s, z * y * v + x * s, c + z * z * v};
}

void setPose(OpenCvCalibration& out, const std::array<double, 9>& R, const std::vector<double>& t) {
  std::array<double, 12> e{};
  for (int i = 0; i < 9; ++i) e[static_cast<size_t>(i)] = R[static_cast<size_t>(i)];
  for (int i = 0; i < 3; ++i) e[static_cast<size_t>(9 + i)] = t[static_cast<size_t>(i)];
  out.extrinsics = e;
}

} // namespace

OpenCvCalibration readOpenCvCalibrationHere(const std::string& bytes, const std::string& path,
                                            std::optional<int> view) {
  cv::FileStorage fs;
  try {
    if (!fs.open(bytes, cv::FileStorage::READ | cv::FileStorage::MEMORY))
      throw Error(path + ": expected an OpenCV FileStorage file (YAML or XML), found data it "
                         "cannot read");
  } catch (const cv::Exception& e) {
    throw Error(path + ": expected an OpenCV FileStorage file (YAML or XML), found an error: " +
                messageOf(e));
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) { // OpenCV's parser lets the standard library's through
    throw Error(path +
                ": expected an OpenCV FileStorage file (YAML or XML), found data its "
                "reader fails on (" +
                e.what() + ")");
  }
  OpenCvCalibration out;
  try {
    requireOneOfEach(fs, path);
    const cv::FileNode k = firstOf(fs, {"camera_matrix", "cameraMatrix", "K", "Camera_Matrix"});
    if (k.empty())
      throw Error(path +
                  ": expected a camera matrix (camera_matrix, cameraMatrix or K), found none");
    int rows = 0, cols = 0;
    const std::vector<double> m = numbersOf(k, "the camera matrix", path, rows, cols);
    if (m.size() != 9 || m[1] != 0 || m[3] != 0 || m[6] != 0 || m[7] != 0 || m[8] != 1)
      throw Error(path + ": expected a 3 x 3 camera matrix [fx 0 cx; 0 fy cy; 0 0 1], found " +
                  std::to_string(m.size()) + " numbers" +
                  (m.size() == 9 ? " with non-zero skew or a last row other than 0 0 1" : ""));
    out.intrinsics = {m[0], m[4], m[2], m[5]};
    const cv::FileNode d = firstOf(fs, {"distortion_coefficients", "dist_coeffs", "distCoeffs", "D",
                                        "Distortion_Coefficients"});
    if (!d.empty()) {
      const std::vector<double> v = numbersOf(d, "the distortion coefficients", path);
      if (v.size() < 4)
        throw Error(path +
                    ": expected 4 or more distortion coefficients (k1, k2, p1, p2[, k3, "
                    "...]), found " +
                    std::to_string(v.size()));
      for (size_t i = 5; i < v.size(); ++i)
        if (v[i] != 0)
          throw Error(path +
                      ": expected at most 5 non-zero distortion coefficients (k1, k2, p1, "
                      "p2, k3: the rational and thin-prism terms are not modelled), found " +
                      numberText(v[i]) + " as coefficient " + std::to_string(i + 1));
      for (size_t i = 0; i < 5 && i < v.size(); ++i) {
        if (!(std::abs(v[i]) <= kMaxDistortionCoefficient))
          throw Error(path + ": expected distortion coefficients within [-" +
                      numberText(kMaxDistortionCoefficient) + ", " +
                      numberText(kMaxDistortionCoefficient) + "] (as <distortion>), found " +
                      numberText(v[i]) + " as coefficient " + std::to_string(i + 1));
        out.distortion[i] = v[i];
      }
    }
    // The image the intrinsics are in pixels of: required, so that a render at another
    // resolution is refused rather than silently wrong.
    const cv::FileNode w = fs["image_width"], h = fs["image_height"], size = fs["image_size"];
    if (!size.empty() && (!w.empty() || !h.empty()))
      throw Error(path + ": expected either image_size or image_width and image_height, found "
                         "both");
    if (!w.empty() || !h.empty()) {
      if (w.empty() || h.empty())
        throw Error(path + ": expected image_width and image_height together, found only " +
                    (w.empty() ? "image_height" : "image_width"));
      out.imageSize =
          std::array<int, 2>{pixelsOf(w, "image_width", path), pixelsOf(h, "image_height", path)};
    } else if (!size.empty()) {
      if (!size.isSeq() || size.size() != 2)
        throw Error(path + ": expected image_size as 2 numbers, width and height");
      out.imageSize = std::array<int, 2>{pixelsOf(size[0], "image_size's width", path),
                                         pixelsOf(size[1], "image_size's height", path)};
    } else {
      throw Error(path + ": expected the calibrated image's size (image_width and image_height, "
                         "or image_size: the camera matrix is in its pixels), found none");
    }
    // The pose: per view (rvecs / tvecs, extrinsic_parameters) or one (R / T).
    const cv::FileNode rv = fs["rvecs"], tv = fs["tvecs"], ep = fs["extrinsic_parameters"];
    if (!rv.empty() || !ep.empty()) {
      std::vector<double> r, t;
      int n = 0;
      if (!ep.empty()) {
        int rows6 = 0, cols6 = 0;
        const std::vector<double> e = numbersOf(ep, "extrinsic_parameters", path, rows6, cols6);
        if (cols6 != 6)
          throw Error(path + ": expected extrinsic_parameters as N x 6 (rvec, tvec per view)");
        n = rows6;
        if (view && *view >= 0 && *view < n) {
          r.assign(e.begin() + *view * 6, e.begin() + *view * 6 + 3);
          t.assign(e.begin() + *view * 6 + 3, e.begin() + *view * 6 + 6);
        }
      } else {
        if (tv.empty()) throw Error(path + ": expected tvecs beside rvecs, found none");
        const std::vector<double> ra = numbersOf(rv, "rvecs", path),
                                  ta = numbersOf(tv, "tvecs", path);
        if (ra.size() % 3 != 0 || ra.size() != ta.size())
          throw Error(path + ": expected as many rvecs as tvecs, 3 numbers each");
        n = static_cast<int>(ra.size() / 3);
        if (view && *view >= 0 && *view < n) {
          r.assign(ra.begin() + *view * 3, ra.begin() + *view * 3 + 3);
          t.assign(ta.begin() + *view * 3, ta.begin() + *view * 3 + 3);
        }
      }
      out.views = n;
      if (!view)
        throw Error(path + ": expected view=\"N\" on <camera> (the file holds " +
                    std::to_string(n) + " views), found none");
      if (*view < 0 || *view >= n)
        throw Error(path + ": expected a view from 0 to " + std::to_string(n - 1) + ", found " +
                    std::to_string(*view));
      setPose(out, rotationFromVector(r), t);
    } else {
      const cv::FileNode R = firstOf(fs, {"R", "rotation", "rotation_matrix"}),
                         T = firstOf(fs, {"T", "translation", "translation_vector"});
      if (!R.empty() || !T.empty()) {
        if (R.empty() || T.empty())
          throw Error(path + ": expected both R and T, found one of them");
        const std::vector<double> r = numbersOf(R, "R", path), t = numbersOf(T, "T", path);
        if (t.size() != 3)
          throw Error(path + ": expected T as 3 numbers, found " + std::to_string(t.size()));
        if (r.size() == 3) {
          setPose(out, rotationFromVector(r), t);
        } else if (r.size() == 9) {
          std::array<double, 9> m9{};
          std::copy(r.begin(), r.end(), m9.begin());
          setPose(out, m9, t);
        } else {
          throw Error(path + ": expected R as 3 x 3 or a rotation vector of 3, found " +
                      std::to_string(r.size()) + " numbers");
        }
      }
      if (view && !out.extrinsics)
        throw Error(path +
                    ": expected poses (rvecs/tvecs, extrinsic_parameters or R/T) for "
                    "view=\"" +
                    std::to_string(*view) + "\", found none");
      if (view && *view != 0)
        throw Error(path +
                    ": expected view=\"0\" or none (the file holds one pose, R and T), "
                    "found " +
                    std::to_string(*view));
      if (out.extrinsics) out.views = 1;
    }
  } catch (const cv::Exception& e) {
    throw Error(path +
                ": expected an OpenCV calibration, found an error reading it: " + messageOf(e));
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    throw Error(path + ": expected an OpenCV calibration, found data its reader fails on (" +
                e.what() + ")");
  }
  return out;
}

namespace {

// The calibration as text the parent reads back exactly (hexadecimal floats).
std::string calibrationText(const OpenCvCalibration& c) {
  std::ostringstream t;
  t << std::hexfloat;
  for (double v : c.intrinsics) t << v << ' ';
  for (double v : c.distortion) t << v << ' ';
  t << (c.imageSize ? 1 : 0) << ' ';
  if (c.imageSize) t << (*c.imageSize)[0] << ' ' << (*c.imageSize)[1] << ' ';
  t << (c.extrinsics ? 1 : 0) << ' ';
  if (c.extrinsics)
    for (double v : *c.extrinsics) t << v << ' ';
  t << c.views;
  return t.str();
}

OpenCvCalibration calibrationFromText(const std::string& text) {
  std::istringstream t(text);
  std::string word;
  auto next = [&] {
    t >> word;
    return strtodC(word.c_str());
  };
  OpenCvCalibration c;
  for (double& v : c.intrinsics) v = next();
  for (double& v : c.distortion) v = next();
  if (next() != 0)
    c.imageSize = std::array<int, 2>{static_cast<int>(next()), static_cast<int>(next())};
  if (next() != 0) {
    std::array<double, 12> e{};
    for (double& v : e) v = next();
    c.extrinsics = e;
  }
  c.views = static_cast<int>(next());
  return c;
}

} // namespace

std::string calibrationReaderWork(const std::string& request) {
  std::istringstream in(request);
  long long v = -1;
  size_t n = 0;
  in >> v >> n;
  in.get();
  if (!in || n > request.size()) throw Error("a malformed request to the calibration reader");
  std::string file(n, '\0');
  in.read(file.data(), static_cast<std::streamsize>(n));
  const std::string text = request.substr(static_cast<size_t>(in.tellg()));
  return calibrationText(readOpenCvCalibrationHere(
      text, file, v < 0 ? std::nullopt : std::optional<int>(static_cast<int>(v))));
}

OpenCvCalibration parseOpenCvCalibration(const std::string& bytes, const std::string& path,
                                         std::optional<int> view, double seconds) {
  // OpenCV's readers take the text as a C string in places: a NUL byte inside made them read
  // past its end (a fuzzed file crashed FileStorage::open). YAML and XML hold none.
  if (const size_t nul = bytes.find('\0'); nul != std::string::npos)
    throw Error(path + ":" +
                std::to_string(
                    1 + std::count(bytes.begin(), bytes.begin() + static_cast<long>(nul), '\n')) +
                ": expected text (YAML or XML), found a NUL byte (a binary file?)");
  // OpenCV 4.6's reader loops forever on some malformed files (a fuzzed YAML with a line
  // "e---"): it reads in a helper process (calibrationReaderWork), killed after `seconds`.
  static IsolatedWorker reader(kCalibrationReaderProgram);
  const std::string request =
      std::to_string(view ? *view : -1) + " " + std::to_string(path.size()) + " " + path + bytes;
  return calibrationFromText(reader.call(request, path + ": OpenCV's calibration reader", seconds));
}

} // namespace nx
