#include "io/gdal_library.h"

#include <dlfcn.h>

#include <mutex>
#include <string>
#include <type_traits>

#include "core/error.h"

#ifndef NX_GDAL_SONAME
#error "NX_GDAL_SONAME (the GDAL library's file name) must be defined by the build"
#endif

namespace nx {
namespace {

GdalLibrary load() {
  // RTLD_LOCAL: GDAL's symbols stay out of the global namespace (nothing else links them).
  void* handle = dlopen(NX_GDAL_SONAME, RTLD_NOW | RTLD_LOCAL);
  if (!handle)
    throw Error(std::string("cannot load the GDAL library " NX_GDAL_SONAME
                            " (needed for ENVI and TIFF rasters): ") +
                dlerror());
  GdalLibrary lib{};
  auto resolve = [&](auto& member, const char* name) {
    void* p = dlsym(handle, name);
    if (!p) throw Error(std::string("the GDAL library " NX_GDAL_SONAME " has no function ") + name);
    member = reinterpret_cast<std::remove_reference_t<decltype(member)>>(p);
  };
#define NX_GDAL_RESOLVE(f) resolve(lib.f, #f)
  NX_GDAL_RESOLVE(CPLErrorReset);
  NX_GDAL_RESOLVE(CPLGetLastErrorMsg);
  NX_GDAL_RESOLVE(CPLGetLastErrorType);
  NX_GDAL_RESOLVE(CPLPushErrorHandler);
  NX_GDAL_RESOLVE(CPLPopErrorHandler);
  NX_GDAL_RESOLVE(CPLQuietErrorHandler);
  NX_GDAL_RESOLVE(CSLDestroy);
  NX_GDAL_RESOLVE(CSLSetNameValue);
  NX_GDAL_RESOLVE(GDALClose);
  NX_GDAL_RESOLVE(GDALCreate);
  NX_GDAL_RESOLVE(GDALDataTypeIsComplex);
  NX_GDAL_RESOLVE(GDALGetDataTypeName);
  NX_GDAL_RESOLVE(GDALGetDataTypeSizeBytes);
  NX_GDAL_RESOLVE(GDALGetDriverByName);
  NX_GDAL_RESOLVE(GDALGetMetadataItem);
  NX_GDAL_RESOLVE(GDALGetRasterBand);
  NX_GDAL_RESOLVE(GDALGetRasterCount);
  NX_GDAL_RESOLVE(GDALGetRasterDataType);
  NX_GDAL_RESOLVE(GDALGetRasterXSize);
  NX_GDAL_RESOLVE(GDALGetRasterYSize);
  NX_GDAL_RESOLVE(GDALOpenEx);
  NX_GDAL_RESOLVE(GDALRasterIO);
  NX_GDAL_RESOLVE(GDALRegister_ENVI);
  NX_GDAL_RESOLVE(GDALRegister_GTiff);
  NX_GDAL_RESOLVE(GDALSetDescription);
  NX_GDAL_RESOLVE(GDALSetMetadataItem);
  NX_GDAL_RESOLVE(GDALSetRasterNoDataValue);
#undef NX_GDAL_RESOLVE
  return lib; // the handle stays open for the life of the process
}

} // namespace

const GdalLibrary& gdal() {
  static const GdalLibrary lib = load(); // a failed load throws and is tried again next time
  return lib;
}

} // namespace nx
