#include "io/spectral_cube.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <mutex>
#include <sstream>

#include "core/error.h"
#include "core/file_text.h"
#include "core/memory.h"
#include "core/text_table.h"
#include "io/envi_header.h"
#include "io/gdal_library.h"
#include "io/spectral_exr.h"
#include "io/srgb_image.h"

namespace nx {
namespace {

namespace fs = std::filesystem;

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

std::string extensionOf(const std::string& path) {
  return lower(fs::path(path).extension().string());
}

// GDAL's messages go to our errors, not to stderr.
struct QuietGdal {
  QuietGdal() { gdal().CPLPushErrorHandler(gdal().CPLQuietErrorHandler); }
  ~QuietGdal() { gdal().CPLPopErrorHandler(); }
  QuietGdal(const QuietGdal&) = delete;
  QuietGdal& operator=(const QuietGdal&) = delete;
};

std::string gdalMessage() {
  const char* m = gdal().CPLGetLastErrorMsg();
  return m && *m ? m : "unknown GDAL error";
}

void registerDrivers() {
  static std::once_flag once;
  std::call_once(once, [] {
    gdal().GDALRegister_ENVI();
    gdal().GDALRegister_GTiff();
  });
}

// The data file of an ENVI header: the header's stem with no extension or a usual one.
std::string enviDataFor(const std::string& header) {
  const fs::path stem = fs::path(header).replace_extension("");
  std::vector<std::string> tried;
  for (const char* ext : {"", ".img", ".dat", ".raw", ".bsq", ".bil", ".bip", ".bin", ".envi"}) {
    fs::path p = stem;
    p += ext;
    std::error_code ec;
    if (fs::exists(p, ec) && !fs::is_directory(p, ec)) return p.string(); // a FIFO: refused later
    tried.push_back(p.filename().string());
  }
  std::string list;
  for (const std::string& t : tried) list += (list.empty() ? "" : ", ") + t;
  throw Error(header + ": expected the ENVI data file beside the header (one of " + list +
              "), found none");
}

// The header of an ENVI data file by GDAL's convention (extension replaced, or .hdr appended);
// empty when there is none.
std::string enviHeaderFor(const std::string& data) {
  std::error_code ec;
  const std::string replaced = fs::path(data).replace_extension(".hdr").string();
  if (fs::exists(replaced, ec)) return replaced;
  if (fs::exists(data + ".hdr", ec)) return data + ".hdr";
  return "";
}

bool hasEnviHeader(const std::string& data) {
  return !enviHeaderFor(data).empty();
}

// Wavelengths in nm from values in `units` (an ENVI or TIFF unit name, or empty).
std::vector<double> toNanometres(std::vector<double> v, const std::string& units,
                                 const std::string& where) {
  const std::string u = lower(units);
  double scale = 0;
  if (u == "nanometers" || u == "nanometres" || u == "nm") {
    scale = 1;
  } else if (u == "micrometers" || u == "micrometres" || u == "microns" || u == "um" ||
             u == "\xc2\xb5m") {
    scale = 1000;
  } else if (u.empty() || u == "unknown") {
    const bool allNm = std::all_of(v.begin(), v.end(), [](double x) { return x >= 100; });
    const bool allUm = std::all_of(v.begin(), v.end(), [](double x) { return x > 0 && x <= 30; });
    if (allNm)
      scale = 1;
    else if (allUm)
      scale = 1000;
    else
      throw Error(where + ": expected wavelength units (Nanometers or Micrometers), found none, "
                          "and the values do not tell");
  } else {
    throw Error(where + ": expected wavelength units Nanometers or Micrometers, found '" + units +
                "'");
  }
  for (double& x : v) x *= scale;
  return v;
}

const char* typeName(GDALDataType t) {
  return gdal().GDALGetDataTypeName(t);
}

SpectralCube fromExr(const std::string& path) {
  SpectralImage img = readSpectralExr(path);
  SpectralCube c;
  c.path = path;
  c.format = "spectral EXR";
  c.width = img.width;
  c.height = img.height;
  for (int b = 0; b < img.bands.count(); ++b) {
    c.wavelengthNm.push_back(img.bands.centroid(b));
    c.channelNm.push_back(img.bands.channelNm(b));
    c.fwhmNm.push_back(img.bands.fwhm(b));
    c.bandNames.push_back(img.bands.channel(b).name);
  }
  if (const auto it = img.attributes.find("nxrender.bands"); it != img.attributes.end())
    c.sensorText = it->second;
  if (const auto it = img.attributes.find("nxrender.objectLabels"); it != img.attributes.end()) {
    std::istringstream lines(it->second);
    std::string line;
    while (std::getline(lines, line)) {
      const size_t tab = line.find('\t');
      if (tab == std::string::npos) continue;
      c.objectLabels[static_cast<uint32_t>(
          std::strtoul(line.substr(0, tab).c_str(), nullptr, 10))] = line.substr(tab + 1);
    }
  }
  c.values = std::move(img.radiance);
  c.variance = std::move(img.bandVariance);
  c.objectId = std::move(img.objectId);
  return c;
}

SpectralCube fromGdal(const std::string& path, const std::string& shownPath, bool envi,
                      const CubeReadOptions& options) {
  // GDAL opens the files itself: only regular files reach it (a FIFO would block it), and an
  // ENVI header's layout fields are checked first (GDAL defaults values it does not know).
  requireRegularFile(path, kMaxExrFileBytes, envi ? "ENVI data file" : "TIFF file");
  if (envi) {
    std::error_code ec;
    checkEnviHeader(enviHeaderFor(path), static_cast<double>(fs::file_size(path, ec)));
  }
  registerDrivers();
  QuietGdal quiet;
  const char* drivers[] = {envi ? "ENVI" : "GTiff", nullptr};
  std::unique_ptr<void, void (*)(void*)> ds(
      gdal().GDALOpenEx(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY, drivers, nullptr, nullptr),
      [](void* d) {
        if (d) gdal().GDALClose(d);
      });
  if (!ds)
    throw Error(shownPath + ": cannot read it as " + (envi ? "an ENVI cube" : "a TIFF") + ": " +
                gdalMessage());
  const int w = gdal().GDALGetRasterXSize(ds.get()), h = gdal().GDALGetRasterYSize(ds.get()),
            nb = gdal().GDALGetRasterCount(ds.get());
  if (w <= 0 || h <= 0 || nb <= 0)
    throw Error(shownPath + ": expected at least one band of at least 1 x 1 pixels, found " +
                std::to_string(w) + " x " + std::to_string(h) + " x " + std::to_string(nb));
  const GDALDataType type = gdal().GDALGetRasterDataType(gdal().GDALGetRasterBand(ds.get(), 1));
  if (gdal().GDALDataTypeIsComplex(type))
    throw Error(shownPath + ": expected real-valued bands, found " + typeName(type));
  SpectralCube c;
  c.path = shownPath;
  c.width = w;
  c.height = h;
  std::string interleave = "";
  if (const char* il = gdal().GDALGetMetadataItem(ds.get(), "INTERLEAVE", "IMAGE_STRUCTURE"))
    interleave = il;
  c.format = std::string(envi ? "ENVI" : "TIFF") + " (" +
             (interleave == "BAND"    ? "BSQ"
              : interleave == "LINE"  ? "BIL"
              : interleave == "PIXEL" ? "BIP"
                                      : interleave) +
             ", " + typeName(type) + ")";

  // The data must be all there: GDAL would read a short file's missing part as zeros.
  if (envi) {
    double offset = 0;
    if (const char* o = gdal().GDALGetMetadataItem(ds.get(), "header_offset", "ENVI"))
      offset = parseNumber(o, shownPath, "a header offset");
    const double need =
        offset + static_cast<double>(w) * h * nb * gdal().GDALGetDataTypeSizeBytes(type);
    std::error_code ec;
    const double have = static_cast<double>(fs::file_size(path, ec));
    const auto bytesText = [](double v) {
      return v < 9e15 ? std::to_string(static_cast<long long>(v)) : numberText(v);
    };
    if (!ec && have < need)
      throw Error(path + ": expected " + bytesText(need) + " bytes (header offset + " +
                  std::to_string(w) + " x " + std::to_string(h) + " x " + std::to_string(nb) + " " +
                  typeName(type) + " values), found " + bytesText(have) +
                  ": the data file is cut short");
  }

  // Wavelengths and widths: the options, else the ENVI header, else the TIFF's band metadata.
  std::string units;
  std::vector<double> wl, fwhm;
  if (envi) {
    if (const char* s = gdal().GDALGetMetadataItem(ds.get(), "wavelength", "ENVI"))
      wl = parseEnviNumberList(s, shownPath, "the header's wavelength list");
    if (const char* s = gdal().GDALGetMetadataItem(ds.get(), "fwhm", "ENVI"))
      fwhm = parseEnviNumberList(s, shownPath, "the header's fwhm list");
    if (const char* s = gdal().GDALGetMetadataItem(ds.get(), "wavelength_units", "ENVI")) units = s;
  } else {
    for (int b = 1; b <= nb; ++b) {
      GDALRasterBandH band = gdal().GDALGetRasterBand(ds.get(), b);
      const char* s = gdal().GDALGetMetadataItem(band, "wavelength", nullptr);
      if (!s) {
        wl.clear();
        break;
      }
      wl.push_back(parseNumber(s, shownPath + " band " + std::to_string(b), "a wavelength"));
      if (const char* f = gdal().GDALGetMetadataItem(band, "fwhm", nullptr))
        fwhm.push_back(parseNumber(f, shownPath + " band " + std::to_string(b), "an fwhm"));
      if (const char* u = gdal().GDALGetMetadataItem(band, "wavelength_units", nullptr)) units = u;
    }
    if (fwhm.size() != wl.size()) fwhm.clear();
  }
  if (!options.wavelengthNm.empty()) {
    wl = options.wavelengthNm;
    units = "nm";
  } else if (!wl.empty()) {
    wl = toNanometres(wl, units, shownPath);
    if (!fwhm.empty()) fwhm = toNanometres(fwhm, units.empty() ? "nm" : units, shownPath);
  }
  if (!options.fwhmNm.empty())
    fwhm = options.fwhmNm.size() == 1
               ? std::vector<double>(static_cast<size_t>(nb), options.fwhmNm[0])
               : options.fwhmNm;
  if (wl.empty())
    throw Error(shownPath + ": expected a wavelength list (" +
                (envi ? std::string("'wavelength = {...}' in the ENVI header")
                      : std::string("a 'wavelength' metadata item on every band")) +
                ", or --capture-wavelengths), found none");
  if (static_cast<int>(wl.size()) != nb)
    throw Error(shownPath + ": expected " + std::to_string(nb) +
                " wavelengths (one per band), found " + std::to_string(wl.size()));
  if (!fwhm.empty() && static_cast<int>(fwhm.size()) != nb)
    throw Error(shownPath + ": expected " + std::to_string(nb) +
                " fwhm values (one per band), found " + std::to_string(fwhm.size()));
  for (size_t i = 0; i < wl.size(); ++i)
    if (!(wl[i] > 0 && std::isfinite(wl[i])) ||
        (!fwhm.empty() && !(fwhm[i] > 0 && std::isfinite(fwhm[i]))))
      throw Error(shownPath + ": expected positive wavelengths and fwhm, found band " +
                  std::to_string(i + 1) + " at " + numberText(wl[i]) + " nm" +
                  (fwhm.empty() ? "" : " with fwhm " + numberText(fwhm[i])));
  c.wavelengthNm = wl;
  c.fwhmNm = fwhm;

  const double pixels = static_cast<double>(w) * h;
  requireMemory(pixels * nb * 8.0, shownPath, "a cube",
                std::to_string(w) + " x " + std::to_string(h) + " x " + std::to_string(nb));
  c.values.resize(static_cast<size_t>(pixels) * static_cast<size_t>(nb));
  std::vector<float> plane(static_cast<size_t>(pixels));
  for (int b = 0; b < nb; ++b) {
    if (gdal().GDALRasterIO(gdal().GDALGetRasterBand(ds.get(), b + 1), GF_Read, 0, 0, w, h,
                            plane.data(), w, h, GDT_Float32, 0, 0) != CE_None)
      throw Error(shownPath + ": cannot read band " + std::to_string(b + 1) + ": " + gdalMessage());
    for (size_t p = 0; p < plane.size(); ++p)
      c.values[p * static_cast<size_t>(nb) + static_cast<size_t>(b)] = plane[p];
  }
  return c;
}

// True when a sorts before b with digit runs compared as numbers ("x_2.png" < "x_10.png").
bool naturalLess(const std::string& a, const std::string& b) {
  size_t i = 0, j = 0;
  while (i < a.size() && j < b.size()) {
    if (std::isdigit(static_cast<unsigned char>(a[i])) &&
        std::isdigit(static_cast<unsigned char>(b[j]))) {
      size_t ie = i, je = j;
      while (ie < a.size() && std::isdigit(static_cast<unsigned char>(a[ie]))) ++ie;
      while (je < b.size() && std::isdigit(static_cast<unsigned char>(b[je]))) ++je;
      const std::string na = a.substr(i, ie - i), nb = b.substr(j, je - j);
      const std::string ta = na.substr(std::min(na.find_first_not_of('0'), na.size())),
                        tb = nb.substr(std::min(nb.find_first_not_of('0'), nb.size()));
      if (ta.size() != tb.size()) return ta.size() < tb.size();
      if (ta != tb) return ta < tb;
      i = ie, j = je;
    } else {
      if (a[i] != b[j]) return a[i] < b[j];
      ++i, ++j;
    }
  }
  return a.size() - i < b.size() - j;
}

// A directory of per-band grey PNGs (the CAVE layout: name_01.png ... name_31.png), in
// natural name order, wavelengths from the options.
SpectralCube fromPngStack(const std::string& dirPath, const CubeReadOptions& options) {
  std::vector<std::string> files;
  for (const auto& e : fs::directory_iterator(dirPath))
    if (e.is_regular_file() && extensionOf(e.path().string()) == ".png")
      files.push_back(e.path().string());
  std::sort(files.begin(), files.end(), [](const std::string& a, const std::string& b) {
    return naturalLess(fs::path(a).filename().string(), fs::path(b).filename().string());
  });
  if (files.empty())
    throw Error(dirPath + ": expected per-band PNG files in the directory, found none");
  if (options.wavelengthNm.empty())
    throw Error(dirPath + ": expected --capture-wavelengths for a stack of " +
                std::to_string(files.size()) +
                " per-band PNGs (e.g. 400:700:10 for the CAVE data), found none");
  if (options.wavelengthNm.size() != files.size())
    throw Error(dirPath + ": expected " + std::to_string(files.size()) +
                " wavelengths (one per PNG file), found " +
                std::to_string(options.wavelengthNm.size()));
  SpectralCube c;
  c.path = dirPath;
  c.wavelengthNm = options.wavelengthNm;
  if (!options.fwhmNm.empty())
    c.fwhmNm = options.fwhmNm.size() == 1 ? std::vector<double>(files.size(), options.fwhmNm[0])
                                          : options.fwhmNm;
  const size_t nb = files.size();
  int bits = 8;
  for (size_t b = 0; b < nb; ++b) {
    const GreyImage img =
        decodeGreyImage(readRegularFile(files[b], 1ull << 31, "PNG file"), files[b]);
    if (b == 0) {
      c.width = img.width;
      c.height = img.height;
      bits = img.bitsPerChannel;
      requireMemory(static_cast<double>(img.width) * img.height * static_cast<double>(nb) * 4.0,
                    dirPath, "a cube",
                    std::to_string(img.width) + " x " + std::to_string(img.height) + " x " +
                        std::to_string(nb));
      c.values.resize(static_cast<size_t>(img.width) * static_cast<size_t>(img.height) * nb);
    } else if (img.width != c.width || img.height != c.height) {
      throw Error(files[b] + ": expected " + std::to_string(c.width) + " x " +
                  std::to_string(c.height) + " pixels like " +
                  fs::path(files[0]).filename().string() + ", found " + std::to_string(img.width) +
                  " x " + std::to_string(img.height));
    }
    for (size_t p = 0; p < img.value.size(); ++p) c.values[p * nb + b] = img.value[p];
  }
  c.format = "PNG stack (" + std::to_string(nb) + " " + std::to_string(bits) + "-bit files)";
  return c;
}

} // namespace

std::vector<double> parseEnviNumberList(const std::string& text, const std::string& where,
                                        const std::string& what) {
  std::string body = text;
  const size_t open = body.find('{'), close = body.rfind('}');
  if (open != std::string::npos) {
    if (close == std::string::npos || close < open)
      throw Error(where + ": expected " + what + " as {a, b, ...}, found no closing brace");
    body = body.substr(open + 1, close - open - 1);
  }
  std::vector<double> out;
  size_t start = 0;
  while (start <= body.size()) {
    size_t end = body.find(',', start);
    if (end == std::string::npos) end = body.size();
    std::string cell = body.substr(start, end - start);
    const auto first = cell.find_first_not_of(" \t\r\n"), last = cell.find_last_not_of(" \t\r\n");
    cell = first == std::string::npos ? "" : cell.substr(first, last - first + 1);
    if (!cell.empty())
      out.push_back(parseNumber(cell, where, "a number in " + what));
    else if (end != body.size() || !out.empty())
      throw Error(where + ": expected a number in " + what + ", found an empty entry");
    start = end + 1;
  }
  return out;
}

SpectralCube readSpectralCube(const std::string& path, const CubeReadOptions& options) {
  std::error_code ec;
  if (!fs::exists(path, ec)) throw Error(path + ": cannot open the file (it does not exist)");
  const std::string ext = extensionOf(path);
  SpectralCube c;
  if (fs::is_directory(path, ec)) {
    c = fromPngStack(path, options);
  } else if (ext == ".exr") {
    c = fromExr(path);
    if (!options.wavelengthNm.empty() || !options.fwhmNm.empty())
      throw Error(path + ": a spectral EXR names its own bands; expected no wavelength options");
  } else if (ext == ".hdr") {
    c = fromGdal(enviDataFor(path), path, true, options);
  } else if (ext == ".tif" || ext == ".tiff") {
    c = fromGdal(path, path, false, options);
  } else if (hasEnviHeader(path)) {
    c = fromGdal(path, path, true, options);
  } else {
    throw Error(path + ": expected a spectral EXR (.exr), an ENVI cube (.hdr or a data file "
                       "with its .hdr beside it), a TIFF (.tif) or a directory of per-band PNGs, "
                       "found neither");
  }
  if (c.channelNm.empty()) c.channelNm = c.wavelengthNm;
  for (size_t i = 1; i < c.wavelengthNm.size(); ++i)
    if (!(c.wavelengthNm[i] > c.wavelengthNm[i - 1]))
      throw Error(path + ": expected increasing band wavelengths, found " +
                  numberText(c.wavelengthNm[i - 1]) + " nm then " + numberText(c.wavelengthNm[i]) +
                  " nm");
  return c;
}

} // namespace nx
