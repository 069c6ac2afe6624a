// nxrender._decode_arrays: an item's arrays from their zstd frames (docs/datasets.md).

#include "apps/python/py_dataset_codec.h"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <immintrin.h>
#include <malloc.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <zstd.h>

#include <array>
#include <cmath>
#include <cstring>
#include <string>
#include <utility>
#include <vector>

namespace nxpy {
namespace {

namespace py = pybind11;

// IEEE binary16 to binary32, exactly (subnormals, infinities and NaN included), by arithmetic:
// the half's exponent and mantissa bits moved into a float's place read as a float are its
// value times 2^-112 (subnormals too), so one multiply by 2^112 gives it exactly. (A table of
// the 65536 values was 2.5x slower: noisy values look it up all over its 256 KB.)
// Without branches, so that the loop over an array vectorises.
inline float halfToFloat(uint32_t h) {
  const uint32_t magnitude = h & 0x7fffu, sign = (h & 0x8000u) << 16;
  const uint32_t shifted = magnitude << 13;
  float v;
  std::memcpy(&v, &shifted, sizeof v);
  v *= 0x1p112f;
  uint32_t bits;
  std::memcpy(&bits, &v, sizeof bits);
  // infinity or NaN: the float's all-ones exponent with the half's mantissa
  bits = magnitude >= 0x7c00u ? 0x7f800000u | (shifted & 0x7fe000u) : bits;
  bits |= sign;
  std::memcpy(&v, &bits, sizeof v);
  return v;
}

// Every float16 of `low`/`high` (the shuffled bytes) times `scale` into out: by the processor's
// F16C conversion, 8 at a time (exact, as the scalar one), where it has it.
__attribute__((target("avx,f16c"))) void halvesToFloatsF16c(const uint8_t* low, const uint8_t* high,
                                                            size_t n, float scale, float* out) {
  const __m256 s = _mm256_set1_ps(scale);
  size_t i = 0;
  for (; i + 8 <= n; i += 8) {
    const __m128i lo = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(low + i));
    const __m128i hi = _mm_loadl_epi64(reinterpret_cast<const __m128i*>(high + i));
    const __m128i halves = _mm_unpacklo_epi8(lo, hi);
    _mm256_storeu_ps(out + i, _mm256_mul_ps(_mm256_cvtph_ps(halves), s));
  }
  for (; i < n; ++i)
    out[i] =
        halfToFloat(static_cast<uint32_t>(low[i]) | (static_cast<uint32_t>(high[i]) << 8)) * scale;
}

void halvesToFloats(const uint8_t* low, const uint8_t* high, size_t n, float scale, float* out) {
  static const bool f16c = __builtin_cpu_supports("f16c") && __builtin_cpu_supports("avx");
  if (f16c) return halvesToFloatsF16c(low, high, n, scale, out);
  for (size_t i = 0; i < n; ++i)
    out[i] =
        halfToFloat(static_cast<uint32_t>(low[i]) | (static_cast<uint32_t>(high[i]) << 8)) * scale;
}

// One zstd frame to decompress: where it lies and where its bytes go.
struct Frame {
  size_t offset = 0, bytes = 0; ///< within the blobs
  uint8_t* out = nullptr;       ///< its content's place
  size_t size = 0;              ///< the content's expected size
  std::string error;            ///< what went wrong, if anything
};

void decompress(const uint8_t* blobs, Frame& f) {
  const uint8_t* frame = blobs + f.offset;
  const unsigned long long size = ZSTD_getFrameContentSize(frame, f.bytes);
  if (size == ZSTD_CONTENTSIZE_UNKNOWN || size == ZSTD_CONTENTSIZE_ERROR || size != f.size) {
    f.error = "expected a zstd frame of " + std::to_string(f.size) + " bytes";
    return;
  }
  const size_t got = ZSTD_decompress(f.out, f.size, frame, f.bytes);
  if (ZSTD_isError(got) || got != f.size)
    f.error = std::string("zstd: ") + (ZSTD_isError(got) ? ZSTD_getErrorName(got) : "short");
}

// One float16 array to convert once its two planes are in: low bytes, then high bytes, times
// 2^-k (exact, as numpy's conversion and multiply).
struct Conversion {
  const uint8_t* planes = nullptr; ///< count low bytes, then count high bytes
  size_t count = 0;
  float scale = 1;
  float* out = nullptr;
};

} // namespace

void bindDatasetCodec(py::module_& m) {
  m.def(
      "_decode_arrays",
      [](const py::buffer& blobs, const py::list& specs, const py::list& differences) {
        // Freed arrays kept for the next item's (glibc returned and re-faulted the ten
        // megabytes of an item's arrays each time: half the read time in the kernel).
        static const bool keep = [] {
          mallopt(M_MMAP_THRESHOLD, 64 << 20);
          return mallopt(M_TRIM_THRESHOLD, 512 << 20) != 0;
        }();
        (void)keep;
        const py::buffer_info info = blobs.request();
        const auto* data = static_cast<const uint8_t*>(info.ptr);
        const size_t total = static_cast<size_t>(info.size * info.itemsize);
        std::vector<Frame> frames;
        std::vector<Conversion> conversions;
        std::vector<std::vector<uint8_t>> planes;      // per float16 array, its two byte planes
        std::vector<std::pair<float*, size_t>> floats; // per array, its float values (or null)
        py::list arrays;
        size_t f16 = 0;
        for (const py::handle spec : specs)
          f16 += spec.cast<py::tuple>()[2].cast<std::string>() == "f16";
        planes.reserve(f16);
        for (const py::handle spec : specs) {
          const py::tuple t = spec.cast<py::tuple>();
          size_t offset = t[0].cast<size_t>();
          const std::vector<size_t> sizes = t[1].cast<std::vector<size_t>>();
          const std::string kind = t[2].cast<std::string>();
          const std::vector<py::ssize_t> shape = t[3].cast<std::vector<py::ssize_t>>();
          const int k = t[4].cast<int>();
          if (kind != "f16" && kind != "uint32" && kind != "float32")
            throw py::value_error("expected arrays of kind f16, uint32 or float32, found " + kind);
          if (sizes.size() != (kind == "f16" ? 2u : 1u))
            throw py::value_error(
                "expected " + std::string(kind == "f16" ? "two frames" : "one frame") +
                " for an array of kind " + kind + ", found " + std::to_string(sizes.size()));
          size_t count = 1;
          for (const py::ssize_t n : shape) count *= static_cast<size_t>(n);
          py::array a = kind == "uint32" ? py::array(py::array_t<int32_t>(shape))
                                         : py::array(py::array_t<float>(shape));
          arrays.append(a);
          if (kind == "f16") { // two planes, then a conversion
            planes.emplace_back(2 * count);
            conversions.push_back({planes.back().data(), count, std::ldexp(1.0f, -k),
                                   static_cast<float*>(a.mutable_data())});
            floats.push_back({static_cast<float*>(a.mutable_data()), count});
          } else { // uint32 ids (read as int32: torch takes no uint32) and float32, as stored
            floats.push_back({nullptr, count});
          }
          for (size_t p = 0; p < sizes.size(); ++p) {
            if (offset + sizes[p] > total)
              throw py::value_error("an array's frame reaches beyond the item's bytes");
            uint8_t* out = kind == "f16" ? planes.back().data() + p * count
                                         : static_cast<uint8_t*>(a.mutable_data());
            frames.push_back({offset, sizes[p], out, kind == "f16" ? count : 4 * count, {}});
            offset += sizes[p];
          }
        }
        // The derived layers: a - b of two decoded float16 arrays of one shape.
        std::vector<std::array<float*, 3>> derived;
        std::vector<size_t> derivedCount;
        for (const py::handle d : differences) {
          const auto [a, b] = d.cast<std::pair<size_t, size_t>>();
          if (a >= floats.size() || b >= floats.size() || !floats[a].first || !floats[b].first ||
              floats[a].second != floats[b].second)
            throw py::value_error("expected differences of two float16 arrays of one shape");
          py::array out = py::array_t<float>(arrays[a].cast<py::array>().request().shape);
          derived.push_back(
              {static_cast<float*>(out.mutable_data()), floats[a].first, floats[b].first});
          derivedCount.push_back(floats[a].second);
          arrays.append(out);
        }
        bool failed = false;
        {
          py::gil_scoped_release release;
          tbb::parallel_for(size_t{0}, frames.size(),
                            [&](size_t f) { decompress(data, frames[f]); });
          for (const Frame& f : frames) failed = failed || !f.error.empty();
          // Conversions and differences in chunks of 64 K values, over both cores.
          constexpr size_t kChunk = 1 << 16;
          if (!failed) {
            tbb::parallel_for(size_t{0}, conversions.size(), [&](size_t c) {
              const Conversion& v = conversions[c];
              tbb::parallel_for(tbb::blocked_range<size_t>(0, v.count, kChunk),
                                [&](const tbb::blocked_range<size_t>& r) {
                                  halvesToFloats(v.planes + r.begin(),
                                                 v.planes + v.count + r.begin(), r.size(), v.scale,
                                                 v.out + r.begin());
                                });
            });
            for (size_t d = 0; d < derived.size(); ++d)
              tbb::parallel_for(tbb::blocked_range<size_t>(0, derivedCount[d], kChunk),
                                [&](const tbb::blocked_range<size_t>& r) {
                                  const auto [out, a, b] = derived[d];
                                  for (size_t i = r.begin(); i < r.end(); ++i) out[i] = a[i] - b[i];
                                });
          }
        }
        for (const Frame& f : frames)
          if (!f.error.empty()) throw py::value_error(f.error);
        return arrays;
      },
      py::arg("blobs"), py::arg("specs"), py::arg("differences") = py::list(),
      "An item's arrays from its bytes: specs are (offset, frame sizes, kind, shape, k) of each "
      "array (kind f16: two zstd frames, the low and the high bytes of float16 bits times 2^k, "
      "read as float32; uint32: one frame, read as int32; float32: one frame), decoded in parallel "
      "without the GIL, then for each (a, b) of "
      "differences the array a - b (a derived layer) appended (nxrender.dataset's reader). "
      "Keeps freed memory in the process for reuse (glibc's trim threshold raised to 512 MB).");
}

} // namespace nxpy
