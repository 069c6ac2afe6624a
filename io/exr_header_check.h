#pragma once
// The structure of an OpenEXR header, checked before OpenEXR reads it: the library allocates
// what an attribute declares, so a 1 KB file declaring a 2 GB attribute took 2 GB and 5 s.

#include <cstdint>
#include <string>

namespace nx {

/// What the first header of an EXR declares, as checkExrHeader read it.
struct ExrHeaderSummary {
  int64_t dataWidth = 0, dataHeight = 0;       ///< the data window's size (pixels stored)
  int64_t displayWidth = 0, displayHeight = 0; ///< the display window's size
  int channels = 0;                            ///< channels in the channel list
  double lineBytes = 0;                        ///< bytes of one scan line of all channels
  int chunkLines = 1;                          ///< scan lines per chunk of its compression
};

/// Throws nx::Error "<path>: expected ..., found ..." unless the file starts with the OpenEXR
/// magic number and version 2, and every header attribute (of every part of a multi-part file)
/// has a name and type of at most 255 bytes and a size that fits in the rest of the file;
/// standard attributes have their type's size, channel lists, string vectors and previews fill
/// theirs exactly (OpenEXR reads those by content); the first header has a data window,
/// display window, a known compression and channels of known types and positive sampling
/// (what OpenEXR sizes its buffers by). Reads the header only.
ExrHeaderSummary checkExrHeader(const std::string& path);

} // namespace nx
