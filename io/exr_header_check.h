#pragma once
// The structure of an OpenEXR header, checked before OpenEXR reads it: the library allocates
// what an attribute declares, so a 1 KB file declaring a 2 GB attribute took 2 GB and 5 s.

#include <string>

namespace nx {

/// Throws nx::Error "<path>: expected ..., found ..." unless the file starts with the OpenEXR
/// magic number and version 2, and every header attribute (of every part of a multi-part file)
/// has a name and type of at most 255 bytes and a size that fits in the rest of the file.
/// Reads the header only (it seeks past every attribute value).
void checkExrHeader(const std::string& path);

} // namespace nx
