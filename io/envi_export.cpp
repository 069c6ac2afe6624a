#include "io/envi_export.h"

#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <functional>
#include <mutex>
#include <vector>

#include "core/error.h"
#include "core/number_text.h"
#include "io/atomic_file.h"
#include "io/gdal_library.h"

namespace nx {
namespace {

// "{a, b, c}": an ENVI list.
std::string enviList(int n, const std::function<std::string(int)>& item) {
  std::string out = "{";
  for (int i = 0; i < n; ++i) out += (i ? ", " : "") + item(i);
  return out + "}";
}

std::string lastGdalError() {
  const char* m = gdal().CPLGetLastErrorMsg();
  return m && *m ? m : "unknown GDAL error";
}

} // namespace

std::string enviHeaderPath(const std::string& dataPath) {
  return std::filesystem::path(dataPath).replace_extension(".hdr").string();
}

void checkEnviOutputName(const std::string& dataPath) {
  if (enviHeaderPath(dataPath) == dataPath)
    throw Error(dataPath +
                ": expected an ENVI data file name with an extension other than .hdr "
                "(e.g. .img), found '" +
                dataPath + "'");
  checkWritable(dataPath);
  checkWritable(enviHeaderPath(dataPath));
}

void writeEnvi(const std::string& dataPath, const SpectralImage& image) {
  static std::once_flag registered;
  std::call_once(registered, [] { gdal().GDALRegister_ENVI(); });
  const Sensor& sensor = image.bands;
  const int nb = sensor.count(), w = image.width, h = image.height;
  checkEnviOutputName(dataPath);
  const std::string hdrPath = enviHeaderPath(dataPath);
  refuseOverwritingASource(dataPath, image);
  refuseOverwritingASource(hdrPath, image);
  // Written under temporary names in the target's directory (with the data file's
  // extension, so that GDAL names the header alike), then renamed: header, then data.
  const std::filesystem::path target(dataPath);
  const std::string stem = ".nxtmp-envi-" + std::to_string(static_cast<long>(getpid())) + "-" +
                           target.stem().string().substr(0, 64);
  const std::string tempData =
                        (target.parent_path() / (stem + target.extension().string())).string(),
                    tempHdr = enviHeaderPath(tempData);
  auto cleanUp = [&] {
    std::remove(tempData.c_str());
    std::remove(tempHdr.c_str());
    std::remove((tempData + ".aux.xml").c_str());
  };
  GDALDriverH driver = gdal().GDALGetDriverByName("ENVI");
  if (!driver) throw Error(dataPath + ": GDAL has no ENVI driver");
  char** options = gdal().CSLSetNameValue(nullptr, "INTERLEAVE", "BSQ");
  GDALDatasetH ds = gdal().GDALCreate(driver, tempData.c_str(), w, h, nb, GDT_Float32, options);
  gdal().CSLDestroy(options);
  if (!ds) {
    cleanUp();
    throw Error(dataPath + ": cannot create the ENVI cube: " + lastGdalError());
  }
  bool ok = true;
  std::vector<float> plane(static_cast<size_t>(w) * static_cast<size_t>(h));
  for (int b = 0; b < nb && ok; ++b) {
    for (size_t i = 0; i < plane.size(); ++i)
      plane[i] = image.radiance[i * static_cast<size_t>(nb) + static_cast<size_t>(b)];
    GDALRasterBandH band = gdal().GDALGetRasterBand(ds, b + 1);
    const std::string desc = fixedText(sensor.channelNm(b), 6) + " nm";
    gdal().GDALSetDescription(band, desc.c_str());
    ok = gdal().GDALRasterIO(band, GF_Write, 0, 0, w, h, plane.data(), w, h, GDT_Float32, 0, 0) ==
         CE_None;
  }
  const auto number = [](double v) { return exactNumberText(v); };
  gdal().GDALSetMetadataItem(ds, "wavelength units", "Nanometers", "ENVI");
  gdal().GDALSetMetadataItem(
      ds, "wavelength", enviList(nb, [&](int b) { return number(sensor.channelNm(b)); }).c_str(),
      "ENVI");
  gdal().GDALSetMetadataItem(
      ds, "fwhm", enviList(nb, [&](int b) { return number(sensor.fwhm(b)); }).c_str(), "ENVI");
  // The ENVI driver writes the dataset's description (by default its file name, here a
  // temporary one) as the header's "description".
  gdal().GDALSetDescription(ds, ("nxrender render: spectral radiance (W m^-2 sr^-1 nm^-1) averaged "
                                 "over each band's response; " +
                                 sensor.summary())
                                    .c_str());
  gdal().CPLErrorReset();
  gdal().GDALClose(ds); // void in GDAL 3.6: a failed flush shows in the last error
  if (!ok || gdal().CPLGetLastErrorType() >= CE_Failure) {
    const std::string why = lastGdalError();
    cleanUp();
    throw Error(dataPath + ": cannot write the ENVI cube: " + why);
  }
  std::error_code ec;
  std::filesystem::rename(tempHdr, hdrPath, ec);
  if (!ec) std::filesystem::rename(tempData, dataPath, ec);
  std::remove((tempData + ".aux.xml").c_str());
  if (ec) {
    cleanUp();
    throw Error(dataPath + ": cannot move the ENVI cube into place: " + ec.message());
  }
}

} // namespace nx
