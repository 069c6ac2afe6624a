#include "io/spectral_exr.h"

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfOutputFile.h>
#include <ImfStringAttribute.h>
#include <cstdio>

#include "core/error.h"
#include "io/atomic_file.h"

namespace nx {

std::string spectralChannelName(double nm) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "S0.%.6fnm", nm);
  std::string name = buf;
  name[name.find('.', 3)] = ',';
  return name;
}

void writeSpectralExr(const std::string& path, const SpectralImage& image) {
  const int nBands = image.bands.count();
  const size_t pixels = static_cast<size_t>(image.width) * static_cast<size_t>(image.height);
  if (image.width <= 0 || image.height <= 0 || image.radiance.size() != pixels * nBands ||
      image.rgb.size() != pixels * 3)
    throw Error(path + ": internal error: image buffers do not match its size");

  writeAtomically(path, [&](const std::string& temp) {
    Imf::Header header(image.width, image.height);
    header.compression() = Imf::ZIP_COMPRESSION;
    header.insert("spectralLayoutVersion", Imf::StringAttribute("1.0"));
    header.insert("emissiveUnits", Imf::StringAttribute("W.m^-2.sr^-1"));
    for (const auto& [key, value] : image.attributes)
      header.insert(key, Imf::StringAttribute(value));

    Imf::FrameBuffer fb;
    const size_t pixelStride = sizeof(float) * nBands;
    for (int b = 0; b < nBands; ++b) {
      const std::string name = spectralChannelName(image.bands.centre(b));
      header.channels().insert(name, Imf::Channel(Imf::FLOAT));
      fb.insert(name, Imf::Slice(Imf::FLOAT, (char*)(image.radiance.data() + b), pixelStride,
                                 pixelStride * image.width));
    }
    const char* rgbNames[3] = {"R", "G", "B"};
    for (int c = 0; c < 3; ++c) {
      header.channels().insert(rgbNames[c], Imf::Channel(Imf::FLOAT));
      fb.insert(rgbNames[c], Imf::Slice(Imf::FLOAT, (char*)(image.rgb.data() + c),
                                        sizeof(float) * 3, sizeof(float) * 3 * image.width));
    }
    Imf::OutputFile file(temp.c_str(), header);
    file.setFrameBuffer(fb);
    file.writePixels(image.height);
  });
}

} // namespace nx
