#include "io/float_tiff.h"

#include <cmath>
#include <mutex>

#include "core/error.h"
#include "io/atomic_file.h"
#include "io/gdal_library.h"

namespace nx {

void writeFloatTiff(const std::string& path, int width, int height,
                    const std::vector<float>& values, const std::string& description) {
  if (values.size() != static_cast<size_t>(width) * static_cast<size_t>(height))
    throw Error(path + ": expected " + std::to_string(width) + " x " + std::to_string(height) +
                " values, found " + std::to_string(values.size()));
  static std::once_flag registered;
  std::call_once(registered, [] { gdal().GDALRegister_GTiff(); });
  writeAtomically(path, [&](const std::string& tmp) {
    gdal().CPLErrorReset();
    GDALDatasetH ds = gdal().GDALCreate(gdal().GDALGetDriverByName("GTiff"), tmp.c_str(), width,
                                        height, 1, GDT_Float32, nullptr);
    if (!ds) throw Error(tmp + ": cannot create the TIFF: " + gdal().CPLGetLastErrorMsg());
    GDALRasterBandH band = gdal().GDALGetRasterBand(ds, 1);
    gdal().GDALSetDescription(band, description.c_str());
    gdal().GDALSetRasterNoDataValue(band, std::nan(""));
    const CPLErr err =
        gdal().GDALRasterIO(band, GF_Write, 0, 0, width, height, const_cast<float*>(values.data()),
                            width, height, GDT_Float32, 0, 0);
    gdal().GDALClose(ds);
    if (err != CE_None || gdal().CPLGetLastErrorType() >= CE_Failure)
      throw Error(tmp + ": cannot write the TIFF: " + gdal().CPLGetLastErrorMsg());
  });
}

} // namespace nx
