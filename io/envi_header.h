#pragma once
// The fields of an ENVI header that decide how its data file is read, checked before GDAL
// sees the file: GDAL reads unknown values of them as defaults (an interleave of "xyz" as BSQ,
// a byte order of 7 as big-endian), which would silently scramble a cube.

#include <string>

namespace nx {

/// Reads the ENVI header at `headerPath` through the bounded reader and throws nx::Error
/// "<header>:<line>: expected ..., found ..." unless it starts with "ENVI", every line is
/// `key = value` (values in braces may span lines), and the fields GDAL would otherwise
/// default hold values it reads as written: interleave bsq|bil|bip, byte order 0|1, data type
/// one of ENVI's real types (1, 2, 3, 4, 5, 12, 13, 14, 15), samples, lines and bands whole
/// numbers of at least 1, header offset a whole number of bytes within `dataBytes` (the data
/// file's size).
void checkEnviHeader(const std::string& headerPath, double dataBytes);

} // namespace nx
