// Scene files (Niixtracer's .scn format and nxrender's extensions) -> SceneDesc.

#include <pugixml.hpp>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "core/error.h"
#include "core/file_text.h"
#include "core/hash.h"
#include "core/kind_lookup.h"
#include "core/math_util.h"
#include "core/memory.h"
#include "core/params/array_values.h"
#include "core/params/material_parameters.h"
#include "core/params/scene_limits.h"
#include "core/text_table.h"
#include "io/camera_checks.h"
#include "io/exr_names.h"
#include "io/opencv_calibration.h"
#include "io/scene_desc.h"
#include "io/scene_kind_schemas.h"
#include "io/scene_state_text.h"
#include "io/scene_tree_text.h"

namespace nx {
namespace {

constexpr double kMaxCoordinate = kMaxSceneCoordinate;
/// The attributes of a Spectrum parameter NAME that are parameters NAME_<attribute>.
constexpr const char* kSpectrumAttributes[] = {"scale", "at"};

std::string shownText(const std::string& s) {
  std::string shown = s.size() > 60 ? s.substr(0, 57) + "..." : s;
  for (char& c : shown)
    if (static_cast<unsigned char>(c) < 32 || static_cast<unsigned char>(c) > 126) c = '?';
  return "'" + shown + "'";
}

std::string trim(const std::string& s) {
  const auto a = s.find_first_not_of(" \t\r\n");
  if (a == std::string::npos) return {};
  return s.substr(a, s.find_last_not_of(" \t\r\n") - a + 1);
}

class SceneParser {
public:
  SceneParser(const std::string& text, std::string file, const SceneKindSchemas& kinds,
              const std::vector<std::string>* linePaths = nullptr)
      : file_(std::move(file)), kinds_(kinds), linePaths_(linePaths) {
    for (size_t i = 0; i < text.size(); ++i)
      if (text[i] == '\n') newlines_.push_back(i);
    if (trim(text).empty())
      failAt(1, "expected an XML document with a <scene> element, found an empty file");
    const pugi::xml_parse_result r = doc_.load_buffer(text.data(), text.size(),
                                                      (pugi::parse_default & ~pugi::parse_escapes) |
                                                          pugi::parse_ws_pcdata_single,
                                                      pugi::encoding_utf8);
    if (r.status == pugi::status_no_document_element)
      failAt(1, "expected an XML document with a <scene> element, found no XML element");
    if (!r)
      failAt(lineOfOffset(static_cast<size_t>(std::max<ptrdiff_t>(r.offset, 0))),
             std::string("expected well-formed XML, found a syntax error (") + r.description() +
                 ")");
  }

  SceneDesc parse() {
    SceneDesc scene;
    scene.file = file_;
    pugi::xml_node root;
    for (pugi::xml_node n : doc_.children()) {
      if (n.type() != pugi::node_element) continue;
      if (root)
        fail(n, "a single root element <scene>", "a second root <" + std::string(n.name()) + ">");
      root = n;
    }
    if (!root) failAt(1, "expected a <scene> element, found no element");
    if (std::string(root.name()) != "scene")
      fail(root, "the root element <scene>", "<" + std::string(root.name()) + ">");
    checkAttributes(root, {});

    bool haveSettings = false, haveCamera = false;
    for (pugi::xml_node n : elements(root)) {
      const std::string tag = n.name();
      if (tag == "settings") {
        if (haveSettings) fail(n, "one <settings>", "a second <settings>");
        haveSettings = true;
        scene.settings = parseSettings(n);
      } else if (tag == "camera") {
        if (haveCamera) {
          scene.warnings.push_back(loc(n).str() +
                                   ": warning: a second <camera> is ignored (the first one wins)");
          continue;
        }
        haveCamera = true;
        scene.camera = parseCamera(n);
      } else if (tag == "light") {
        scene.lights.push_back(parseLight(n));
      } else if (const auto shape = kinds_.shape(tag)) {
        scene.objects.push_back(parseObject(n, *shape));
      } else if (tag == "spectrum") {
        scene.spectra.push_back(parseNamedSpectrum(n));
      } else if (tag == "material") {
        scene.materials.push_back(parseNamedMaterial(n));
      } else {
        std::string shapes;
        for (const std::string& k : kinds_.shapeNames()) shapes += "<" + k + ">, ";
        fail(n, "one of <settings>, <camera>, <light>, " + shapes + "<material>, <spectrum>",
             "<" + tag + ">");
      }
    }
    resolveMaterialReferences(scene);
    if (!haveSettings) fail(root, "a <settings> element", "none");
    if (!haveCamera) fail(root, "a <camera> element", "none");
    if (const auto& size = scene.camera.calibrationSize;
        size && ((*size)[0] != scene.settings.width || (*size)[1] != scene.settings.height))
      throw Error(
          scene.camera.loc.str() + ": expected <xres>, <yres> of the calibration's image (" +
          std::to_string((*size)[0]) + "x" + std::to_string((*size)[1]) + " in " +
          scene.camera.calibrationFile + "; intrinsics are in its pixels), found " +
          std::to_string(scene.settings.width) + "x" + std::to_string(scene.settings.height));
    checkMemory(scene.settings);
    std::set<std::string> names;
    for (const auto& s : scene.spectra)
      if (!names.insert(s.name).second)
        throw Error(s.loc.str() + ": expected a new spectrum name, found '" + s.name +
                    "' defined twice");
    return scene;
  }

private:
  // ---- locations and errors ----
  int lineOfOffset(size_t offset) const {
    return static_cast<int>(std::lower_bound(newlines_.begin(), newlines_.end(), offset) -
                            newlines_.begin()) +
           1;
  }
  // Where line `line` is: file:line, or the data path of the line in a scene given as data.
  SourceLocation locOfLine(int line) const {
    if (linePaths_ && line >= 1 && static_cast<size_t>(line) <= linePaths_->size())
      return {(*linePaths_)[static_cast<size_t>(line) - 1], 0};
    return {file_, line};
  }
  SourceLocation loc(const pugi::xml_node& n) const {
    const ptrdiff_t off = n.offset_debug();
    return locOfLine(off < 0 ? 0 : lineOfOffset(static_cast<size_t>(off)));
  }
  [[noreturn]] void failAt(int line, const std::string& message) const {
    throw Error(locOfLine(line).str() + ": " + message);
  }
  [[noreturn]] void fail(const pugi::xml_node& n, const std::string& expected,
                         const std::string& found) const {
    throw Error(loc(n).str() + ": expected " + expected + ", found " + found);
  }

  // ---- structure ----
  std::vector<pugi::xml_node> elements(const pugi::xml_node& parent) const {
    std::vector<pugi::xml_node> out;
    for (pugi::xml_node c : parent.children()) {
      if (c.type() == pugi::node_element) {
        out.push_back(c);
      } else if ((c.type() == pugi::node_pcdata || c.type() == pugi::node_cdata) &&
                 !trim(c.value()).empty()) {
        const std::string v = c.value();
        const size_t lead = v.find_first_not_of(" \t\r\n");
        failAt(lineOfOffset(static_cast<size_t>(std::max<ptrdiff_t>(c.offset_debug(), 0)) + lead),
               "expected only elements inside <" + std::string(parent.name()) + ">, found text " +
                   shownText(trim(v)));
      }
    }
    return out;
  }

  // Children of an element, each allowed tag at most once.
  std::map<std::string, pugi::xml_node>
  uniqueChildren(const pugi::xml_node& parent, const std::vector<std::string>& allowed) const {
    std::map<std::string, pugi::xml_node> out;
    for (pugi::xml_node c : elements(parent)) {
      const std::string tag = c.name();
      if (std::find(allowed.begin(), allowed.end(), tag) == allowed.end()) {
        std::string list;
        for (const auto& a : allowed) list += (list.empty() ? "<" : ", <") + a + ">";
        fail(c, "one of " + list + " inside <" + std::string(parent.name()) + ">", "<" + tag + ">");
      }
      if (!out.emplace(tag, c).second) fail(c, "one <" + tag + ">", "a second <" + tag + ">");
    }
    return out;
  }

  void checkAttributes(const pugi::xml_node& n, const std::vector<std::string>& allowed) const {
    for (pugi::xml_attribute a : n.attributes())
      if (std::find(allowed.begin(), allowed.end(), a.name()) == allowed.end())
        fail(
            n,
            allowed.empty() ? "no attributes on <" + std::string(n.name()) + ">"
                            : "only the attribute(s) " +
                                  [&] {
                                    std::string l;
                                    for (const auto& s : allowed) l += (l.empty() ? "" : ", ") + s;
                                    return l;
                                  }() +
                                  " on <" + std::string(n.name()) + ">",
            "attribute '" + std::string(a.name()) + "'");
  }

  // Text of a leaf element (no child elements, no attributes unless allowed).
  std::string text(const pugi::xml_node& n, const std::vector<std::string>& attributes = {}) const {
    checkAttributes(n, attributes);
    std::string t;
    for (pugi::xml_node c : n.children()) {
      if (c.type() == pugi::node_element)
        fail(c, "text inside <" + std::string(n.name()) + ">",
             "element <" + std::string(c.name()) + ">");
      if (c.type() == pugi::node_pcdata) t += decoded(c.value(), n);
      if (c.type() == pugi::node_cdata) t += c.value();
    }
    return trim(t);
  }

  // Character references resolved here rather than by pugixml, which keeps an undefined entity
  // such as "&foo;" as literal text: the five predefined entities and &#...; / &#x...; are
  // known, anything else after '&' is an error at the element.
  std::string decoded(const char* raw, const pugi::xml_node& where) const {
    std::string out;
    for (const char* p = raw; *p;) {
      if (*p != '&') {
        out += *p++;
        continue;
      }
      const char* semi = std::strchr(p, ';');
      const std::string ref = semi ? std::string(p + 1, semi) : std::string(p + 1);
      static const std::map<std::string, char> predefined{
          {"amp", '&'}, {"lt", '<'}, {"gt", '>'}, {"quot", '"'}, {"apos", '\''}};
      if (!semi)
        fail(where, "'&' only in an entity such as &amp;", shownText(std::string(p).substr(0, 12)));
      if (const auto it = predefined.find(ref); it != predefined.end()) {
        out += it->second;
      } else if (ref.size() > 1 && ref[0] == '#') {
        const bool hex = ref[1] == 'x' || ref[1] == 'X';
        const std::string digits = ref.substr(hex ? 2 : 1);
        char* end = nullptr;
        const unsigned long code = std::strtoul(digits.c_str(), &end, hex ? 16 : 10);
        if (digits.empty() || *end != '\0' || code == 0 || code > 0x10FFFF)
          fail(where, "a character reference &#N; or &#xN;", shownText("&" + ref + ";"));
        appendUtf8(out, static_cast<uint32_t>(code));
      } else {
        fail(where, "only the entities &amp; &lt; &gt; &quot; &apos; and character references",
             "the undefined entity " + shownText("&" + ref + ";"));
      }
      p = semi + 1;
    }
    return out;
  }

  static void appendUtf8(std::string& out, uint32_t c) {
    if (c < 0x80) {
      out += static_cast<char>(c);
    } else if (c < 0x800) {
      out += static_cast<char>(0xC0 | (c >> 6));
      out += static_cast<char>(0x80 | (c & 0x3F));
    } else if (c < 0x10000) {
      out += static_cast<char>(0xE0 | (c >> 12));
      out += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (c & 0x3F));
    } else {
      out += static_cast<char>(0xF0 | (c >> 18));
      out += static_cast<char>(0x80 | ((c >> 12) & 0x3F));
      out += static_cast<char>(0x80 | ((c >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (c & 0x3F));
    }
  }

  std::vector<std::string> tokens(const std::string& t) const {
    std::vector<std::string> out;
    std::string cur;
    for (char c : t) {
      if (c == ',' || c == ' ' || c == '\t' || c == '\n' || c == '\r') {
        if (!cur.empty()) out.push_back(cur);
        cur.clear();
      } else {
        cur += c;
      }
    }
    if (!cur.empty()) out.push_back(cur);
    return out;
  }

  double numberOf(const pugi::xml_node& n, const std::string& token,
                  const std::string& what) const {
    const std::string where = loc(n).str();
    return parseNumber(token, where, what + " in <" + std::string(n.name()) + ">");
  }

  double number(const pugi::xml_node& n, const std::string& what, double lo, double hi,
                bool openLow = false) const {
    const std::string t = text(n);
    const auto tk = tokens(t);
    if (tk.size() != 1)
      fail(n, "one number (" + what + ") in <" + std::string(n.name()) + ">",
           tk.empty() ? "nothing" : shownText(t));
    const double v = numberOf(n, tk[0], what);
    if (v < lo || v > hi || (openLow && v == lo)) {
      std::ostringstream range;
      range << what << " in " << (openLow ? "(" : "[") << lo << ", " << hi << "]";
      fail(n, range.str(), shownText(t));
    }
    return v;
  }

  double number(const pugi::xml_node& n, const ParameterRange& r) const {
    return number(n, r.what, r.lo, r.hi, r.openLow);
  }

  int integer(const pugi::xml_node& n, const std::string& what, long lo, long hi) const {
    const std::string t = text(n);
    const auto tk = tokens(t);
    if (tk.size() != 1)
      fail(n, "one whole number (" + what + ") in <" + std::string(n.name()) + ">",
           tk.empty() ? "nothing" : shownText(t));
    const std::string& s = tk[0];
    bool digits = !s.empty();
    for (size_t i = 0; i < s.size(); ++i)
      digits = digits && (std::isdigit(static_cast<unsigned char>(s[i])) ||
                          (i == 0 && (s[i] == '-' || s[i] == '+')));
    if (!digits)
      fail(n, "a whole number (" + what + ") in <" + std::string(n.name()) + ">", shownText(t));
    errno = 0;
    const long long v = std::strtoll(s.c_str(), nullptr, 10);
    if (errno == ERANGE || v < lo || v > hi)
      fail(n, what + " in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]", shownText(t));
    return static_cast<int>(v);
  }

  std::vector<double> numbers(const pugi::xml_node& n, size_t minCount, size_t maxCount,
                              const std::string& what) const {
    const std::string t = text(n);
    const auto tk = tokens(t);
    if (tk.size() < minCount || tk.size() > maxCount) {
      const std::string count = minCount == maxCount
                                    ? std::to_string(minCount)
                                    : std::to_string(minCount) + " to " + std::to_string(maxCount);
      fail(n, count + " numbers (" + what + ") in <" + std::string(n.name()) + ">",
           std::to_string(tk.size()) + (tk.empty() ? "" : " (" + shownText(t) + ")"));
    }
    std::vector<double> v;
    for (const auto& s : tk) v.push_back(numberOf(n, s, what));
    return v;
  }

  Vec3d vec3(const pugi::xml_node& n, const std::string& what) const {
    const auto v = numbers(n, 3, 3, what);
    for (double x : v)
      if (std::abs(x) > kMaxCoordinate)
        fail(n, what + " with coordinates within +/-1e12", shownText(text(n)));
    return {v[0], v[1], v[2]};
  }

  pugi::xml_node required(const std::map<std::string, pugi::xml_node>& children,
                          const pugi::xml_node& parent, const std::string& tag) const {
    const auto it = children.find(tag);
    if (it == children.end())
      fail(parent, "<" + tag + "> inside <" + std::string(parent.name()) + ">", "none");
    return it->second;
  }

  // ---- spectra ----
  // A spectrum written as text: a number, "nm:value" pairs, or a name; or csv="file".
  // A <reflectance>: a spectrum, or texture="colorchecker" / "image.exr" / "image.png".
  std::optional<SpectrumDesc> reflectance(const pugi::xml_node& n) const {
    const pugi::xml_attribute tex = n.attribute("texture");
    if (!tex) return spectrum(n, false);
    const std::string t = text(n, {"texture", "extrapolate"});
    if (!t.empty()) fail(n, "either texture=\"...\" or text in <reflectance>", "both");
    SpectrumDesc s;
    s.loc = loc(n);
    s.kind = SpectrumDesc::Kind::Texture;
    s.extrapolate = extrapolation(n);
    const std::string name = trim(decoded(tex.value(), n));
    if (name.empty())
      fail(n, "texture=\"colorchecker\", a spectral EXR or a PNG/JPEG file in texture=\"...\"",
           "an empty one");
    s.texture = name == "colorchecker" ? name : relativeToScene(name);
    return s;
  }

  // A table's extrapolate="zero|hold" (Unset when absent).
  SpectrumDesc::Extrapolation extrapolation(const pugi::xml_node& n) const {
    const pugi::xml_attribute e = n.attribute("extrapolate");
    if (!e) return SpectrumDesc::Extrapolation::Unset;
    const std::string mode = trim(decoded(e.value(), n));
    if (mode == "zero") return SpectrumDesc::Extrapolation::Zero;
    if (mode != "hold") fail(n, "extrapolate=\"zero\" or extrapolate=\"hold\"", shownText(mode));
    return SpectrumDesc::Extrapolation::Hold;
  }

  std::optional<SpectrumDesc> spectrum(const pugi::xml_node& n, bool emptyMeansNone,
                                       const std::vector<std::string>& extraAttributes = {}) const {
    std::vector<std::string> attrs = extraAttributes;
    attrs.push_back("csv");
    attrs.push_back("column");
    attrs.push_back("extrapolate");
    attrs.push_back("negative");
    const std::string t = text(n, attrs);
    SpectrumDesc s;
    s.loc = loc(n);
    s.extrapolate = extrapolation(n);
    if (const pugi::xml_attribute neg = n.attribute("negative")) {
      const std::string mode = trim(decoded(neg.value(), n));
      if (mode != "clamp") fail(n, "negative=\"clamp\"", shownText(mode));
      s.clampNegative = true;
    }
    if (n.attribute("column") && !n.attribute("csv"))
      fail(n, "column=\"...\" only with csv=\"file\"", "column alone");
    if (pugi::xml_attribute csv = n.attribute("csv")) {
      if (!t.empty())
        fail(n, "either csv=\"file\" or text in <" + std::string(n.name()) + ">", "both");
      const std::string csvName = decoded(csv.value(), n);
      if (trim(csvName).empty()) fail(n, "a file name in csv=\"...\"", "an empty one");
      s.kind = SpectrumDesc::Kind::CsvFile;
      s.path = relativeToScene(csvName);
      if (pugi::xml_attribute column = n.attribute("column")) {
        s.column = trim(decoded(column.value(), n));
        if (s.column.empty()) fail(n, "a column name in column=\"...\"", "an empty one");
      }
      return s;
    }
    if (t.empty()) {
      if (emptyMeansNone) return std::nullopt;
      fail(n,
           "a spectrum (a name, a number, nm:value pairs or csv=\"file\") in <" +
               std::string(n.name()) + ">",
           "nothing");
    }
    const char first = t[0];
    const bool numeric = std::isdigit(static_cast<unsigned char>(first)) || first == '.' ||
                         first == '-' || first == '+';
    if (numeric && t.find(':') != std::string::npos) {
      s.kind = SpectrumDesc::Kind::Pairs;
      for (const auto& tok : tokens(t)) {
        const auto colon = tok.find(':');
        if (colon == std::string::npos || tok.find(':', colon + 1) != std::string::npos)
          fail(n, "nm:value pairs such as 400:0.2, 500:0.7", shownText(tok));
        s.nm.push_back(numberOf(n, tok.substr(0, colon), "a wavelength in nm"));
        s.value.push_back(numberOf(n, tok.substr(colon + 1), "a spectrum value"));
      }
      if (s.nm.size() < 2) fail(n, "at least two nm:value pairs", shownText(t));
      for (size_t i = 1; i < s.nm.size(); ++i)
        if (!(s.nm[i] > s.nm[i - 1]))
          fail(n, "increasing wavelengths in nm:value pairs", shownText(t));
      return s;
    }
    if (numeric) {
      s.kind = SpectrumDesc::Kind::Number;
      const auto tk = tokens(t);
      if (tk.size() != 1)
        fail(n, "one number, a name or nm:value pairs in <" + std::string(n.name()) + ">",
             shownText(t));
      s.number = numberOf(n, tk[0], "a spectrum value");
      if (s.number < 0)
        fail(n, "a non-negative value in <" + std::string(n.name()) + ">", shownText(t));
      if (s.number == 0 && emptyMeansNone) return std::nullopt;
      return s;
    }
    if (tokens(t).size() != 1)
      fail(n, "one spectrum name in <" + std::string(n.name()) + ">", shownText(t));
    s.kind = SpectrumDesc::Kind::Name;
    s.name = t;
    return s;
  }

  std::string relativeToScene(const std::string& p) const {
    const std::filesystem::path path(trim(p));
    if (path.is_absolute()) return path.string();
    return (std::filesystem::path(file_).parent_path() / path).lexically_normal().string();
  }

  NamedSpectrumDesc parseNamedSpectrum(const pugi::xml_node& n) const {
    NamedSpectrumDesc d;
    d.loc = loc(n);
    const std::string name = trim(decoded(n.attribute("name").value(), n));
    if (name.empty()) fail(n, "a name=\"...\" attribute on <spectrum>", "none");
    if (name.find_first_of(" \t,:") != std::string::npos ||
        std::isdigit(static_cast<unsigned char>(name[0])))
      fail(n, "a spectrum name without spaces, commas or colons, not starting with a digit",
           shownText(name));
    d.name = name;
    d.spectrum = *spectrum(n, false, {"name"});
    return d;
  }

  // <sensor csv="file"/>, <sensor gaussian="CENTRES" fwhm="FWHM"/> or <sensor boxes="LO-HI,..."/>.
  Sensor sensor(const pugi::xml_node& n) const {
    checkAttributes(n, {"csv", "gaussian", "fwhm", "boxes", "centres"});
    if (n.attribute("centres") && !n.attribute("csv"))
      fail(n, "centres=\"...\" (nominal band centres) only with csv=\"file\"", "centres alone");
    if (n.first_child()) fail(n, "an empty <sensor .../> with attributes", "content");
    const bool csv = n.attribute("csv"), gaussian = n.attribute("gaussian"),
               boxes = n.attribute("boxes");
    if (csv + gaussian + boxes != 1)
      fail(n,
           "exactly one of csv=\"file\", gaussian=\"centres\" fwhm=\"...\" or boxes=\"LO-HI,...\"",
           csv + gaussian + boxes == 0 ? std::string("none") : std::string("several"));
    if (n.attribute("fwhm") && !gaussian)
      fail(n, "fwhm=\"...\" only with gaussian=\"...\"", "fwhm alone");
    const std::string where = loc(n).str() + ": <sensor>";
    try {
      if (csv) {
        const std::string name = trim(decoded(n.attribute("csv").value(), n));
        if (name.empty()) fail(n, "a file name in csv=\"...\"", "an empty one");
        const Sensor measured = Sensor::readCsv(relativeToScene(name));
        if (const pugi::xml_attribute centres = n.attribute("centres"))
          return measured.withNominalCentres(decoded(centres.value(), n), where + " centres");
        return measured;
      }
      if (boxes) return Sensor::parse("boxes:" + decoded(n.attribute("boxes").value(), n), where);
      if (!n.attribute("fwhm")) fail(n, "a fwhm=\"...\" attribute with gaussian=\"...\"", "none");
      return Sensor::parse("gaussian:" + decoded(n.attribute("gaussian").value(), n) + "@" +
                               decoded(n.attribute("fwhm").value(), n),
                           where);
    } catch (const Error& e) {
      const std::string m = e.what();
      if (m.rfind(loc(n).str(), 0) == 0) throw;
      throw Error(loc(n).str() + ": " + m);
    }
  }

  // ---- elements ----
  SettingsDesc parseSettings(const pugi::xml_node& n) const {
    checkAttributes(n, {});
    const auto c = uniqueChildren(n, {"xres", "yres", "path", "mode", "depth", "sampl", "samp1",
                                      "illum", "bands", "sensor", "background", "seed"});
    SettingsDesc s;
    s.loc = loc(n);
    const pugi::xml_node xres = required(c, n, "xres");
    s.widthLoc = loc(xres);
    s.width = integer(xres, "a width in pixels", 1, kMaxResolution);
    s.height = integer(required(c, n, "yres"), "a height in pixels", 1, kMaxResolution);
    const pugi::xml_node mode = required(c, n, "mode");
    s.modeLoc = loc(mode);
    const std::string m = text(mode);
    const std::optional<RenderMode> parsed = parseRenderMode(m);
    if (!parsed) fail(mode, "a mode rt, mcpt or spectral_mcpt", shownText(m));
    s.mode = *parsed;
    if (c.count("path")) {
      s.outputPath = text(c.at("path"));
      if (s.outputPath.empty()) fail(c.at("path"), "an output file name in <path>", "nothing");
    }
    if (c.count("depth")) s.depth = integer(c.at("depth"), "a bounce count", 0, 100000);
    if (c.count("sampl") && c.count("samp1"))
      fail(c.at("samp1"), "one of <sampl> and <samp1>", "both");
    for (const char* tag : {"sampl", "samp1"})
      if (c.count(tag)) s.samples = integer(c.at(tag), "a sample count per pixel", 1, 1 << 30);
    if (c.count("illum")) s.illuminant = spectrum(c.at("illum"), false);
    if (c.count("background")) {
      s.background = spectrum(c.at("background"), true, {"group"});
      s.backgroundGroup = groupAttribute(c.at("background"));
    }
    if (c.count("bands")) {
      try {
        s.bands = Sensor(SpectralBands::parse(text(c.at("bands"))));
      } catch (const Error& e) {
        throw Error(loc(c.at("bands")).str() + ": " + e.what());
      }
    }
    if (c.count("sensor")) {
      const pugi::xml_node sn = c.at("sensor");
      if (c.count("bands")) fail(sn, "one of <bands> and <sensor>", "both");
      s.bands = sensor(sn);
      if (sn.attribute("csv")) {
        s.sensorFile = relativeToScene(trim(decoded(sn.attribute("csv").value(), sn)));
        s.sensorCentres = trim(decoded(sn.attribute("centres").value(), sn));
      }
    }
    if (c.count("seed"))
      s.seed = static_cast<uint32_t>(integer(c.at("seed"), "a seed", 0, 2147483647));
    return s;
  }

  CameraDesc parseCamera(const pugi::xml_node& n) const {
    checkAttributes(n, {"calibration", "view"});
    const auto c = uniqueChildren(n, {"position", "look_at", "up", "fov", "intrinsics",
                                      "extrinsics", "distortion", "thin_lens"});
    CameraDesc cam;
    cam.loc = loc(n);
    // calibration="calib.yml" view="N": intrinsics, distortion and (if the file has poses) the
    // pose from an OpenCV calibration file; the elements it replaces are then refused.
    std::optional<OpenCvCalibration> calib;
    if (n.attribute("view") && !n.attribute("calibration"))
      fail(n, "view=\"N\" only with calibration=\"file\" on <camera>", "view alone");
    if (const pugi::xml_attribute ca = n.attribute("calibration")) {
      const std::string f = trim(decoded(ca.value(), n));
      if (f.empty()) fail(n, "a file name in calibration=\"...\"", "an empty one");
      cam.calibrationFile = relativeToScene(f);
      std::optional<int> view;
      if (const pugi::xml_attribute va = n.attribute("view")) {
        const std::string vt = trim(decoded(va.value(), n));
        if (vt.empty() || vt.find_first_not_of("0123456789") != std::string::npos || vt.size() > 9)
          fail(n, "a view index 0, 1, ... in view=\"...\"", shownText(vt));
        view = std::stoi(vt);
      }
      try {
        const std::string bytes =
            readRegularFile(cam.calibrationFile, 16u << 20, "calibration file");
        calib = parseOpenCvCalibration(bytes, cam.calibrationFile, view);
        cam.calibrationDigest = fnv1a64(bytes);
      } catch (const Error& e) {
        throw Error(loc(n).str() + ": " + e.what());
      }
      for (const char* tag : {"intrinsics", "distortion", "fov"})
        if (c.count(tag))
          fail(c.at(tag), "either calibration=\"...\" or <" + std::string(tag) + "> on <camera>",
               "both");
      if (calib->extrinsics)
        for (const char* tag : {"position", "look_at", "up", "extrinsics"})
          if (c.count(tag))
            fail(c.at(tag),
                 "no <" + std::string(tag) + "> with a calibration file that gives the pose",
                 "<" + std::string(tag) + ">");
      cam.intrinsics = calib->intrinsics;
      cam.distortion = calib->distortion;
      cam.distortionLoc = cam.loc;
      cam.calibrationSize = calib->imageSize;
      if (calib->extrinsics) {
        if (const std::string problem = extrinsicsProblem(*calib->extrinsics); !problem.empty())
          throw Error(loc(n).str() + ": " + cam.calibrationFile + ": expected " + problem);
        cam.extrinsics = calib->extrinsics;
      }
    }
    if (cam.extrinsics) {
    } else if (c.count("extrinsics")) {
      for (const char* tag : {"position", "look_at", "up"})
        if (c.count(tag))
          fail(c.at(tag), "either <extrinsics> or <position>/<look_at>/<up> in <camera>",
               "both (<" + std::string(tag) + "> and <extrinsics>)");
      cam.extrinsics = extrinsics(c.at("extrinsics"));
    } else {
      cam.position = vec3(required(c, n, "position"), "a camera position x, y, z");
      cam.lookAt = vec3(required(c, n, "look_at"), "a point to look at x, y, z");
      if (length(cam.lookAt - cam.position) == 0)
        fail(c.at("look_at"), "a look_at point different from the camera position",
             shownText(text(c.at("look_at"))));
      if (c.count("up")) {
        cam.up = vec3(c.at("up"), "an up direction x, y, z");
        if (length(cam.up) == 0)
          fail(c.at("up"), "a non-zero up direction", shownText(text(c.at("up"))));
      }
    }
    if (c.count("intrinsics") && c.count("fov"))
      fail(c.at("fov"), "either <intrinsics> or <fov> in <camera>", "both");
    if (c.count("fov")) cam.fovDegrees = number(c.at("fov"), kFovRange);
    if (c.count("intrinsics")) {
      const pugi::xml_node k = c.at("intrinsics");
      const auto v = numbers(k, 4, 4, "fx, fy, cx, cy in pixels");
      if (!(v[0] > 0 && v[1] > 0))
        fail(k, "focal lengths fx, fy > 0 in <intrinsics>", shownText(text(k)));
      if (std::abs(v[2]) > 1e7 || std::abs(v[3]) > 1e7 || v[0] > 1e9 || v[1] > 1e9)
        fail(k, "fx, fy and the principal point cx, cy within 1e9 and 1e7 pixels",
             shownText(text(k)));
      cam.intrinsics = std::array<double, 4>{v[0], v[1], v[2], v[3]};
    }
    if (c.count("distortion")) {
      const pugi::xml_node d = c.at("distortion");
      const auto v = numbers(d, 4, 5, "k1, k2, p1, p2[, k3]");
      for (size_t i = 0; i < v.size(); ++i) {
        if (std::abs(v[i]) > kMaxDistortionCoefficient)
          fail(d,
               "distortion coefficients within [-" + numberText(kMaxDistortionCoefficient) + ", " +
                   numberText(kMaxDistortionCoefficient) + "]",
               shownText(text(d)));
        cam.distortion[i] = v[i];
      }
      cam.distortionLoc = loc(d);
    }
    if (c.count("thin_lens")) {
      const pugi::xml_node l = c.at("thin_lens");
      const auto v = numbers(l, 2, 2, "an aperture radius and a focus distance");
      if (!(v[0] >= 0 && v[0] <= kMaxCoordinate && v[1] > 0 && v[1] <= kMaxCoordinate))
        fail(l, "an aperture radius >= 0 and a focus distance > 0 (scene units) in <thin_lens>",
             shownText(text(l)));
      cam.thinLens = std::array<double, 2>{v[0], v[1]};
    }
    return cam;
  }

  // R (row by row) and t of x_cam = R x_world + t; R must be a rotation up to the rounding of
  // printed calibration output (R^T R within 1e-4 of the identity, determinant +1).
  std::array<double, 12> extrinsics(const pugi::xml_node& e) const {
    const auto v = numbers(e, 12, 12, "r11, r12, r13, r21, r22, r23, r31, r32, r33, t1, t2, t3");
    std::array<double, 12> out{};
    std::copy(v.begin(), v.end(), out.begin());
    if (const std::string problem = extrinsicsProblem(out); !problem.empty())
      throw Error(loc(e).str() + ": expected " + problem);
    return out;
  }

  // A light group's name from group="NAME" on an emitter: letters, digits, '_' and '-' (it
  // becomes part of EXR channel names, light.NAME.S0.<band>nm); empty when absent.
  std::string groupAttribute(const pugi::xml_node& n) const {
    const pugi::xml_attribute a = n.attribute("group");
    if (!a) return {};
    const std::string g = trim(decoded(a.value(), n));
    const bool valid = !g.empty() && std::all_of(g.begin(), g.end(), [](char ch) {
      return std::isalnum(static_cast<unsigned char>(ch)) || ch == '_' || ch == '-';
    });
    if (!valid)
      fail(n,
           "a light group name of letters, digits, '_' and '-' in group=\"...\" on <" +
               std::string(n.name()) + ">",
           g.empty() ? "an empty one" : shownText(g));
    // Its channels' and attributes' names must fit OpenEXR's (longer ones are cut, and two
    // groups then share one channel).
    if (longestExrNameOfLightGroup(g) > kMaxExrNameBytes)
      fail(n,
           "a light group name of at most " + std::to_string(longestLightGroupName()) +
               " bytes in group=\"...\" (its EXR channel names, up to " +
               std::to_string(longestExrNameOfLightGroup(g) - g.size()) +
               " bytes longer, must fit OpenEXR's " + std::to_string(kMaxExrNameBytes) + ")",
           "one of " + std::to_string(g.size()) + " bytes");
    return g;
  }

  // <light type="kind"> (point when absent) with the kind's parameters as children.
  LightDesc parseLight(const pugi::xml_node& n) const {
    checkAttributes(n, {"type", "group"});
    LightDesc l;
    l.loc = loc(n);
    l.group = groupAttribute(n);
    if (n.attribute("type")) l.kind = trim(decoded(n.attribute("type").value(), n));
    const auto kind = kinds_.light(l.kind);
    if (!kind) fail(n, "a light type " + kinds_.lightList(), shownText(l.kind));
    parseTakenParameters(n, kind->params, l.params);
    return l;
  }

  // A light's or medium's parameters, the children of `n`, each read by its declared type; a
  // Spectrum parameter NAME's attributes scale="..." and at="..." are the parameters
  // NAME_scale and NAME_at where the kind takes them (kSpectrumAttributes); an empty optional
  // spectrum is no parameter ("absent, 0 or empty").
  void parseTakenParameters(const pugi::xml_node& n, std::span<const TakenParameter> params,
                            ParameterSet& out) const {
    // NAME_<attribute> is an attribute of NAME's element when NAME is a Spectrum parameter
    // (look_at is not one of an element "look").
    auto isAttribute = [&](const std::string& name) {
      for (const char* a : kSpectrumAttributes) {
        const std::string suffix = std::string("_") + a;
        if (!name.ends_with(suffix)) continue;
        const TakenParameter* base =
            findParameterNamed(params, name.substr(0, name.size() - suffix.size()));
        if (base && base->spec.type == ParamType::Spectrum) return true;
      }
      return false;
    };
    std::vector<std::string> names;
    for (const TakenParameter& p : params)
      if (!isAttribute(p.spec.name)) names.push_back(p.spec.name);
    const auto c = uniqueChildren(n, names);
    for (const TakenParameter& p : params) {
      const auto it = c.find(p.spec.name);
      if (it == c.end()) {
        if (p.required) required(c, n, p.spec.name);
        continue;
      }
      const pugi::xml_node e = it->second;
      if (p.spec.type == ParamType::Spectrum) {
        std::vector<std::string> attributes;
        for (const char* a : kSpectrumAttributes)
          if (findParameterNamed(params, std::string(p.spec.name) + "_" + a))
            attributes.push_back(a);
        std::optional<SpectrumDesc> s = spectrum(e, !p.required, attributes);
        for (const std::string& a : attributes) {
          if (!e.attribute(a.c_str())) continue;
          const TakenParameter& d = *findParameterNamed(params, std::string(p.spec.name) + "_" + a);
          const std::string noun = d.spec.what;
          const std::string article =
              std::string("aeiou").find(noun[0]) == std::string::npos ? "a" : "an";
          const double v = a == "scale" ? scaleAttribute(e, article, noun,
                                                         d.spec.range && !d.spec.range->openLow)
                                        : numberAttribute(e, a.c_str(), *d.spec.range);
          out.set({d.spec.name, v, loc(e)});
        }
        if (s) out.set({p.spec.name, *s, loc(e)});
        continue;
      }
      out.set({p.spec.name, parameterValue(p.spec, e), loc(e)});
    }
  }

  // The optional scale="..." of an element (an <emission>, a medium's coefficient): a positive
  // finite number (or zero where allowed: an emission switched off), 1 if absent; errors name
  // it "<article> <noun>" ("an", "emission scale").
  double scaleAttribute(const pugi::xml_node& e, const std::string& article,
                        const std::string& noun, bool zeroAllowed) const {
    const pugi::xml_attribute sc = e.attribute("scale");
    if (!sc) return 1.0;
    const std::string text = decoded(sc.value(), e);
    const double v = parseNumber(text, loc(e).str(), article + " " + noun + " in scale=\"...\"");
    if (!(zeroAllowed ? v >= 0 : v > 0) || !std::isfinite(v))
      fail(e, (zeroAllowed ? "a non-negative " : "a positive ") + noun, shownText(text));
    return v;
  }

  std::array<double, 4> colour(const pugi::xml_node& n, bool reflectance) const {
    const auto v = numbers(n, 3, 4, "R, G, B[, A]");
    std::array<double, 4> rgba{v[0], v[1], v[2], v.size() == 4 ? v[3] : 1.0};
    for (int i = 0; i < 3; ++i) {
      if (rgba[i] < 0) fail(n, "non-negative colour channels", shownText(text(n)));
      if (reflectance && rgba[i] > 1)
        fail(n, "reflectance colour channels in [0, 1]", shownText(text(n)));
    }
    return rgba;
  }

  // The material parameters among an element's children (an object's, or a <material id>'s),
  // each read by its declared type (core/params/material_parameters.h).
  void parseMaterialParameters(const std::map<std::string, pugi::xml_node>& c,
                               MaterialDesc& m) const {
    for (const ParamSpec& spec : materialParameters()) {
      const auto it = c.find(spec.name);
      if (it == c.end()) continue;
      m.params.set({spec.name, parameterValue(spec, it->second), loc(it->second)});
    }
  }

  // One parameter's value from its element, by type.
  ParamValue parameterValue(const ParamSpec& spec, const pugi::xml_node& n) const {
    switch (spec.type) {
    case ParamType::Number:
      return number(n, *spec.range);
    case ParamType::Rgb:
      return colour(n, spec.range != nullptr);
    case ParamType::Point:
      return vec3(n, *spec.what ? spec.what : "x, y, z");
    case ParamType::Transform:
      return transform(n);
    case ParamType::File: {
      const std::string t = text(n);
      if (t.empty()) fail(n, "a file name in <" + std::string(n.name()) + ">", "nothing");
      return relativeToScene(t);
    }
    case ParamType::Spectrum:
      return *spectrum(n, false);
    case ParamType::Reflectance:
      return *reflectance(n);
    case ParamType::Ior:
      return ior(n);
    case ParamType::Fluorescence:
      return fluorescence(n);
    case ParamType::Dye:
      return fluorescence(n, true);
    case ParamType::Coating: {
      checkAttributes(n, {});
      const auto cc = uniqueChildren(n, {"thickness", "ior"});
      CoatingDesc coat;
      coat.loc = loc(n);
      coat.thicknessNm = number(required(cc, n, "thickness"), *spec.range);
      coat.ior = ior(required(cc, n, "ior"));
      return coat;
    }
    case ParamType::Name: {
      const std::string t = text(n);
      if (t.empty()) fail(n, "a name in <" + std::string(n.name()) + ">", "nothing");
      return t;
    }
    case ParamType::Reals:
    case ParamType::Indices:
      try {
        return arrayFromText(text(n), spec.type == ParamType::Indices, spec.columns);
      } catch (const Error& e) {
        throw Error(loc(n).str() + ": <" + std::string(n.name()) + "> (" + spec.what +
                    "): " + e.what());
      }
    }
    fail(n, "a declared parameter type", "none"); // unreachable: the switch is exhaustive
  }

  // The material parameter names in the order they are listed.
  static std::vector<std::string> materialParameterNames() {
    std::vector<std::string> names;
    for (const ParamSpec& spec : materialParameters()) names.push_back(spec.name);
    return names;
  }

  // <material id="name" type="kind"> with the material's parameters as children.
  NamedMaterialDesc parseNamedMaterial(const pugi::xml_node& n) const {
    checkAttributes(n, {"id", "type"});
    NamedMaterialDesc d;
    d.loc = loc(n);
    if (!n.attribute("id")) fail(n, "an id=\"...\" on a top-level <material>", "none");
    if (!n.attribute("type"))
      fail(n, "a type=\"...\" (" + kinds_.materialList() + ") on <material>", "none");
    d.id = trim(decoded(n.attribute("id").value(), n));
    if (d.id.empty()) fail(n, "a non-empty material id", "id=\"\"");
    if (kinds_.isMaterial(d.id))
      fail(n, "a material id that is not a built-in kind's name", shownText(d.id));
    d.material.material = trim(decoded(n.attribute("type").value(), n));
    d.material.materialLoc = d.loc;
    if (!kinds_.isMaterial(d.material.material))
      fail(n, "a material type " + kinds_.materialList(), shownText(d.material.material));
    parseMaterialParameters(uniqueChildren(n, materialParameterNames()), d.material);
    kinds_.checkMaterial(d.material.material, d.material.params);
    return d;
  }

  // Objects whose <material> names a <material id>: checked to exist and to carry no material
  // parameters of their own; ids defined twice are errors. The others name a kind, whose
  // schema their parameters are checked against.
  void resolveMaterialReferences(SceneDesc& scene) const {
    std::map<std::string, const NamedMaterialDesc*> byId;
    for (const NamedMaterialDesc& m : scene.materials)
      if (!byId.emplace(m.id, &m).second)
        throw Error(m.loc.str() + ": expected a new material id, found '" + m.id +
                    "' defined twice (first at " + byId.at(m.id)->loc.str() + ")");
    for (ObjectDesc& o : scene.objects) resolveMaterialReference(o, byId);
  }

  // One object's material: a kind, whose schema its parameters are checked against, or the id
  // of a named material, and then no parameters of its own.
  void resolveMaterialReference(ObjectDesc& o,
                                const std::map<std::string, const NamedMaterialDesc*>& byId) const {
    const auto it = byId.find(o.material);
    if (it == byId.end()) {
      if (!kinds_.isMaterial(o.material))
        throw Error(o.materialLoc.str() + ": expected a material " + kinds_.materialList() +
                    " or the id of a <material id=\"...\"> of the scene, found " +
                    shownText(o.material));
      kinds_.checkMaterial(o.material, o.params);
      return;
    }
    o.materialRef = o.material;
    if (!o.params.empty())
      throw Error(o.params.items().front().loc.str() +
                  ": expected no material parameters on an object whose material '" +
                  o.materialRef + "' is defined at " + it->second->loc.str() + ", found <" +
                  o.params.items().front().name + "> (define a second material instead)");
  }

public:
  // The one item of a document holding only an object or only a light (an item given as
  // data); an object's material may name one of `scene`'s materials.
  std::variant<ObjectDesc, LightDesc> parseItem(const SceneDesc& scene) const {
    const pugi::xml_node root = doc_.child("scene");
    const std::vector<pugi::xml_node> items = elements(root);
    if (items.size() != 1) failAt(1, "expected one object or light");
    const pugi::xml_node n = items.front();
    if (std::string(n.name()) == "light") return parseLight(n);
    const auto shape = kinds_.shape(n.name());
    if (!shape) fail(n, "a shape " + kinds_.shapeList(), shownText(n.name()));
    ObjectDesc o = parseObject(n, *shape);
    std::map<std::string, const NamedMaterialDesc*> byId;
    for (const NamedMaterialDesc& m : scene.materials) byId.emplace(m.id, &m);
    resolveMaterialReference(o, byId);
    return o;
  }

private:
  // <transform>: translate, rotate (axis x, y, z and an angle in degrees), scale (one or three
  // factors) and matrix (4x4, row-major, last row 0 0 0 1) steps, applied in the order written.
  AffineDesc transform(const pugi::xml_node& n) const {
    checkAttributes(n, {});
    AffineDesc a;
    auto then = [&](const std::array<std::array<double, 3>, 3>& m, const Vec3d& t) {
      AffineDesc r;
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
          r.m[i][j] = m[i][0] * a.m[0][j] + m[i][1] * a.m[1][j] + m[i][2] * a.m[2][j];
      r.t = Vec3d(m[0][0] * a.t.x + m[0][1] * a.t.y + m[0][2] * a.t.z,
                  m[1][0] * a.t.x + m[1][1] * a.t.y + m[1][2] * a.t.z,
                  m[2][0] * a.t.x + m[2][1] * a.t.y + m[2][2] * a.t.z) +
            t;
      a = r;
    };
    using M = std::array<std::array<double, 3>, 3>;
    const M identity{{{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}};
    for (pugi::xml_node c : elements(n)) {
      const std::string tag = c.name();
      if (tag == "translate") {
        then(identity, vec3(c, "a translation x, y, z"));
      } else if (tag == "rotate") {
        const auto v = numbers(c, 4, 4, "axis x, y, z and an angle in degrees");
        const Vec3d axis(v[0], v[1], v[2]);
        const double len = length(axis);
        if (!(len > 0)) fail(c, "a non-zero rotation axis", shownText(text(c)));
        const Vec3d k = axis / len;
        const double th = v[3] * kPi / 180, co = std::cos(th), si = std::sin(th), t = 1 - co;
        // Rodrigues' rotation formula.
        then({{{t * k.x * k.x + co, t * k.x * k.y - si * k.z, t * k.x * k.z + si * k.y},
               {t * k.x * k.y + si * k.z, t * k.y * k.y + co, t * k.y * k.z - si * k.x},
               {t * k.x * k.z - si * k.y, t * k.y * k.z + si * k.x, t * k.z * k.z + co}}},
             Vec3d(0, 0, 0));
      } else if (tag == "scale") {
        const auto v = numbers(c, 1, 3, "one factor or three factors x, y, z");
        if (v.size() == 2) fail(c, "one or three scale factors", "2");
        const Vec3d f = v.size() == 1 ? Vec3d(v[0], v[0], v[0]) : Vec3d(v[0], v[1], v[2]);
        if (!(f.x != 0 && f.y != 0 && f.z != 0))
          fail(c, "non-zero scale factors", shownText(text(c)));
        then({{{f.x, 0, 0}, {0, f.y, 0}, {0, 0, f.z}}}, Vec3d(0, 0, 0));
      } else if (tag == "matrix") {
        const auto v = numbers(c, 16, 16, "a 4x4 matrix, row by row");
        if (v[12] != 0 || v[13] != 0 || v[14] != 0 || v[15] != 1)
          fail(c, "an affine matrix (last row 0, 0, 0, 1)", shownText(text(c)));
        then({{{v[0], v[1], v[2]}, {v[4], v[5], v[6]}, {v[8], v[9], v[10]}}},
             Vec3d(v[3], v[7], v[11]));
      } else {
        fail(c, "one of <translate>, <rotate>, <scale>, <matrix> inside <transform>",
             "<" + tag + ">");
      }
    }
    const double det = a.determinant();
    if (!a.keepsVolume())
      fail(n, "a transform that keeps volume (non-zero determinant)",
           "determinant " + numberText(det));
    return a;
  }

  // An object element (<sphere>, <plane>, ...: a shape kind) with its kind's parameters, each
  // read by its declared type and checked by the kind, and its appearance: <material> (a kind
  // or a <material id>) with the material's parameters, <emission>, and a <medium> where the
  // kind holds one.
  ObjectDesc parseObject(const pugi::xml_node& n, const ShapeKindSchema& kind) const {
    const std::string tag = n.name();
    std::vector<std::string> attributes, allowed{"material"};
    for (const std::string& p : materialParameterNames()) allowed.push_back(p);
    allowed.push_back("emission");
    for (const ShapeParameter& p : kind.params)
      (p.attribute ? attributes : allowed).push_back(p.spec.name);
    attributes.push_back("name");
    attributes.push_back("group");
    checkAttributes(n, attributes);
    if (kind.holdsMedium) allowed.push_back("medium");
    const auto c = uniqueChildren(n, allowed);
    ObjectDesc o;
    o.shape = tag;
    o.loc = loc(n);
    if (const pugi::xml_attribute a = n.attribute("name")) {
      o.name = trim(decoded(a.value(), n));
      const bool printable = std::none_of(o.name.begin(), o.name.end(), [](char ch) {
        return static_cast<unsigned char>(ch) < 0x20;
      });
      if (o.name.empty() || !printable)
        fail(n, "a name of printable characters in name=\"...\" on <" + tag + ">",
             o.name.empty() ? "an empty one" : "control characters");
    }
    for (const ShapeParameter& p : kind.params) {
      if (p.attribute) {
        const pugi::xml_attribute a = n.attribute(p.spec.name);
        const std::string v = a ? trim(decoded(a.value(), n)) : std::string();
        if (v.empty()) {
          if (!p.required) continue;
          fail(n,
               "a " + std::string(p.spec.name) + "=\"...\" (" + p.spec.what + ") on <" + tag + ">",
               "none");
        }
        o.geometry.set({p.spec.name, relativeToScene(v), o.loc});
        continue;
      }
      const auto it = c.find(p.spec.name);
      if (it == c.end()) {
        if (p.required) required(c, n, p.spec.name);
        continue;
      }
      const ParamValue v = parameterValue(p.spec, it->second);
      if (p.valueProblem)
        if (const char* expected = p.valueProblem(v))
          fail(it->second, expected, shownText(text(it->second)));
      o.geometry.set({p.spec.name, v, loc(it->second)});
    }
    if (const auto problem = kind.problem(o.geometry)) fail(n, problem->expected, problem->found);
    const pugi::xml_node mat = required(c, n, "material");
    o.material = text(mat);
    o.materialLoc = loc(mat);
    if (o.material.empty())
      fail(mat, "a material " + kinds_.materialList() + " or a <material id>", "nothing");
    parseMaterialParameters(c, o);
    if (c.count("emission")) {
      const pugi::xml_node e = c.at("emission");
      o.emission = spectrum(e, true, {"scale", "at", "quantity"});
      o.emissionScale = scaleAttribute(e, "an", "emission scale", true);
      // A lamp as measured: irradiance on its axis at="d", or its total flux.
      if (e.attribute("at")) o.emissionAt = numberAttribute(e, "at", kMeasuredDistanceRange);
      o.emissionFlux = choiceAttribute(e, "quantity", {"radiance", "flux"}) == 1;
      if (o.emissionAt && o.emissionFlux)
        fail(e, "either at=\"d\" (irradiance at a distance) or quantity=\"flux\" on <emission>",
             "both");
    }
    if (c.count("medium")) o.medium = medium(c.at("medium"));
    o.group = groupAttribute(n);
    if (!o.group.empty() && !o.emission && !o.medium)
      fail(n, "group=\"" + o.group + "\" on an emitter (an <emission> or an emitting <medium>)",
           "a <" + tag + "> that emits nothing");
    return o;
  }

  // <medium type="kind"> (homogeneous when absent) with the kind's parameters as children.
  MediumDesc medium(const pugi::xml_node& n) const {
    checkAttributes(n, {"type"});
    MediumDesc m;
    m.loc = loc(n);
    if (n.attribute("type")) m.kind = trim(decoded(n.attribute("type").value(), n));
    const auto kind = kinds_.medium(m.kind);
    if (!kind) fail(n, "a medium type " + kinds_.mediumList(), shownText(m.kind));
    parseTakenParameters(n, kind->params, m.params);
    return m;
  }

  IorDesc ior(const pugi::xml_node& n) const {
    IorDesc d;
    d.loc = loc(n);
    const std::string t = text(n);
    if (t.empty())
      fail(n,
           "an IOR (a number, bk7, diamond, fused_silica, cauchy: A, B[, C] or sellmeier: B1, B2, "
           "B3, C1, C2, C3)",
           "nothing");
    const auto colon = t.find(':');
    if (colon != std::string::npos) {
      const std::string kind = trim(t.substr(0, colon));
      const auto tk = tokens(t.substr(colon + 1));
      if (kind == "cauchy") {
        d.kind = IorDesc::Kind::Cauchy;
        if (tk.size() < 2 || tk.size() > 3)
          fail(n, "cauchy: A, B[, C] (2 or 3 numbers)", std::to_string(tk.size()) + " numbers");
      } else if (kind == "sellmeier") {
        d.kind = IorDesc::Kind::Sellmeier;
        if (tk.size() != 6)
          fail(n, "sellmeier: B1, B2, B3, C1, C2, C3 (6 numbers)",
               std::to_string(tk.size()) + " numbers");
      } else {
        fail(n, "a dispersion formula cauchy: or sellmeier:", shownText(kind + ":"));
      }
      for (const auto& s : tk) d.coefficients.push_back(numberOf(n, s, "a dispersion coefficient"));
      return d;
    }
    const char first = t[0];
    if (std::isdigit(static_cast<unsigned char>(first)) || first == '.' || first == '-' ||
        first == '+') {
      d.kind = IorDesc::Kind::Number;
      d.value = number(n, kIorRange);
      return d;
    }
    if (t != "bk7" && t != "diamond" && t != "fused_silica")
      fail(n, "a named glass bk7, diamond or fused_silica", shownText(t));
    d.kind = IorDesc::Kind::Named;
    d.name = t;
    return d;
  }

  // <fluorescence> of a surface, or of a medium (inMedium: no measured matrix, and <peak> is
  // the dye's peak absorption coefficient per unit length, required).
  FluorescenceDesc fluorescence(const pugi::xml_node& n, bool inMedium = false) const {
    checkAttributes(n, {});
    const auto c =
        uniqueChildren(n, {"absorption", "stokes", "width", "skew", "yield", "peak", "matrix",
                           "eem", "absorptance", "emission", "reference", "concentration"});
    FluorescenceDesc f;
    f.loc = loc(n);
    if (c.count("concentration")) {
      const pugi::xml_node k = c.at("concentration");
      if (inMedium)
        fail(k,
             "no <concentration> in a medium's <fluorescence> (its <peak> is the dye's "
             "concentration)",
             "<concentration>");
      if (c.count("matrix"))
        fail(k,
             "a <concentration> map only with the parametric model or an <eem> (a measured "
             "matrix's elastic part is not the dye's)",
             "<concentration> with a <matrix>");
      checkAttributes(k, {});
      const std::string p = text(k);
      if (p.empty()) fail(k, "a CSV file of concentrations in <concentration>", "nothing");
      f.concentrationCsv = relativeToScene(p);
    }
    for (const char* measured : {"matrix", "eem"})
      if (inMedium && c.count(measured))
        fail(c.at(measured),
             "the parametric model in a medium's <fluorescence> (<absorption>, <stokes>, <peak>, "
             "...; measured matrices and EEMs describe surfaces)",
             "<" + std::string(measured) + ">");
    if (c.count("eem")) return importedEem(c, n, f);
    if (c.count("emission")) return dyeSpectra(c, n, f, inMedium);
    if (c.count("reference"))
      fail(c.at("reference"), "<reference> only with an <eem> in <fluorescence>",
           "<reference> without one");
    if (c.count("absorptance"))
      fail(c.at("absorptance"),
           "<absorptance> only with an <eem> or an <emission> spectrum in <fluorescence>",
           "<absorptance> without either");
    if (inMedium && !c.count("peak"))
      fail(n,
           "a <peak> (the dye's peak absorption coefficient per unit length) in a medium's "
           "<fluorescence>",
           "none");
    if (c.count("matrix")) {
      for (const char* tag : {"absorption", "stokes", "width", "skew", "yield", "peak"})
        if (c.count(tag))
          fail(c.at(tag), "only <matrix> when a measured matrix is given",
               "<" + std::string(tag) + ">");
      const std::string p = text(c.at("matrix"));
      if (p.empty()) fail(c.at("matrix"), "a CSV file name in <matrix>", "nothing");
      f.matrixCsv = relativeToScene(p);
      return f;
    }
    const pugi::xml_node abs = required(c, n, "absorption");
    const std::string a = text(abs);
    if (!a.empty() &&
        (std::isdigit(static_cast<unsigned char>(a[0])) || a[0] == '.' || a[0] == '-'))
      f.absorptionNm = number(abs, kAbsorptionRange);
    else if (!a.empty())
      f.absorptionName = a;
    else
      fail(abs, "an absorption colour name or peak wavelength", "nothing");
    f.stokesNm = number(required(c, n, "stokes"), kStokesRange);
    if (c.count("width")) f.widthNm = number(c.at("width"), kWidthRange);
    if (c.count("skew")) f.skew = number(c.at("skew"), kSkewRange);
    if (c.count("yield")) f.quantumYield = number(c.at("yield"), kYieldRange);
    if (c.count("peak"))
      f.peakAbsorptance = number(c.at("peak"), inMedium ? kPeakCoefficientRange : kPeakRange);
    return f;
  }

  // A number in attribute `name` of n, within r: "expected <what> in name="..." within
  // (lo, hi], found '...'".
  double numberAttribute(const pugi::xml_node& n, const char* name, const ParameterRange& r) const {
    const std::string t = decoded(n.attribute(name).value(), n);
    const std::string what = std::string(r.what) + " in " + name + "=\"...\"";
    const double v = parseNumber(t, loc(n).str(), what);
    if (!r.contains(v))
      fail(n,
           what + " within " + (r.openLow ? "(" : "[") + numberText(r.lo) + ", " +
               numberText(r.hi) + "]",
           shownText(t));
    return v;
  }

  // One of the words in attribute `name` of n (the first when absent): its index.
  size_t choiceAttribute(const pugi::xml_node& n, const char* name,
                         const std::vector<std::string>& words) const {
    const pugi::xml_attribute a = n.attribute(name);
    if (!a) return 0;
    const std::string t = trim(decoded(a.value(), n));
    for (size_t i = 0; i < words.size(); ++i)
      if (t == words[i]) return i;
    std::string list;
    for (size_t i = 0; i < words.size(); ++i)
      list +=
          (i ? (i + 1 == words.size() ? " or " : ", ") : "") + (name + ("=\"" + words[i] + "\""));
    fail(n, list, shownText(t));
  }

  // <fluorescence> with <absorptance> and <emission> spectra and a <yield>: a dye as a
  // datasheet gives it (the separable matrix); in a medium, <peak> is the coefficient its
  // absorptance's maximum is scaled to.
  FluorescenceDesc dyeSpectra(const std::map<std::string, pugi::xml_node>& c,
                              const pugi::xml_node& n, FluorescenceDesc f, bool inMedium) const {
    for (const char* tag : {"absorption", "stokes", "width", "skew", "matrix", "reference"})
      if (c.count(tag))
        fail(c.at(tag),
             "only <absorptance>, <emission>, <yield>" + std::string(inMedium ? ", <peak>" : "") +
                 " and <concentration> with an <emission> spectrum (the separable form)",
             "<" + std::string(tag) + ">");
    if (!inMedium && c.count("peak"))
      fail(c.at("peak"),
           "no <peak> with an <absorptance> spectrum on a surface (the spectrum is the "
           "absorptance itself)",
           "<peak>");
    if (inMedium && !c.count("peak"))
      fail(n,
           "a <peak> (the dye's peak absorption coefficient per unit length) in a medium's "
           "<fluorescence>",
           "none");
    auto spectra = std::make_shared<DyeSpectra>();
    spectra->absorptance = *spectrum(required(c, n, "absorptance"), false);
    spectra->emission = *spectrum(c.at("emission"), false);
    f.spectra = spectra;
    if (c.count("yield")) f.quantumYield = number(c.at("yield"), kYieldRange);
    if (c.count("peak")) f.peakAbsorptance = number(c.at("peak"), kPeakCoefficientRange);
    return f;
  }

  // <fluorescence> with an <eem file="..." rayleigh_width="..." .../>: an instrument EEM, made
  // absolute by <yield> or <reference>, and <peak> or <absorptance> (docs/eem-import.md).
  FluorescenceDesc importedEem(const std::map<std::string, pugi::xml_node>& c,
                               const pugi::xml_node& n, FluorescenceDesc f) const {
    for (const char* tag : {"absorption", "stokes", "width", "skew", "matrix", "emission"})
      if (c.count(tag))
        fail(c.at(tag), "only <yield> or <reference>, and <peak> or <absorptance>, with an <eem>",
             "<" + std::string(tag) + ">");
    const pugi::xml_node x = c.at("eem");
    checkAttributes(x, {"file", "layout", "units", "rayleigh_width", "second_order", "raman_shift",
                        "raman_width", "emission_shape"});
    if (!text(x, {"file", "layout", "units", "rayleigh_width", "second_order", "raman_shift",
                  "raman_width", "emission_shape"})
             .empty())
      fail(x, "attributes only on <eem>", "text inside it");
    auto e = std::make_shared<EemDesc>();
    e->loc = loc(x);
    const std::string file = trim(decoded(x.attribute("file").value(), x));
    if (file.empty()) fail(x, "an EEM CSV file in file=\"...\" on <eem>", "none");
    e->file = relativeToScene(file);
    e->layout.emissionRows = choiceAttribute(x, "layout", {"excitation_rows", "emission_rows"});
    e->layout.energyUnits = choiceAttribute(x, "units", {"photons", "energy"});
    if (!x.attribute("rayleigh_width"))
      fail(x,
           "rayleigh_width=\"nm\" on <eem> (the full width of the Rayleigh bands to remove; 0 "
           "for an EEM without them)",
           "none");
    e->layout.rayleighWidthNm = numberAttribute(x, "rayleigh_width", kScatterWidthRange);
    e->layout.secondOrder = choiceAttribute(x, "second_order", {"true", "false"}) == 0;
    const bool hasShift = x.attribute("raman_shift"), hasWidth = x.attribute("raman_width");
    if (hasShift != hasWidth)
      fail(x, "raman_shift=\"cm^-1\" (or \"water\") and raman_width=\"nm\" together on <eem>",
           "only one of them");
    if (x.attribute("raman_shift")) {
      const std::string shift = trim(decoded(x.attribute("raman_shift").value(), x));
      e->layout.ramanShiftCm = shift == "water"
                                   ? kWaterRamanShiftCm
                                   : numberAttribute(x, "raman_shift", kRamanShiftRange);
      e->layout.ramanWidthNm = numberAttribute(x, "raman_width", kScatterWidthRange);
    }
    e->layout.meanEmissionShape = choiceAttribute(x, "emission_shape", {"rows", "mean"}) == 1;
    // The absolute scale: a yield or a reference dye; an absorptance or a peak.
    if (c.count("yield") == c.count("reference"))
      fail(n, "either <yield> or <reference> with an <eem>", c.count("yield") ? "both" : "neither");
    if (c.count("peak") == c.count("absorptance"))
      fail(n,
           "either <peak> (absorptance from the EEM's excitation profile) or <absorptance> "
           "with an <eem>",
           c.count("peak") ? "both" : "neither");
    if (c.count("yield")) f.quantumYield = number(c.at("yield"), kYieldRange);
    if (c.count("peak")) f.peakAbsorptance = number(c.at("peak"), kPeakRange);
    if (c.count("absorptance")) e->absorptance = spectrum(c.at("absorptance"), false);
    if (c.count("reference")) {
      const pugi::xml_node r = c.at("reference");
      checkAttributes(r, {"file", "yield", "absorptance", "excitation"});
      for (const char* a : {"file", "yield", "absorptance"})
        if (!r.attribute(a))
          fail(r, std::string(a) + "=\"...\" on <reference> (file, yield and absorptance)", "none");
      const std::string rf = trim(decoded(r.attribute("file").value(), r));
      if (rf.empty()) fail(r, "a reference EEM file in file=\"...\"", "an empty one");
      e->referenceFile = relativeToScene(rf);
      e->referenceYield = numberAttribute(r, "yield", kReferenceYieldRange);
      e->referenceAbsorptance = numberAttribute(r, "absorptance", kReferenceAbsorptanceRange);
      if (r.attribute("excitation"))
        e->referenceExcitationNm = numberAttribute(r, "excitation", kInstrumentNmRange);
    }
    f.eem = std::move(e);
    return f;
  }

  void checkMemory(const SettingsDesc& s) const {
    const double bytes = renderBufferBytes(s.width, s.height, s.bands.count());
    std::ostringstream found;
    found << s.width << "x" << s.height << " with " << s.bands.count() << " bands";
    requireMemory(bytes, s.widthLoc.str(), "a resolution", found.str());
  }

  std::string file_;
  const SceneKindSchemas& kinds_;             ///< what the kinds take
  const std::vector<std::string>* linePaths_; ///< a tree's path per line, or null (a file)
  std::vector<size_t> newlines_;
  pugi::xml_document doc_;
};

} // namespace

double renderBufferBytes(int width, int height, int bands) {
  // Film accumulators (two doubles per band, plus XYZ, a luminance half-sum and counts) and
  // the output image (float band means and variances, RGB, XYZ, a variance, a count).
  const double pixels = static_cast<double>(width) * height;
  return pixels * ((2.0 * bands + 6) * 8.0 + (2.0 * bands + 9) * 4.0);
}

namespace {
// The key of the scene's state (with the calibration file's bytes), not of its text: the
// same scene written otherwise, given as data or edited into it from Python, renders under
// the same key.
SceneDesc keyed(SceneDesc d) {
  d.textDigest = sceneStateDigest(d);
  return d;
}
} // namespace

SceneDesc parseScene(const std::string& text, const std::string& file,
                     const SceneKindSchemas& kinds) {
  return keyed(SceneParser(text, file, kinds).parse());
}

SceneDesc parseSceneTree(const SceneTree& tree, const std::string& name,
                         const SceneKindSchemas& kinds) {
  const SceneTreeText t = sceneTreeText(tree);
  return keyed(SceneParser(t.text, name, kinds, &t.linePaths).parse());
}

std::variant<ObjectDesc, LightDesc> parseItemTree(const SceneTree& item, bool light,
                                                  const std::string& path, const SceneDesc& scene,
                                                  const SceneKindSchemas& kinds) {
  const SceneTreeText t = itemTreeText(item, light, path);
  // File names as Scene.to_dict gives them: relative to the working directory.
  return SceneParser(t.text, "<item>", kinds, &t.linePaths).parseItem(scene);
}

SceneDesc loadScene(const std::string& path, const SceneKindSchemas& kinds) {
  return parseScene(readRegularFile(path, 64u << 20, "scene file"), path, kinds);
}

} // namespace nx
