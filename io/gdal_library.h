#pragma once
// GDAL, loaded the first time a raster is read or written. Linking it would load the library
// and its hundred-odd dependencies at the start of every process (60 ms, most of nxrender's
// start-up), although only ENVI export and capture reading use it.

#include <cpl_error.h>
#include <cpl_string.h>
#include <gdal.h>
#include <gdal_frmts.h>

namespace nx {

/// The GDAL functions this project calls, resolved from the shared library; each member has
/// the function's own name and type.
struct GdalLibrary {
  decltype(&::CPLErrorReset) CPLErrorReset;
  decltype(&::CPLGetLastErrorMsg) CPLGetLastErrorMsg;
  decltype(&::CPLGetLastErrorType) CPLGetLastErrorType;
  decltype(&::CPLPushErrorHandler) CPLPushErrorHandler;
  decltype(&::CPLPopErrorHandler) CPLPopErrorHandler;
  decltype(&::CPLQuietErrorHandler) CPLQuietErrorHandler;
  decltype(&::CSLDestroy) CSLDestroy;
  decltype(&::CSLSetNameValue) CSLSetNameValue;
  decltype(&::GDALClose) GDALClose;
  decltype(&::GDALCreate) GDALCreate;
  decltype(&::GDALDataTypeIsComplex) GDALDataTypeIsComplex;
  decltype(&::GDALGetDataTypeName) GDALGetDataTypeName;
  decltype(&::GDALGetDataTypeSizeBytes) GDALGetDataTypeSizeBytes;
  decltype(&::GDALGetDriverByName) GDALGetDriverByName;
  decltype(&::GDALGetMetadataItem) GDALGetMetadataItem;
  decltype(&::GDALGetRasterBand) GDALGetRasterBand;
  decltype(&::GDALGetRasterCount) GDALGetRasterCount;
  decltype(&::GDALGetRasterDataType) GDALGetRasterDataType;
  decltype(&::GDALGetRasterXSize) GDALGetRasterXSize;
  decltype(&::GDALGetRasterYSize) GDALGetRasterYSize;
  decltype(&::GDALOpenEx) GDALOpenEx;
  decltype(&::GDALRasterIO) GDALRasterIO;
  decltype(&::GDALRegister_ENVI) GDALRegister_ENVI;
  decltype(&::GDALRegister_GTiff) GDALRegister_GTiff;
  decltype(&::GDALSetDescription) GDALSetDescription;
  decltype(&::GDALSetMetadataItem) GDALSetMetadataItem;
  decltype(&::GDALSetRasterNoDataValue) GDALSetRasterNoDataValue;
};

/// GDAL, loaded on the first call (thread-safe); throws nx::Error naming the library and the
/// loader's message when it or one of its functions cannot be found.
const GdalLibrary& gdal();

} // namespace nx
