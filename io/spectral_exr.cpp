#include "io/spectral_exr.h"

#include "core/number_text.h"
#include "io/aov_names.h"

#include <Imath/half.h>
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>
#include <ImfStringAttribute.h>
#include <ImfThreading.h>
#include <algorithm>
#include <tbb/global_control.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <set>

#include "core/error.h"
#include "core/file_text.h"
#include "core/input_files.h"
#include "core/memory.h"
#include "io/atomic_file.h"
#include "io/exr_header_check.h"
#include "io/exr_names.h"
#include "io/exr_write_cost.h"
#include "io/fichet_channels.h"
#include "io/relight_channels.h"
#include "spectra/band_colour.h"
#include "spectra/colour.h"

namespace nx {

namespace {
// The attributes bandAttributes writes: derived from the bands, so dropped when read.
constexpr const char* kBandAttributeKeys[] = {"nxrender.bandNames", "nxrender.bandCentroids",
                                              "nxrender.bandFwhm"};
} // namespace

std::map<std::string, std::string> bandAttributes(const Sensor& bands) {
  std::string names, centroids, fwhm;
  for (int b = 0; b < bands.count(); ++b) {
    const char* sep = b ? "," : "";
    std::string name = bands.channel(b).name;
    std::replace(name.begin(), name.end(), ',', ';'); // the list's separator
    names += sep + name;
    centroids += sep + exactNumberText(bands.centroid(b));
    fwhm += sep + exactNumberText(bands.fwhm(b));
  }
  return {{kBandAttributeKeys[0], names},
          {kBandAttributeKeys[1], centroids},
          {kBandAttributeKeys[2], fwhm}};
}

std::string spectralChannelName(double nm) {
  std::string name = "S0." + fixedText(nm, 6) + "nm";
  name[name.find('.', 3)] = ',';
  return name;
}

static_assert(static_cast<int>(ExrCompression::Zip) == Imf::ZIP_COMPRESSION &&
                  static_cast<int>(ExrCompression::Dwab) == Imf::DWAB_COMPRESSION &&
                  static_cast<int>(ExrCompression::None) == Imf::NO_COMPRESSION,
              "ExrCompression follows OpenEXR's order");

namespace {
void checkFiniteValues(const std::string& path, const SpectralImage& image);
void writeExr(const std::string& path, const SpectralImage& image, Imf::PixelType stored,
              const ExrEncoding& encoding);
} // namespace

void refuseOverwritingASource(const std::string& path, const SpectralImage& image) {
  for (const std::string& source : image.sourceFiles)
    if (sameFile(path, source))
      throw Error(path + ": expected an output other than the file the image was read from (" +
                  source + "), found " + (path == source ? std::string("that file") : "it again") +
                  " (writing would destroy the image's own source: choose another name)");
  refuseReplacingAnInput(path);
}

void setPixelColour(SpectralImage& image, size_t i, const Xyz& xyz) {
  const Rgb c = xyzToLinearSrgb(xyz);
  image.rgb[i * 3] = static_cast<float>(std::max(c.r, 0.0));
  image.rgb[i * 3 + 1] = static_cast<float>(std::max(c.g, 0.0));
  image.rgb[i * 3 + 2] = static_cast<float>(std::max(c.b, 0.0));
  image.xyz[i * 3] = static_cast<float>(xyz.x);
  image.xyz[i * 3 + 1] = static_cast<float>(xyz.y);
  image.xyz[i * 3 + 2] = static_cast<float>(xyz.z);
}

void checkExrOutputName(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext != ".exr")
    throw Error(path +
                ": expected an output name ending in .exr (the file is an OpenEXR), found '" +
                (ext.empty() ? std::string("no extension") : ext) + "'");
}

void writeSpectralExr(const std::string& path, const SpectralImage& image,
                      const ExrEncoding& encoding) {
  writeExr(path, image, Imf::FLOAT, encoding);
}

void writeSpectralExrHalf(const std::string& path, const SpectralImage& image,
                          const ExrEncoding& encoding) {
  checkFiniteValues(path, image);
  if (!fitsInHalf(image))
    throw Error(path + ": expected values within the half-float range (65504) for half output, "
                       "found larger ones");
  writeExr(path, image, Imf::HALF, encoding);
}

bool fitsInHalf(const SpectralImage& image) {
  for (const std::vector<float>* v : {&image.radiance, &image.rgb, &image.xyz, &image.bandVariance,
                                      &image.yVariance, &image.white, &image.depth})
    for (float x : *v)
      if (!(std::abs(x) <= 65504.0f)) return false;
  for (const ImageLayer& l : image.layers)
    for (const std::vector<float>* v : {&l.values, &l.variances})
      for (float x : *v)
        if (!(std::abs(x) <= 65504.0f)) return false;
  for (const AovImageLayer& l : image.aovs)
    for (float x : l.values)
      if (!(std::abs(x) <= 65504.0f)) return false;
  for (const std::vector<float>* v : {&image.relight.values, &image.relight.halfDifferences})
    for (float x : *v)
      if (!(std::abs(x) <= 65504.0f)) return false;
  return true;
}

namespace {
// No NaN or infinity is written (a render never holds one; an image built elsewhere, e.g. in
// Python, may): the first one is named with its channel and pixel.
void checkFiniteValues(const std::string& path, const SpectralImage& image) {
  const auto check = [&](const std::vector<float>& v, size_t perPixel, const char* what) {
    for (size_t k = 0; k < v.size(); ++k)
      if (!std::isfinite(v[k])) {
        const size_t p = k / perPixel;
        throw Error(path + ": expected finite values in " + what + ", found " + numberText(v[k]) +
                    " at pixel " +
                    std::to_string(image.originX + static_cast<int>(p % image.width)) + "," +
                    std::to_string(image.originY + static_cast<int>(p / image.width)) +
                    " (nothing written)");
      }
  };
  const size_t nb = static_cast<size_t>(image.bands.count());
  check(image.radiance, nb, "the spectral channels");
  check(image.rgb, 3, "R, G, B");
  check(image.xyz, 3, "X, Y, Z");
  check(image.bandVariance, nb, "the Variance channels");
  check(image.yVariance, 1, "Variance.Y");
  check(image.white, nb, "the white-reference channels");
  check(image.depth, 1, "Depth");
  for (const ImageLayer& l : image.layers) {
    check(l.values, nb, ("the " + l.name + " layer").c_str());
    check(l.variances, nb, ("the " + l.name + " layer's variances").c_str());
  }
  for (const AovImageLayer& l : image.aovs)
    if (const auto k = aovKindNamed(l.name))
      check(l.values, static_cast<size_t>(aovChannelCount(*k, image.bands.count())),
            ("the " + l.name + " layer").c_str());
  // The transport is planar ([group][entry][pixel]): name the pixel within its plane.
  const size_t pixels = static_cast<size_t>(image.width) * static_cast<size_t>(image.height);
  for (const std::vector<float>* v : {&image.relight.values, &image.relight.halfDifferences})
    for (size_t k = 0; k < v->size(); ++k)
      if (!std::isfinite((*v)[k])) {
        const size_t p = k % pixels;
        throw Error(path + ": expected finite values in the relight channels, found " +
                    numberText((*v)[k]) + " at pixel " +
                    std::to_string(image.originX + static_cast<int>(p % image.width)) + "," +
                    std::to_string(image.originY + static_cast<int>(p / image.width)) +
                    " (nothing written)");
      }
}

// The text naming each band's wavelength in its channel ("550,000000nm").
std::vector<std::string> bandWavelengthTexts(const std::vector<std::string>& bandChannels) {
  std::vector<std::string> out;
  for (const std::string& c : bandChannels) out.push_back(c.substr(c.find('.') + 1));
  return out;
}

// Float channels are stored as `stored` (FLOAT or HALF; OpenEXR converts from the float
// buffers); SampleCount always as UINT.
void writeExr(const std::string& path, const SpectralImage& image, Imf::PixelType stored,
              const ExrEncoding& encoding) {
  refuseOverwritingASource(path, image);
  const int nBands = image.bands.count();
  const size_t pixels = static_cast<size_t>(image.width) * static_cast<size_t>(image.height);
  if (image.width <= 0 || image.height <= 0 || image.radiance.size() != pixels * nBands ||
      image.rgb.size() != pixels * 3 ||
      (!image.sampleCount.empty() && image.sampleCount.size() != pixels) ||
      (!image.xyz.empty() && image.xyz.size() != pixels * 3) ||
      (!image.bandVariance.empty() && image.bandVariance.size() != pixels * nBands) ||
      (!image.yVariance.empty() && image.yVariance.size() != pixels) ||
      (!image.white.empty() && image.white.size() != pixels * nBands) ||
      (!image.objectId.empty() && image.objectId.size() != pixels) ||
      (!image.materialId.empty() && image.materialId.size() != pixels) ||
      (!image.depth.empty() && image.depth.size() != pixels) ||
      std::any_of(image.layers.begin(), image.layers.end(),
                  [&](const ImageLayer& l) {
                    return l.values.size() != pixels * nBands ||
                           (!l.variances.empty() && l.variances.size() != pixels * nBands) ||
                           l.name.empty() || l.name.find(',') != std::string::npos;
                  }) ||
      std::any_of(image.aovs.begin(), image.aovs.end(),
                  [&](const AovImageLayer& l) {
                    const auto k = aovKindNamed(l.name);
                    return !k || l.values.size() != pixels * static_cast<size_t>(aovChannelCount(
                                                                 *k, image.bands.count()));
                  }) ||
      image.relight.values.size() !=
          image.relight.sources.size() * image.relight.entries.size() * pixels ||
      image.relight.halfDifferences.size() != image.relight.values.size() ||
      image.relight.spectra.size() != image.relight.sources.size() || image.originX < 0 ||
      image.originY < 0 || image.originX + image.width > image.displayWidth() ||
      image.originY + image.height > image.displayHeight())
    throw Error(path + ": internal error: image buffers do not match its size");
  checkExrOutputName(path);
  checkFiniteValues(path, image);

  // The names a caller gives (Python's attributes) are checked before anything is written;
  // those derived from them again as they are inserted.
  for (const auto& [key, value] : image.attributes) checkExrName(path, key, "attribute");
  writeAtomically(path, [&](const std::string& temp) {
    const Imath::Box2i display({0, 0}, {image.displayWidth() - 1, image.displayHeight() - 1});
    const Imath::Box2i data({image.originX, image.originY},
                            {image.originX + image.width - 1, image.originY + image.height - 1});
    Imf::Header header(display, data);
    // ExrCompression lists OpenEXR's methods in the file format's order.
    header.compression() = static_cast<Imf::Compression>(
        encoding.compression.value_or(defaultExrCompression(stored == Imf::HALF)));
    if (encoding.zipLevel < 1 || encoding.zipLevel > 9)
      throw Error(path + ": expected a zip level from 1 to 9, found " +
                  std::to_string(encoding.zipLevel));
    header.zipCompressionLevel() = encoding.zipLevel;
    // OpenEXR cuts names beyond 255 bytes without a word (two long names then share one
    // channel): every name is checked before it is inserted.
    std::set<std::string> channelNames;
    auto insertAttribute = [&](const std::string& key, const std::string& value) {
      checkExrName(path, key, "attribute");
      header.insert(key, Imf::StringAttribute(value));
    };
    insertAttribute("spectralLayoutVersion", "1.0");
    insertAttribute("emissiveUnits", "W.m^-2.sr^-1");
    for (const auto& [key, value] : image.attributes) insertAttribute(key, value);
    // What each band is, beside the wavelength its channel is named by: its own name (a
    // measured sensor's band list), centroid and FWHM, comma-separated in channel order.
    for (const auto& [key, value] : bandAttributes(image.bands)) insertAttribute(key, value);
    if (!image.layers.empty()) {
      std::string names;
      for (const ImageLayer& l : image.layers) names += (names.empty() ? "" : ",") + l.name;
      insertAttribute(kComponentLayersAttribute, names);
    }
    if (!image.aovs.empty()) {
      std::string names;
      for (const AovImageLayer& l : image.aovs) names += (names.empty() ? "" : ",") + l.name;
      insertAttribute(kAovLayersAttribute, names);
    }
    if (image.relight.present())
      for (const auto& [key, value] : relightAttributes(image.relight)) insertAttribute(key, value);

    Imf::FrameBuffer fb;
    // A float channel: `first` is its value in the first pixel, `stride` floats apart. Half
    // channels get converted copies (OpenEXR converts half to float when reading, not float to
    // half when writing).
    std::vector<std::vector<half>> halves;
    size_t aovChannels = 0;
    for (const AovImageLayer& l : image.aovs)
      aovChannels += static_cast<size_t>(aovChannelCount(*aovKindNamed(l.name), nBands));
    halves.reserve((2 + 2 * image.layers.size()) * static_cast<size_t>(nBands) + 8 + aovChannels +
                   2 * image.relight.sources.size() * image.relight.entries.size());
    auto addChannel = [&](const std::string& name, const float* first, size_t stride) {
      checkExrName(path, name, "channel");
      if (!channelNames.insert(name).second)
        throw Error(path + ": expected distinct channel names, found '" + name + "' twice");
      header.channels().insert(name, Imf::Channel(stored));
      if (stored == Imf::FLOAT) {
        fb.insert(name, Imf::Slice::Make(Imf::FLOAT, first, data, sizeof(float) * stride,
                                         sizeof(float) * stride * image.width));
        return;
      }
      std::vector<half>& h = halves.emplace_back(pixels);
      for (size_t p = 0; p < pixels; ++p) h[p] = half(first[p * stride]);
      fb.insert(name, Imf::Slice::Make(Imf::HALF, h.data(), data, sizeof(half),
                                       sizeof(half) * image.width));
    };
    const size_t nb = static_cast<size_t>(nBands);
    for (int b = 0; b < nBands; ++b)
      addChannel(spectralChannelName(image.bands.channelNm(b)), image.radiance.data() + b, nb);
    const char* rgbNames[3] = {"R", "G", "B"};
    for (int c = 0; c < 3; ++c) addChannel(rgbNames[c], image.rgb.data() + c, 3);
    const char* xyzNames[3] = {"X", "Y", "Z"};
    for (int c = 0; c < 3 && !image.xyz.empty(); ++c)
      addChannel(xyzNames[c], image.xyz.data() + c, 3);
    for (int b = 0; b < nBands && !image.bandVariance.empty(); ++b)
      addChannel(kVariancePrefix + spectralChannelName(image.bands.channelNm(b)),
                 image.bandVariance.data() + b, nb);
    if (!image.yVariance.empty())
      addChannel(std::string(kVariancePrefix) + "Y", image.yVariance.data(), 1);
    for (int b = 0; b < nBands && !image.white.empty(); ++b)
      addChannel(kWhitePrefix + spectralChannelName(image.bands.channelNm(b)),
                 image.white.data() + b, nb);
    if (!image.depth.empty()) addChannel(kDepthChannel, image.depth.data(), 1);
    for (const ImageLayer& l : image.layers)
      for (int b = 0; b < nBands; ++b) {
        const std::string channel = l.name + "." + spectralChannelName(image.bands.channelNm(b));
        addChannel(channel, l.values.data() + b, nb);
        if (!l.variances.empty()) addChannel(kVariancePrefix + channel, l.variances.data() + b, nb);
      }
    for (const AovImageLayer& l : image.aovs) {
      const std::vector<std::string> channels = aovChannelNames(*aovKindNamed(l.name), image.bands);
      for (size_t c = 0; c < channels.size(); ++c)
        addChannel(l.name + "." + channels[c], l.values.data() + c, channels.size());
    }
    if (image.relight.present()) {
      std::vector<std::string> bandChannels;
      for (int b = 0; b < nBands; ++b)
        bandChannels.push_back(spectralChannelName(image.bands.channelNm(b)));
      const std::vector<std::string> bandText = bandWavelengthTexts(bandChannels);
      const RelightLayers& rl = image.relight;
      for (size_t g = 0; g < rl.sources.size(); ++g)
        for (size_t e = 0; e < rl.size(); ++e) {
          const std::string channel = relightChannelName(rl, g, e, bandText);
          const size_t plane = (g * rl.size() + e) * pixels;
          addChannel(channel, rl.values.data() + plane, 1);
          addChannel(kHalfDifferencePrefix + channel, rl.halfDifferences.data() + plane, 1);
        }
    }
    auto addUint = [&](const char* name, const std::vector<uint32_t>& v) {
      if (v.empty()) return;
      header.channels().insert(name, Imf::Channel(Imf::UINT));
      fb.insert(name, Imf::Slice::Make(Imf::UINT, v.data(), data, sizeof(uint32_t),
                                       sizeof(uint32_t) * image.width));
    };
    addUint(kSampleCountChannel, image.sampleCount);
    addUint(kObjectIdChannel, image.objectId);
    addUint(kMaterialIdChannel, image.materialId);
    // Compress line blocks on as many threads as the render may use (the zlib compression
    // of ~70 float channels otherwise takes longer than a short render), but with one line
    // buffer where a chunk is huge (exr_write_cost.h counts the same).
    double channels = 0;
    for (auto it = header.channels().begin(); it != header.channels().end(); ++it) ++channels;
    const int threads =
        exrWriterThreads(exrChunkLines(static_cast<ExrCompression>(header.compression())) *
                         image.width * (stored == Imf::HALF ? 2.0 : 4.0) * channels);
    if (Imf::globalThreadCount() != threads) Imf::setGlobalThreadCount(threads);
    Imf::OutputFile file(temp.c_str(), header, threads);
    file.setFrameBuffer(fb);
    file.writePixels(image.height);
  });
}
} // namespace

SpectralImage readSpectralExr(const std::string& path) {
  requireRegularFile(path, kMaxExrFileBytes, "EXR file");
  // The header as declared, checked before OpenEXR allocates by it: the pixels read (every
  // channel as 4 bytes, and the RGB computed for a file without one) and OpenEXR's own line
  // buffers must fit in memory, so a small file declaring a huge image is refused with figures.
  const ExrHeaderSummary declared = checkExrHeader(path);
  requireMemory(static_cast<double>(declared.dataWidth) * static_cast<double>(declared.dataHeight) *
                        (declared.channels + 3) * 4.0 +
                    2 * declared.lineBytes * declared.chunkLines,
                path, "an EXR",
                std::to_string(declared.dataWidth) + " x " + std::to_string(declared.dataHeight) +
                    " pixels of " + std::to_string(declared.channels) + " channels");
  try {
    Imf::InputFile file(path.c_str());
    const Imf::Header& h = file.header();
    SpectralImage img;
    img.sourceFiles = {path};
    const Imath::Box2i dw = h.dataWindow(), disp = h.displayWindow();
    if (disp.min.x != 0 || disp.min.y != 0)
      throw Error(path + ": expected a display window starting at 0,0");
    img.fullWidth = disp.max.x + 1;
    img.fullHeight = disp.max.y + 1;
    img.originX = dw.min.x;
    img.originY = dw.min.y;
    // The data window must be a non-empty part of the display window (a crop of the image):
    // every reader and nxmerge index the full image by it.
    if (dw.min.x < 0 || dw.min.y < 0 || dw.max.x > disp.max.x || dw.max.y > disp.max.y ||
        dw.max.x < dw.min.x || dw.max.y < dw.min.y)
      throw Error(path + ": expected a data window inside the display window 0,0-" +
                  std::to_string(disp.max.x) + "," + std::to_string(disp.max.y) + ", found " +
                  std::to_string(dw.min.x) + "," + std::to_string(dw.min.y) + "-" +
                  std::to_string(dw.max.x) + "," + std::to_string(dw.max.y));
    img.width = dw.max.x - dw.min.x + 1;
    img.height = dw.max.y - dw.min.y + 1;
    for (auto it = h.begin(); it != h.end(); ++it)
      if (const auto* s = dynamic_cast<const Imf::StringAttribute*>(&it.attribute()))
        img.attributes[it.name()] = s->value();
    img.attributes.erase("spectralLayoutVersion");
    img.attributes.erase("emissiveUnits");
    for (const char* key : kBandAttributeKeys) img.attributes.erase(key);
    // This project's files name their bands (a sensor's responses) in nxrender.bands; other
    // files of the layout are read by their channel names.
    std::vector<std::string> bandChannels;
    const auto bandsAttr = img.attributes.find("nxrender.bands");
    if (bandsAttr != img.attributes.end()) {
      img.bands = Sensor::parse(bandsAttr->second, path + ": nxrender.bands");
      // Named by the nominal centre (the SRF's band list) or, in files written before
      // channels kept it, by the centroid.
      for (int b = 0; b < img.bands.count(); ++b) {
        const std::string nominal = spectralChannelName(img.bands.channelNm(b));
        const std::string centroid = spectralChannelName(img.bands.centroid(b));
        bandChannels.push_back(h.channels().findChannel(nominal)    ? nominal
                               : h.channels().findChannel(centroid) ? centroid
                                                                    : nominal);
      }
    } else {
      std::vector<std::string> names;
      for (auto it = h.channels().begin(); it != h.channels().end(); ++it)
        names.push_back(it.name());
      std::string kind;
      const std::vector<FichetChannel> found = fichetSpectralChannels(names, kind);
      if (found.empty())
        throw Error(path + ": expected spectral channels named S0.<wavelength><unit> or "
                           "T.<wavelength><unit> (Fichet et al. 2021), found none");
      std::vector<double> nm;
      for (const FichetChannel& c : found) {
        nm.push_back(c.nm);
        bandChannels.push_back(c.name);
      }
      img.bands = sensorAtWavelengths(nm, path);
      img.attributes["nxrender.spectralChannels"] = kind;
    }
    const int nb = img.bands.count();
    for (int b = 0; b < nb; ++b)
      if (!h.channels().findChannel(bandChannels[static_cast<size_t>(b)]))
        throw Error(path + ": expected a channel " + bandChannels[static_cast<size_t>(b)] +
                    ", found none");
    const size_t pixels = static_cast<size_t>(img.width) * img.height;
    img.radiance.assign(pixels * nb, 0.0f);
    img.rgb.assign(pixels * 3, 0.0f);
    Imf::FrameBuffer fb;
    for (int b = 0; b < nb; ++b)
      fb.insert(bandChannels[static_cast<size_t>(b)],
                Imf::Slice::Make(Imf::FLOAT, img.radiance.data() + b, dw, sizeof(float) * nb,
                                 sizeof(float) * nb * img.width));
    const char* rgbNames[3] = {"R", "G", "B"};
    const bool haveRgb = h.channels().findChannel("R") && h.channels().findChannel("G") &&
                         h.channels().findChannel("B");
    for (int c = 0; c < 3 && haveRgb; ++c)
      fb.insert(rgbNames[c], Imf::Slice::Make(Imf::FLOAT, img.rgb.data() + c, dw, sizeof(float) * 3,
                                              sizeof(float) * 3 * img.width));
    const char* xyzNames[3] = {"X", "Y", "Z"};
    if (h.channels().findChannel("X") && h.channels().findChannel("Y") &&
        h.channels().findChannel("Z")) {
      img.xyz.assign(pixels * 3, 0.0f);
      for (int c = 0; c < 3; ++c)
        fb.insert(xyzNames[c], Imf::Slice::Make(Imf::FLOAT, img.xyz.data() + c, dw,
                                                sizeof(float) * 3, sizeof(float) * 3 * img.width));
    }
    if (h.channels().findChannel(kVariancePrefix + bandChannels[0])) {
      img.bandVariance.assign(pixels * nb, 0.0f);
      for (int b = 0; b < nb; ++b)
        fb.insert(kVariancePrefix + bandChannels[static_cast<size_t>(b)],
                  Imf::Slice::Make(Imf::FLOAT, img.bandVariance.data() + b, dw, sizeof(float) * nb,
                                   sizeof(float) * nb * img.width));
    }
    if (h.channels().findChannel(std::string(kVariancePrefix) + "Y")) {
      img.yVariance.assign(pixels, 0.0f);
      fb.insert(std::string(kVariancePrefix) + "Y",
                Imf::Slice::Make(Imf::FLOAT, img.yVariance.data(), dw, sizeof(float),
                                 sizeof(float) * img.width));
    }
    if (h.channels().findChannel(kWhitePrefix + bandChannels[0])) {
      img.white.assign(pixels * nb, 0.0f);
      for (int b = 0; b < nb; ++b)
        fb.insert(kWhitePrefix + bandChannels[static_cast<size_t>(b)],
                  Imf::Slice::Make(Imf::FLOAT, img.white.data() + b, dw, sizeof(float) * nb,
                                   sizeof(float) * nb * img.width));
    }
    // Ground-truth layers: the channels of each kind the attribute names, each one required.
    if (const auto it = img.attributes.find(kAovLayersAttribute); it != img.attributes.end()) {
      std::string rest = it->second;
      img.attributes.erase(it);
      while (!rest.empty()) {
        const size_t comma = rest.find(',');
        const std::string name = rest.substr(0, comma);
        rest = comma == std::string::npos ? "" : rest.substr(comma + 1);
        const auto kind = aovKindNamed(name);
        if (!kind)
          throw Error(path + ": expected ground-truth layers named as nxrender names them in " +
                      kAovLayersAttribute + ", found '" + name + "'");
        AovImageLayer& l = img.aovs.emplace_back();
        l.name = name;
        const std::vector<std::string> channels = aovChannelNames(*kind, img.bands);
        l.values.assign(pixels * channels.size(), 0.0f);
        for (size_t c = 0; c < channels.size(); ++c) {
          const std::string channel = name + "." + channels[c];
          if (!h.channels().findChannel(channel))
            throw Error(path + ": expected a channel " + channel + " (" + kAovLayersAttribute +
                        " lists the layer " + name + "), found none");
          fb.insert(channel, Imf::Slice::Make(Imf::FLOAT, l.values.data() + c, dw,
                                              sizeof(float) * channels.size(),
                                              sizeof(float) * channels.size() * img.width));
        }
      }
    }
    // Component layers: the channels the attribute names, each one required.
    if (const auto it = img.attributes.find(kComponentLayersAttribute);
        it != img.attributes.end()) {
      std::string rest = it->second;
      img.attributes.erase(it);
      while (!rest.empty()) {
        const size_t comma = rest.find(',');
        ImageLayer& l = img.layers.emplace_back();
        l.name = rest.substr(0, comma);
        rest = comma == std::string::npos ? "" : rest.substr(comma + 1);
      }
      for (ImageLayer& l : img.layers) {
        const bool variances =
            h.channels().findChannel(kVariancePrefix + l.name + "." + bandChannels[0]) != nullptr;
        l.values.assign(pixels * nb, 0.0f);
        if (variances) l.variances.assign(pixels * nb, 0.0f);
        for (int b = 0; b < nb; ++b) {
          const std::string channel = l.name + "." + bandChannels[static_cast<size_t>(b)];
          if (!h.channels().findChannel(channel))
            throw Error(path + ": expected a channel " + channel + " (" +
                        kComponentLayersAttribute + " lists the layer " + l.name + "), found none");
          fb.insert(channel, Imf::Slice::Make(Imf::FLOAT, l.values.data() + b, dw,
                                              sizeof(float) * nb, sizeof(float) * nb * img.width));
          if (!variances) continue;
          if (!h.channels().findChannel(kVariancePrefix + channel))
            throw Error(path + ": expected a channel " + kVariancePrefix + channel +
                        " (the layer's other bands have variances), found none");
          fb.insert(kVariancePrefix + channel,
                    Imf::Slice::Make(Imf::FLOAT, l.variances.data() + b, dw, sizeof(float) * nb,
                                     sizeof(float) * nb * img.width));
        }
      }
    }
    // The transport of a relightable render: planes per group and entry.
    std::vector<std::string> relightChannels;
    {
      std::vector<std::string> names;
      for (auto it = h.channels().begin(); it != h.channels().end(); ++it)
        names.push_back(it.name());
      relightChannels = parseRelightChannels(img.attributes, names,
                                             bandWavelengthTexts(bandChannels), path, img.relight);
      img.relight.values.assign(relightChannels.size() * pixels, 0.0f);
      img.relight.halfDifferences.assign(relightChannels.size() * pixels, 0.0f);
      for (size_t k = 0; k < relightChannels.size(); ++k) {
        fb.insert(relightChannels[k],
                  Imf::Slice::Make(Imf::FLOAT, img.relight.values.data() + k * pixels, dw,
                                   sizeof(float), sizeof(float) * img.width));
        fb.insert(kHalfDifferencePrefix + relightChannels[k],
                  Imf::Slice::Make(Imf::FLOAT, img.relight.halfDifferences.data() + k * pixels, dw,
                                   sizeof(float), sizeof(float) * img.width));
      }
    }
    if (h.channels().findChannel(kDepthChannel)) {
      img.depth.assign(pixels, 0.0f);
      fb.insert(kDepthChannel, Imf::Slice::Make(Imf::FLOAT, img.depth.data(), dw, sizeof(float),
                                                sizeof(float) * img.width));
    }
    auto readUint = [&](const char* name, const char* what, std::vector<uint32_t>& v) {
      const Imf::Channel* c = h.channels().findChannel(name);
      if (!c) return;
      if (c->type != Imf::UINT)
        throw Error(path + ": expected the " + std::string(name) +
                    " channel as 32-bit unsigned integers (" + what + "), found " +
                    (c->type == Imf::HALF ? "half floats" : "floats"));
      v.assign(pixels, 0);
      fb.insert(name, Imf::Slice::Make(Imf::UINT, v.data(), dw, sizeof(uint32_t),
                                       sizeof(uint32_t) * img.width));
    };
    readUint(kSampleCountChannel, "sample counts", img.sampleCount);
    readUint(kObjectIdChannel, "object ids", img.objectId);
    readUint(kMaterialIdChannel, "material ids", img.materialId);
    file.setFrameBuffer(fb);
    file.readPixels(dw.min.y, dw.max.y);
    checkRelightValues(img.relight, relightChannels, img.width, img.height, path);
    if (!haveRgb) {
      // A file without an RGB preview: colour from its bands.
      std::vector<double> nm;
      for (int b = 0; b < nb; ++b) nm.push_back(img.bands.centroid(b));
      std::vector<float> xyz;
      BandColour(nm).fill(img.radiance, xyz, img.rgb);
    }
    return img;
  } catch (const Error&) {
    throw;
  } catch (const std::exception& e) {
    throw Error(path + ": cannot read the EXR file: " + e.what());
  }
}

ExrFootprint spectralExrFootprint(const std::string& path) {
  requireRegularFile(path, kMaxExrFileBytes, "EXR file");
  const ExrHeaderSummary h = checkExrHeader(path); // the header alone, without OpenEXR
  ExrFootprint f;
  f.channels = h.channels;
  f.displayPixels = static_cast<double>(h.displayWidth) * static_cast<double>(h.displayHeight);
  f.dataPixels = static_cast<double>(h.dataWidth) * static_cast<double>(h.dataHeight);
  return f;
}

} // namespace nx
