#include "io/mesh_file_check.h"

#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <set>
#include <vector>

#include "core/error.h"
#include "core/number_text.h"

namespace nx {
namespace {

// Lines of a text with their 1-based numbers, without the line ends.
class LineReader {
public:
  explicit LineReader(const std::string& text, size_t start = 0) : text_(text), pos_(start) {}
  bool next(std::string& line) {
    if (pos_ >= text_.size()) return false;
    size_t end = text_.find('\n', pos_);
    if (end == std::string::npos) end = text_.size();
    line = text_.substr(pos_, end - pos_);
    if (!line.empty() && line.back() == '\r') line.pop_back();
    pos_ = end + 1;
    ++number_;
    return true;
  }
  int number() const { return number_; }
  size_t position() const { return pos_; }

private:
  const std::string& text_;
  size_t pos_;
  int number_ = 0;
};

std::vector<std::string> words(const std::string& line) {
  std::vector<std::string> out;
  size_t i = 0;
  while (i < line.size()) {
    while (i < line.size() && (line[i] == ' ' || line[i] == '\t')) ++i;
    const size_t b = i;
    while (i < line.size() && line[i] != ' ' && line[i] != '\t') ++i;
    if (i > b) out.push_back(line.substr(b, i - b));
  }
  return out;
}

// True for a number written as the mesh library reads it: an optional '-', digits with an
// optional fraction, an optional exponent ("+3", "0x10", ".5", "3e" are not: the library
// reads them otherwise than strtod, e.g. a face count "+3" became a face it then asserted on).
bool plainDecimal(const std::string& s) {
  size_t i = 0;
  const auto digits = [&] {
    const size_t from = i;
    while (i < s.size() && s[i] >= '0' && s[i] <= '9') ++i;
    return i > from;
  };
  if (i < s.size() && s[i] == '-') ++i;
  if (!digits()) return false; // ".5": the library's OBJ reader misreads it (a leak, fuzzing)
  if (i < s.size() && s[i] == '.') {
    ++i;
    digits();
  }
  if (i < s.size() && (s[i] == 'e' || s[i] == 'E')) {
    ++i;
    if (i < s.size() && (s[i] == '-' || s[i] == '+')) ++i;
    if (!digits()) return false;
  }
  return i == s.size();
}

bool parseDouble(const std::string& s, double& v) {
  if (s.empty() || !plainDecimal(s)) return false;
  const char* end = nullptr;
  v = strtodC(s.c_str(), &end);
  return end == s.c_str() + s.size() && std::isfinite(v);
}

// PLY scalar types and their sizes in bytes.
int plyTypeSize(const std::string& t) {
  if (t == "char" || t == "uchar" || t == "int8" || t == "uint8") return 1;
  if (t == "short" || t == "ushort" || t == "int16" || t == "uint16") return 2;
  if (t == "int" || t == "uint" || t == "int32" || t == "uint32" || t == "float" || t == "float32")
    return 4;
  if (t == "double" || t == "float64") return 8;
  return 0;
}

bool plyIntegerType(const std::string& t) {
  return t != "float" && t != "float32" && t != "double" && t != "float64";
}

struct PlyProperty {
  std::string name, type, countType; // countType non-empty: a list
};
struct PlyElement {
  std::string name;
  uint64_t count = 0;
  std::vector<PlyProperty> properties;
};

uint64_t readUnsigned(const unsigned char* p, int size, bool bigEndian) {
  uint64_t v = 0;
  for (int i = 0; i < size; ++i)
    v |= static_cast<uint64_t>(p[bigEndian ? size - 1 - i : i]) << (8 * i);
  return v;
}

// The two's-complement value of a `size`-byte integer read as unsigned.
int64_t signExtend(uint64_t raw, int size) {
  const int shift = 64 - 8 * size;
  return static_cast<int64_t>(raw << shift) >> shift;
}

} // namespace

MeshFileCounts checkPlyFile(const std::string& bytes, const std::string& path) {
  LineReader lines(bytes);
  std::string line;
  auto fail = [&](const std::string& what) {
    throw Error(path + ":" + std::to_string(lines.number()) + ": " + what);
  };
  if (!lines.next(line) || line != "ply") fail("expected the PLY magic line 'ply'");
  std::string format;
  std::vector<PlyElement> elements;
  bool ended = false;
  while (!ended && lines.next(line)) {
    if (lines.position() > (1u << 20)) fail("expected end_header within the first MB");
    // The header is ASCII text (the format says so); a NUL or other control byte would make
    // the library read a different header than this check (it did: a crash in its
    // triangulation).
    for (const char c : line)
      if (!(c == '\t' || (c >= 0x20 && c <= 0x7e)))
        fail("expected printable ASCII in the PLY header, found the byte " +
             std::to_string(static_cast<unsigned char>(c)));
    const auto w = words(line);
    if (w.empty()) continue;
    if (w[0] == "comment" || w[0] == "obj_info") continue;
    if (w[0] == "format") {
      if (w.size() != 3 ||
          (w[1] != "ascii" && w[1] != "binary_little_endian" && w[1] != "binary_big_endian"))
        fail("expected 'format ascii|binary_little_endian|binary_big_endian 1.0', found '" + line +
             "'");
      format = w[1];
    } else if (w[0] == "element") {
      double n;
      if (w.size() != 3 || !parseDouble(w[2], n) || n < 0 || n != std::floor(n) || n > 4e9)
        fail("expected 'element <name> <count>', found '" + line + "'");
      elements.push_back({w[1], static_cast<uint64_t>(n), {}});
    } else if (w[0] == "property") {
      if (elements.empty()) fail("expected an element before '" + line + "'");
      if (w.size() == 3 && plyTypeSize(w[1]) > 0) {
        elements.back().properties.push_back({w[2], w[1], ""});
      } else if (w.size() == 5 && w[1] == "list" && plyTypeSize(w[2]) > 0 && plyIntegerType(w[2]) &&
                 plyTypeSize(w[3]) > 0) {
        elements.back().properties.push_back({w[4], w[3], w[2]});
      } else {
        fail("expected 'property <type> <name>' or 'property list <count type> <type> <name>', "
             "found '" +
             line + "'");
      }
    } else if (w[0] == "end_header") {
      ended = true;
    } else {
      fail("expected a PLY header line (format, element, property, comment, end_header), found '" +
           line + "'");
    }
  }
  if (!ended) fail("expected end_header, found the end of the file");
  if (format.empty()) fail("expected a format line in the header, found none");
  // What the mesh library reads must be unambiguous: one vertex and one face element, each
  // property named once, positions as scalars and vertex indices as an integer list (a second
  // vertex element, a list-valued x or float indices passed the check and reached the
  // library, which corrupted memory on them).
  const PlyElement* vertex = nullptr;
  const PlyElement* face = nullptr;
  for (const auto& e : elements) {
    if ((e.name == "vertex" && vertex) || (e.name == "face" && face))
      fail("expected one '" + e.name + "' element in the header, found two");
    if (e.name == "vertex") vertex = &e;
    if (e.name == "face") face = &e;
    std::set<std::string> seen;
    for (const auto& p : e.properties)
      if (!seen.insert(p.name).second)
        fail("expected each property of element '" + e.name + "' named once, found '" + p.name +
             "' twice");
  }
  if (!vertex) fail("expected a 'vertex' element in the header, found none");
  std::set<std::string> names;
  for (const auto& p : vertex->properties)
    if (p.countType.empty()) names.insert(p.name);
  if (!names.count("x") || !names.count("y") || !names.count("z"))
    fail("expected vertex properties x, y and z (scalars) in the header");
  if (!face) fail("expected a 'face' element in the header (the mesh has no faces)");
  int faceLists = 0;
  for (const auto& p : face->properties)
    if (p.name == "vertex_indices" || p.name == "vertex_index") {
      if (p.countType.empty() || !plyIntegerType(p.type))
        fail("expected the face property '" + p.name +
             "' as a list of integers (property list <count type> <integer type> " + p.name + ")");
      ++faceLists;
    }
  if (faceLists == 0) fail("expected a face property list vertex_indices (or vertex_index)");
  if (faceLists > 1) fail("expected one face property list of vertex indices, found two");

  if (format == "ascii") {
    for (const auto& e : elements) {
      for (uint64_t item = 0; item < e.count; ++item) {
        do {
          if (!lines.next(line))
            throw Error(path + ": expected " + std::to_string(e.count) + " " + e.name +
                        " lines, found the end of the file after " + std::to_string(item));
        } while (words(line).empty());
        const auto w = words(line);
        size_t k = 0;
        auto value = [&](const std::string& type, const char* what) {
          double v;
          if (k >= w.size())
            fail("expected more numbers on this " + e.name + " line, found " +
                 std::to_string(w.size()));
          if (!parseDouble(w[k], v) ||
              (plyIntegerType(type) &&
               (v != std::floor(v) || w[k].find_first_of(".eE") != std::string::npos)))
            fail(std::string("expected ") + what + ", found '" + w[k] + "'");
          ++k;
          return v;
        };
        for (const auto& p : e.properties) {
          if (p.countType.empty()) {
            value(p.type, "a finite number");
            continue;
          }
          const double n = value(p.countType, "a whole list length");
          const bool indices =
              &e == face && (p.name == "vertex_indices" || p.name == "vertex_index");
          if (n < 0 || (indices && n < 3))
            fail("expected a face of at least 3 vertices, found " + w[k - 1]);
          for (double i = 0; i < n; ++i) {
            const double idx = value(p.type, "a whole number");
            if (indices && (idx < 0 || idx >= static_cast<double>(vertex->count)))
              fail("expected vertex indices within [0, " + std::to_string(vertex->count) +
                   "), found " + w[k - 1]);
          }
        }
        if (k != w.size())
          fail("expected " + std::to_string(k) + " numbers on this " + e.name + " line, found " +
               std::to_string(w.size()));
      }
    }
    while (lines.next(line))
      if (!words(line).empty()) fail("expected the end of the file after the last element");
    return {vertex->count, face->count};
  }

  // Binary: walk the items (list lengths read from the data) and check that they fit.
  const bool big = format == "binary_big_endian";
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
  uint64_t pos = lines.position();
  const uint64_t size = bytes.size();
  for (const auto& e : elements) {
    const auto truncated = [&](uint64_t item) {
      return Error(path + ": expected " + std::to_string(e.count) + " " + e.name +
                   " items in the binary body, found the file ending " +
                   (pos == size ? "before" : "within") + " item " + std::to_string(item) +
                   " (truncated at byte " + std::to_string(size) + ")");
    };
    // The smallest size of an item (lists empty): a body too short for the declared count is
    // refused before walking it, so 4e9 declared items in a few bytes fail at once.
    uint64_t minItem = 0;
    for (const auto& p : e.properties)
      minItem += static_cast<uint64_t>(plyTypeSize(p.countType.empty() ? p.type : p.countType));
    if (minItem > 0 && e.count > (size - std::min(size, pos)) / minItem) throw truncated(0);
    for (uint64_t item = 0; item < e.count; ++item) {
      if (pos >= size) throw truncated(item);
      for (const auto& p : e.properties) {
        if (p.countType.empty()) {
          pos += static_cast<uint64_t>(plyTypeSize(p.type));
          continue;
        }
        const int cs = plyTypeSize(p.countType);
        if (pos + static_cast<uint64_t>(cs) > size) throw truncated(item);
        const uint64_t n = readUnsigned(data + pos, cs, big);
        pos += static_cast<uint64_t>(cs);
        const bool indices = &e == face && (p.name == "vertex_indices" || p.name == "vertex_index");
        if (indices && n < 3)
          throw Error(path + ": expected faces of at least 3 vertices, found face " +
                      std::to_string(item) + " with " + std::to_string(n));
        const int ts = plyTypeSize(p.type);
        if (n > (size - std::min(size, pos)) / static_cast<uint64_t>(ts)) throw truncated(item);
        if (indices && plyIntegerType(p.type))
          for (uint64_t k = 0; k < n; ++k) {
            const uint64_t raw = readUnsigned(data + pos + k * static_cast<uint64_t>(ts), ts, big);
            const bool isSigned = p.type[0] != 'u';
            const int64_t index = isSigned ? signExtend(raw, ts) : static_cast<int64_t>(raw);
            if (index < 0 || static_cast<uint64_t>(index) >= vertex->count)
              throw Error(path + ": expected vertex indices within [0, " +
                          std::to_string(vertex->count) + "), found " + std::to_string(index) +
                          " in face " + std::to_string(item));
          }
        pos += n * static_cast<uint64_t>(ts);
      }
      if (pos > size) throw truncated(item);
    }
  }
  return {vertex->count, face->count};
}

MeshFileCounts checkObjFile(const std::string& bytes, const std::string& path) {
  static const std::set<std::string> kIgnored{
      "g",    "o",      "s",      "usemtl",     "mtllib",    "vp",    "cstype",   "deg",
      "bmat", "step",   "curv",   "curv2",      "surf",      "parm",  "trim",     "hole",
      "scrv", "sp",     "end",    "con",        "mg",        "bevel", "c_interp", "d_interp",
      "lod",  "maplib", "usemap", "shadow_obj", "trace_obj", "ctech", "stech"};
  LineReader lines(bytes);
  std::string line;
  auto fail = [&](const std::string& what) {
    throw Error(path + ":" + std::to_string(lines.number()) + ": " + what);
  };
  int64_t v = 0, vt = 0, vn = 0, faces = 0;
  while (lines.next(line)) {
    const auto w = words(line);
    // Control bytes (a NUL in a group name) make the library read other statements than
    // this check (a leak, found by fuzzing); names may be UTF-8.
    for (const char c : line)
      if (static_cast<unsigned char>(c) < 0x20 && c != '\t')
        fail("expected text without control bytes in an OBJ file, found the byte " +
             std::to_string(static_cast<unsigned char>(c)));
      else if (c == 0x7f)
        fail("expected text without control bytes in an OBJ file, found the byte 127");
    if (w.empty() || w[0][0] == '#') continue;
    // The library skips an indented statement ("  v 1 2 3"): it would read fewer vertices than
    // this check counts (a leak on the faces that then referred past them; fuzzing).
    if (line[0] == ' ' || line[0] == '\t')
      fail("expected the statement '" + w[0] +
           "' at the start of its line (the mesh library skips indented lines), found it "
           "indented");
    auto numbers = [&](size_t lo, size_t hi, const char* what) {
      if (w.size() - 1 < lo || w.size() - 1 > hi)
        fail("expected " + std::to_string(lo) + (lo == hi ? "" : " to " + std::to_string(hi)) +
             " numbers after '" + w[0] + "' (" + what + "), found " + std::to_string(w.size() - 1));
      for (size_t i = 1; i < w.size(); ++i) {
        double x;
        if (!parseDouble(w[i], x)) fail("expected a finite number, found '" + w[i] + "'");
      }
    };
    if (w[0] == "v") {
      // 5 or 7 numbers are neither x y z w nor x y z r g b; the library misreads them.
      if (w.size() != 4 && w.size() != 5 && w.size() != 7)
        fail("expected 3, 4 or 6 numbers after 'v' (x y z, x y z w or x y z r g b), found " +
             std::to_string(w.size() - 1));
      numbers(3, 6, "x y z [w or r g b]");
      ++v;
    } else if (w[0] == "vt") {
      numbers(1, 3, "u [v [w]]");
      ++vt;
    } else if (w[0] == "vn") {
      numbers(3, 3, "x y z");
      ++vn;
    } else if (w[0] == "f" || w[0] == "l" || w[0] == "p") {
      // Faces, and the lines and points the library reads (and drops) with the same references.
      const size_t least = w[0] == "f" ? 3 : w[0] == "l" ? 2 : 1;
      if (w.size() < least + 1)
        fail(std::string("expected ") +
             (w[0] == "f"   ? "a face of at least 3 vertices"
              : w[0] == "l" ? "a line of at least 2 vertices"
                            : "a point of at least 1 vertex") +
             ", found " + std::to_string(w.size() - 1));
      for (size_t i = 1; i < w.size(); ++i) {
        // v, v/t, v//n or v/t/n, each index 1-based or negative (relative).
        const std::string& ref = w[i];
        const int64_t counts[3] = {v, vt, vn};
        size_t start = 0;
        for (int part = 0; part < 3 && start <= ref.size(); ++part) {
          const size_t slash = ref.find('/', start);
          const std::string s =
              ref.substr(start, slash == std::string::npos ? std::string::npos : slash - start);
          if (!s.empty() || part == 0) {
            char* end = nullptr;
            errno = 0;
            const long long idx = std::strtoll(s.c_str(), &end, 10);
            if (s.empty() || end != s.c_str() + s.size() || errno == ERANGE || idx == 0)
              fail("expected a vertex reference (v, v/t, v//n or v/t/n with indices from 1 or "
                   "negative), found '" +
                   ref + "'");
            const int64_t resolved = idx > 0 ? idx : counts[part] + 1 + idx;
            if (resolved < 1 || resolved > counts[part])
              fail("expected references to the " + std::to_string(counts[part]) + " " +
                   (part == 0   ? "vertices"
                    : part == 1 ? "texture coordinates"
                                : "normals") +
                   " read so far, found '" + ref + "'");
          }
          if (slash == std::string::npos) break;
          start = slash + 1;
        }
      }
      if (w[0] == "f") ++faces;
    } else if (!kIgnored.count(w[0])) {
      fail("expected an OBJ statement (v, vt, vn, f, g, o, s, usemtl, mtllib, ...), found '" +
           w[0] + "'");
    }
  }
  if (faces == 0) throw Error(path + ": expected faces ('f' lines), found none");
  return {static_cast<uint64_t>(v), static_cast<uint64_t>(faces)};
}

} // namespace nx
