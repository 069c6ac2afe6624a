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
#include <span>
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

// One array to decode: where its frame lies, what it holds, and where it goes.
struct Job {
  size_t offset = 0, bytes = 0; ///< its zstd frame within the blobs
  std::string kind;             ///< "f16" (shuffled bits, scale 2^k), "uint32", "float32"
  int k = 0;                    ///< the float16 arrays' power-of-2 scale
  size_t count = 0;             ///< values
  void* out = nullptr;          ///< float32 (f16, float32) or int32 (uint32) values
  std::string error;            ///< what went wrong, if anything
};

void decode(const uint8_t* blobs, Job& job) {
  const uint8_t* frame = blobs + job.offset;
  const unsigned long long size = ZSTD_getFrameContentSize(frame, job.bytes);
  const size_t width = job.kind == "f16" ? 2 : 4;
  if (size == ZSTD_CONTENTSIZE_UNKNOWN || size == ZSTD_CONTENTSIZE_ERROR ||
      size != job.count * width) {
    job.error = "expected a zstd frame of " + std::to_string(job.count * width) + " bytes";
    return;
  }
  // (a thread's buffer kept between items: a fresh megabyte each time cost a third of the time
  // in the kernel's page faults)
  thread_local std::vector<uint8_t> buffer;
  if (buffer.size() < job.count * width) buffer.resize(job.count * width);
  const std::span<uint8_t> raw(buffer.data(), job.count * width);
  const size_t got = ZSTD_decompress(raw.data(), raw.size(), frame, job.bytes);
  if (ZSTD_isError(got) || got != raw.size()) {
    job.error = std::string("zstd: ") + (ZSTD_isError(got) ? ZSTD_getErrorName(got) : "short");
    return;
  }
  if (job.kind == "f16") { // low bytes, then high bytes; then times 2^-k (exact, as numpy)
    halvesToFloats(raw.data(), raw.data() + job.count, job.count, std::ldexp(1.0f, -job.k),
                   static_cast<float*>(job.out));
  } else { // uint32 ids (read as int32: torch takes no uint32) and float32 values, as stored
    std::memcpy(job.out, raw.data(), raw.size());
  }
}

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
        std::vector<Job> jobs;
        py::list arrays;
        for (const py::handle spec : specs) {
          const py::tuple t = spec.cast<py::tuple>();
          Job job;
          job.offset = t[0].cast<size_t>();
          job.bytes = t[1].cast<size_t>();
          job.kind = t[2].cast<std::string>();
          const std::vector<py::ssize_t> shape = t[3].cast<std::vector<py::ssize_t>>();
          job.k = t[4].cast<int>();
          if (job.offset + job.bytes > total)
            throw py::value_error("an array's frame reaches beyond the item's bytes");
          if (job.kind != "f16" && job.kind != "uint32" && job.kind != "float32")
            throw py::value_error("expected arrays of kind f16, uint32 or float32, found " +
                                  job.kind);
          job.count = 1;
          for (const py::ssize_t n : shape) job.count *= static_cast<size_t>(n);
          py::array a = job.kind == "uint32" ? py::array(py::array_t<int32_t>(shape))
                                             : py::array(py::array_t<float>(shape));
          job.out = a.mutable_data();
          arrays.append(a);
          jobs.push_back(std::move(job));
        }
        // The derived layers: a - b of two decoded float arrays of one shape.
        std::vector<std::array<float*, 3>> derived;
        std::vector<size_t> derivedCount;
        for (const py::handle d : differences) {
          const auto [a, b] = d.cast<std::pair<size_t, size_t>>();
          if (a >= jobs.size() || b >= jobs.size() || jobs[a].kind != "f16" ||
              jobs[b].kind != "f16" || jobs[a].count != jobs[b].count)
            throw py::value_error("expected differences of two float16 arrays of one shape");
          py::array out = py::array_t<float>(arrays[a].cast<py::array>().request().shape);
          derived.push_back({static_cast<float*>(out.mutable_data()),
                             static_cast<float*>(jobs[a].out), static_cast<float*>(jobs[b].out)});
          derivedCount.push_back(jobs[a].count);
          arrays.append(out);
        }
        {
          py::gil_scoped_release release;
          tbb::parallel_for(size_t{0}, jobs.size(), [&](size_t j) { decode(data, jobs[j]); });
          for (const Job& j : jobs)
            if (!j.error.empty()) break;
          for (size_t d = 0; d < derived.size(); ++d)
            tbb::parallel_for(tbb::blocked_range<size_t>(0, derivedCount[d], 1 << 16),
                              [&](const tbb::blocked_range<size_t>& r) {
                                const auto [out, a, b] = derived[d];
                                for (size_t i = r.begin(); i < r.end(); ++i) out[i] = a[i] - b[i];
                              });
        }
        for (const Job& j : jobs)
          if (!j.error.empty()) throw py::value_error(j.error);
        return arrays;
      },
      py::arg("blobs"), py::arg("specs"), py::arg("differences") = py::list(),
      "An item's arrays from its bytes: specs are (offset, bytes, kind, shape, k) of each zstd "
      "frame (kind f16: byte-shuffled float16 bits times 2^k, read as float32; uint32: read as "
      "int32; float32), decoded in parallel without the GIL, then for each (a, b) of "
      "differences the array a - b (a derived layer) appended (nxrender.dataset's reader). "
      "Keeps freed memory in the process for reuse (glibc's trim threshold raised to 512 MB).");
}

} // namespace nxpy
