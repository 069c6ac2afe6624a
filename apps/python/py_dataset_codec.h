#pragma once
// Decoding a dataset item's arrays in the library (nxrender.dataset's format, docs/datasets.md):
// two zstd frames per float16 array (its bits' low and high bytes, scaled by 2^k), one of raw
// uint32 / float32 values for the others,
// decoded in parallel without the GIL. Python's zstd and numpy conversions took 6 ms of an
// item's 6.5.

#include <pybind11/pybind11.h>

namespace nxpy {

/// Adds nxrender._decode_arrays(blobs, specs) to the module.
void bindDatasetCodec(pybind11::module_& m);

} // namespace nxpy
