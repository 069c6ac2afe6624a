// nx-calibration-reader: the helper process in which nxrender reads OpenCV calibration files
// (io/isolated_call.h): OpenCV 4.6's reader loops forever or crashes on some malformed files,
// so it runs here, started by posix_spawn and killed after a time limit, never in the caller.
// Not for use on its own: it answers requests on descriptor 3.

#include <cstdio>
#include <cstring>

#include "io/isolated_call.h"
#include "io/opencv_calibration.h"

int main(int argc, char** argv) {
  if (argc != 2 || std::strcmp(argv[1], "--serve") != 0) {
    std::fprintf(stderr, "nx-calibration-reader: a helper process of nxrender, started by it "
                         "(it reads OpenCV calibration files); not for use on its own\n");
    return 2;
  }
  return nx::serveIsolatedRequests(3, nx::calibrationReaderWork);
}
