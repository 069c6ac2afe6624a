// Writes a small spectral EXR for command-line tests of the image tools: 4x3 pixels, bands
// 500:600:100, every value 1. `--nan` puts a NaN into the first band of pixel 0 (as another
// tool might: nxrender's writer refuses NaN, so the value is patched in with OpenEXR); `--huge`
// makes the 4x3 pixels a crop of a 200000x200000 image (a part whose merge cannot fit).
//
//   write_test_exr OUT.exr [--nan | --huge]
#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfHeader.h>
#include <ImfInputFile.h>
#include <ImfOutputFile.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <string>
#include <vector>

#include "io/spectral_exr.h"

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: write_test_exr OUT.exr [--nan | --huge]\n");
    return 2;
  }
  nx::SpectralImage img;
  img.width = 4;
  img.height = 3;
  img.bands = nx::SpectralBands::parse("500:600:100");
  const size_t pixels = 12;
  img.radiance.assign(pixels * 2, 1.0f);
  img.rgb.assign(pixels * 3, 1.0f);
  img.xyz.assign(pixels * 3, 1.0f);
  img.sampleCount.assign(pixels, 4);
  if (argc > 2 && std::string(argv[2]) == "--huge") img.fullWidth = img.fullHeight = 200000;
  img.attributes["nxrender.bands"] = img.bands.toString();
  img.attributes["nxrender.renderKey"] = "test";
  img.attributes["nxrender.seed"] = "0";
  img.attributes["nxrender.sampleRange"] = "0:4";
  nx::writeSpectralExr(argv[1], img);
  if (argc > 2 && std::string(argv[2]) == "--nan") {
    // Every channel read back as raw 4-byte words (floats and uints alike), the NaN put in,
    // and the same header and channels written again.
    Imf::InputFile in(argv[1]);
    const Imf::Header header = in.header();
    const Imath::Box2i dw = header.dataWindow();
    std::map<std::string, std::vector<uint32_t>> words;
    Imf::FrameBuffer fb;
    for (auto c = header.channels().begin(); c != header.channels().end(); ++c) {
      std::vector<uint32_t>& w = words[c.name()];
      w.assign(pixels, 0);
      fb.insert(c.name(), Imf::Slice::Make(c.channel().type, w.data(), dw, 4, 16));
    }
    in.setFrameBuffer(fb);
    in.readPixels(dw.min.y, dw.max.y);
    const float nan = NAN;
    std::memcpy(words.at(nx::spectralChannelName(500)).data(), &nan, 4);
    Imf::OutputFile out(argv[1], header);
    out.setFrameBuffer(fb);
    out.writePixels(3);
  }
  return 0;
}
