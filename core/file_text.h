#pragma once
// Reading an input file whole, safely: regular files only, size checked before reading.

#include <cstdint>
#include <string>

namespace nx {

/// Checks, without opening it, that `path` is a regular file of at most maxBytes bytes: the
/// same refusals as readRegularFile (missing, directory, FIFO, socket, device, too large). For
/// inputs that a library opens itself (EXR, TIFF, ENVI): a FIFO never reaches the library.
/// The file is noted as an input (core/input_files.h): no output may replace it.
void requireRegularFile(const std::string& path, std::uintmax_t maxBytes, const std::string& what);

/// The content of the regular file at `path`, of at most maxBytes bytes. `what` names the
/// kind of file in errors ("scene file", "table"). Refused with an nx::Error naming the file:
/// a missing or unreadable file ("cannot open the <what>"), a directory, FIFO, socket or
/// device ("expected a <what>, found a directory" / "... found a FIFO or device"), a file over
/// the limit (checked before reading, and the read itself stops at the limit, so a file that
/// grows or lies about its size cannot exhaust memory).
std::string readRegularFile(const std::string& path, std::uintmax_t maxBytes,
                            const std::string& what);

} // namespace nx
