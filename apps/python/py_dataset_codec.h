#pragma once
// Decoding a dataset item's arrays in the library (nxrender.dataset's format, docs/datasets.md):
// a float16 array (its bits scaled by 2^k) as two zstd frames per chunk of values, its low
// bytes' (or their packed high nibbles') and its high bytes'; one frame of raw uint32 / float32
// values for the others. Decoded chunk by chunk in parallel without the GIL, the derived layers
// subtracted while the chunk is in the cache.

#include <pybind11/pybind11.h>

namespace nxpy {

/// Adds nxrender._decode_arrays(blobs, specs, differences) to the module.
void bindDatasetCodec(pybind11::module_& m);

} // namespace nxpy
