// nxrender._decode_arrays: an item's arrays from their zstd frames (docs/datasets.md).

#include "apps/python/py_dataset_codec.h"

#include <pybind11/numpy.h>
#include <pybind11/stl.h>

#include <immintrin.h>
#include <malloc.h>
#include <tbb/parallel_for.h>
#include <zstd.h>

#include <algorithm>
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

// out[i] = x[i] - y[i] for i < n, 8 at a time where the processor has AVX.
__attribute__((target("avx"))) void subtractAvx(const float* x, const float* y, size_t n,
                                                float* out) {
  size_t i = 0;
  for (; i + 8 <= n; i += 8)
    _mm256_storeu_ps(out + i, _mm256_sub_ps(_mm256_loadu_ps(x + i), _mm256_loadu_ps(y + i)));
  for (; i < n; ++i) out[i] = x[i] - y[i];
}

void subtract(const float* x, const float* y, size_t n, float* out) {
  static const bool avx = __builtin_cpu_supports("avx");
  if (avx) return subtractAvx(x, y, n, out);
  for (size_t i = 0; i < n; ++i) out[i] = x[i] - y[i];
}

// Every low byte of n values from their packed high nibbles (format 4, when at least 4 low bits
// were dropped): value 2j's in byte j's low nibble, value 2j+1's in its high nibble.
void expandNibbles(const uint8_t* packed, size_t n, uint8_t* low) {
  size_t j = 0;
  const __m128i mask = _mm_set1_epi8(static_cast<char>(0xF0));
  for (; 2 * j + 32 <= n; j += 16) { // (SSE2: 16 packed bytes to 32 low bytes)
    const __m128i p = _mm_loadu_si128(reinterpret_cast<const __m128i*>(packed + j));
    const __m128i even = _mm_and_si128(_mm_slli_epi16(p, 4), mask), odd = _mm_and_si128(p, mask);
    _mm_storeu_si128(reinterpret_cast<__m128i*>(low + 2 * j), _mm_unpacklo_epi8(even, odd));
    _mm_storeu_si128(reinterpret_cast<__m128i*>(low + 2 * j + 16), _mm_unpackhi_epi8(even, odd));
  }
  for (; 2 * j < n; ++j) {
    low[2 * j] = static_cast<uint8_t>(packed[j] << 4);
    if (2 * j + 1 < n) low[2 * j + 1] = static_cast<uint8_t>(packed[j] & 0xF0u);
  }
}

// Where one zstd frame lies within the item's bytes.
struct FrameRef {
  size_t offset = 0, bytes = 0;
};

// A float16 array: its frames (per chunk of `chunk` values, its low bytes' then its high
// bytes'), the scale back and where its float32 values go.
struct HalfArray {
  std::vector<FrameRef> frames;
  size_t count = 0, chunk = 0;
  bool nibbles = false; ///< the low frames hold one nibble per value
  float scale = 1;
  float* out = nullptr;
};

// A uint32 or float32 array: one frame, decompressed into its values as they are.
struct RawArray {
  FrameRef frame;
  uint8_t* out = nullptr;
  size_t bytes = 0;
};

// Float16 arrays decoded chunk by chunk together, so that their differences (the derived
// layers) are taken while the values are in the cache.
struct Group {
  std::vector<size_t> members;                    ///< HalfArray indices
  std::vector<std::array<size_t, 2>> differences; ///< (a, b) as member positions
  std::vector<float*> differenceOut;              ///< a - b of each
  size_t count = 0, chunk = 0;
};

// One thread's zstd context and plane buffers, kept between items.
struct Scratch {
  ZSTD_DCtx* context = ZSTD_createDCtx();
  std::vector<uint8_t> planes, nibbles;
  Scratch() = default;
  Scratch(const Scratch&) = delete;
  Scratch& operator=(const Scratch&) = delete;
  ~Scratch() { ZSTD_freeDCtx(context); }
};

Scratch& scratch() {
  static thread_local Scratch s;
  return s;
}

// Decompresses one frame of exactly `size` content bytes into out; the error, if any.
std::string decompress(const uint8_t* blobs, const FrameRef& f, uint8_t* out, size_t size) {
  const uint8_t* frame = blobs + f.offset;
  const unsigned long long content = ZSTD_getFrameContentSize(frame, f.bytes);
  if (content == ZSTD_CONTENTSIZE_UNKNOWN || content == ZSTD_CONTENTSIZE_ERROR || content != size)
    return "expected a zstd frame of " + std::to_string(size) + " bytes";
  const size_t got = ZSTD_decompressDCtx(scratch().context, out, size, frame, f.bytes);
  if (ZSTD_isError(got) || got != size)
    return std::string("zstd: ") + (ZSTD_isError(got) ? ZSTD_getErrorName(got) : "short");
  return {};
}

// Chunk c of every member of g: both planes into this thread's buffers, then converted and
// the differences taken in blocks that stay in the first-level cache. The error, if any.
std::string decodeChunk(const uint8_t* blobs, const std::vector<HalfArray>& arrays, const Group& g,
                        size_t c) {
  const size_t begin = c * g.chunk, n = std::min(g.chunk, g.count - begin);
  Scratch& s = scratch();
  s.planes.resize(2 * n * g.members.size()); // (no shrinking: kept between items)
  for (size_t m = 0; m < g.members.size(); ++m) {
    const HalfArray& a = arrays[g.members[m]];
    uint8_t* low = s.planes.data() + 2 * n * m;
    uint8_t* high = low + n;
    std::string error;
    if (a.nibbles) {
      s.nibbles.resize((n + 1) / 2);
      error = decompress(blobs, a.frames[2 * c], s.nibbles.data(), (n + 1) / 2);
      if (error.empty()) expandNibbles(s.nibbles.data(), n, low);
    } else {
      error = decompress(blobs, a.frames[2 * c], low, n);
    }
    if (error.empty()) error = decompress(blobs, a.frames[2 * c + 1], high, n);
    if (!error.empty()) return error;
  }
  constexpr size_t kBlock = 2048; // (values per block: a group's blocks fit the L1 cache)
  for (size_t b = 0; b < n; b += kBlock) {
    const size_t len = std::min(kBlock, n - b);
    for (size_t m = 0; m < g.members.size(); ++m) {
      const HalfArray& a = arrays[g.members[m]];
      const uint8_t* low = s.planes.data() + 2 * n * m;
      halvesToFloats(low + b, low + n + b, len, a.scale, a.out + begin + b);
    }
    for (size_t d = 0; d < g.differences.size(); ++d)
      subtract(arrays[g.members[g.differences[d][0]]].out + begin + b,
               arrays[g.members[g.differences[d][1]]].out + begin + b, len,
               g.differenceOut[d] + begin + b);
  }
  return {};
}

// Where each decoded array goes: the caller's arrays when given (a batch's slices: checked),
// else new ones.
class OutputArrays {
public:
  explicit OutputArrays(const py::object& outputs)
      : given_(!outputs.is_none()), outs_(given_ ? outputs.cast<py::list>() : py::list()) {}

  /// Array i (int32 when ints, else float32) of this shape.
  py::array make(size_t i, bool ints, const std::vector<py::ssize_t>& shape) const {
    if (!given_)
      return ints ? py::array(py::array_t<int32_t>(shape)) : py::array(py::array_t<float>(shape));
    if (i >= outs_.size())
      throw py::value_error("expected an output array for each array and difference");
    py::array out = outs_[i].cast<py::array>();
    const bool typed =
        ints ? py::isinstance<py::array_t<int32_t>>(out) : py::isinstance<py::array_t<float>>(out);
    if (!typed || !(out.flags() & py::array::c_style) || !out.writeable() ||
        std::vector<py::ssize_t>(out.shape(), out.shape() + out.ndim()) != shape)
      throw py::value_error(std::string("expected a writable C-contiguous ") +
                            (ints ? "int32" : "float32") + " output array of the item's shape");
    return out;
  }

private:
  bool given_;
  py::list outs_;
};

// An item's decoding: its arrays, how each is stored, and the units of work.
struct Decoding {
  std::vector<HalfArray> halves;
  std::vector<RawArray> raws;
  std::vector<long> halfIndex; ///< per spec, its HalfArray index (-1: a raw array)
  std::vector<Group> groups;
  py::list arrays; ///< the specs' arrays, then the differences'
};

// The specs' arrays (offset, frame sizes, kind, shape, k, chunk, nibbles), their frames checked
// against the item's `total` bytes.
void readSpecs(Decoding& d, size_t total, const py::list& specs, const OutputArrays& output) {
  for (const py::handle spec : specs) {
    const py::tuple t = spec.cast<py::tuple>();
    if (t.size() != 7)
      throw py::value_error("expected (offset, frames, kind, shape, k, chunk, nibbles)");
    size_t offset = t[0].cast<size_t>();
    const std::vector<size_t> sizes = t[1].cast<std::vector<size_t>>();
    const std::string kind = t[2].cast<std::string>();
    const std::vector<py::ssize_t> shape = t[3].cast<std::vector<py::ssize_t>>();
    if (kind != "f16" && kind != "uint32" && kind != "float32")
      throw py::value_error("expected arrays of kind f16, uint32 or float32, found " + kind);
    size_t count = 1;
    for (const py::ssize_t n : shape) count *= static_cast<size_t>(n);
    py::array a = output.make(d.arrays.size(), kind == "uint32", shape);
    d.arrays.append(a);
    std::vector<FrameRef> frames;
    for (const size_t bytes : sizes) {
      if (offset + bytes > total)
        throw py::value_error("an array's frame reaches beyond the item's bytes");
      frames.push_back({offset, bytes});
      offset += bytes;
    }
    if (kind != "f16") {
      if (frames.size() != 1)
        throw py::value_error("expected one frame for an array of kind " + kind + ", found " +
                              std::to_string(frames.size()));
      d.raws.push_back({frames[0], static_cast<uint8_t*>(a.mutable_data()), 4 * count});
      d.halfIndex.push_back(-1);
      continue;
    }
    HalfArray h;
    h.count = count;
    h.chunk = t[5].cast<size_t>();
    if (h.chunk == 0 || h.chunk > count) h.chunk = std::max<size_t>(count, 1);
    h.nibbles = t[6].cast<bool>();
    const size_t chunks = count == 0 ? 0 : (count + h.chunk - 1) / h.chunk;
    if (frames.size() != 2 * chunks)
      throw py::value_error("expected " + std::to_string(2 * chunks) +
                            " frames for a float16 array of " + std::to_string(count) +
                            " values in chunks of " + std::to_string(h.chunk) + ", found " +
                            std::to_string(frames.size()));
    if (h.nibbles && chunks > 1 && h.chunk % 2)
      throw py::value_error("expected an even chunk for packed low nibbles");
    h.frames = std::move(frames);
    h.scale = std::ldexp(1.0f, -t[4].cast<int>());
    h.out = static_cast<float*>(a.mutable_data());
    d.halfIndex.push_back(static_cast<long>(d.halves.size()));
    d.halves.push_back(std::move(h));
  }
}

// Groups the float16 arrays that differences (a, b) of spec indices link, so that they decode
// chunk by chunk together, and appends each difference's array.
void groupDifferences(Decoding& d, const py::list& differences, const OutputArrays& output) {
  std::vector<size_t> groupOf(d.halves.size());
  for (size_t h = 0; h < d.halves.size(); ++h) groupOf[h] = h;
  const auto root = [&](size_t h) {
    while (groupOf[h] != h) h = groupOf[h];
    return h;
  };
  std::vector<std::pair<size_t, size_t>> pairs; // spec indices
  for (const py::handle pair : differences) {
    const auto [a, b] = pair.cast<std::pair<size_t, size_t>>();
    if (a >= d.halfIndex.size() || b >= d.halfIndex.size() || d.halfIndex[a] < 0 ||
        d.halfIndex[b] < 0 || a == b ||
        d.halves[d.halfIndex[a]].count != d.halves[d.halfIndex[b]].count ||
        d.halves[d.halfIndex[a]].chunk != d.halves[d.halfIndex[b]].chunk)
      throw py::value_error("expected differences of two float16 arrays of one shape and chunk "
                            "size");
    pairs.emplace_back(a, b);
    groupOf[root(d.halfIndex[a])] = root(d.halfIndex[b]);
  }
  std::vector<long> groupIndex(d.halves.size(), -1);
  for (size_t h = 0; h < d.halves.size(); ++h) {
    const size_t r = root(h);
    if (groupIndex[r] < 0) {
      groupIndex[r] = static_cast<long>(d.groups.size());
      d.groups.push_back({});
      d.groups.back().count = d.halves[h].count;
      d.groups.back().chunk = d.halves[h].chunk;
    }
    d.groups[groupIndex[r]].members.push_back(h);
  }
  const auto position = [](const Group& g, long h) {
    return static_cast<size_t>(
        std::find(g.members.begin(), g.members.end(), static_cast<size_t>(h)) - g.members.begin());
  };
  for (const auto& [a, b] : pairs) {
    Group& g = d.groups[groupIndex[root(d.halfIndex[a])]];
    const py::buffer_info of = d.arrays[a].cast<py::array>().request();
    py::array out = output.make(d.arrays.size(), false, of.shape);
    g.differences.push_back({position(g, d.halfIndex[a]), position(g, d.halfIndex[b])});
    g.differenceOut.push_back(static_cast<float*>(out.mutable_data()));
    d.arrays.append(out);
  }
}

// Decodes every raw array and every chunk of every group over the cores, without the GIL.
void run(const Decoding& d, const uint8_t* data) {
  std::vector<std::pair<long, size_t>> units; // (group, chunk), or (-1, raw array)
  for (size_t r = 0; r < d.raws.size(); ++r) units.emplace_back(-1, r);
  for (size_t g = 0; g < d.groups.size(); ++g)
    for (size_t c = 0; c * d.groups[g].chunk < d.groups[g].count; ++c)
      units.emplace_back(static_cast<long>(g), c);
  std::vector<std::string> errors(units.size());
  {
    py::gil_scoped_release release;
    tbb::parallel_for(size_t{0}, units.size(), [&](size_t u) {
      const auto [g, i] = units[u];
      errors[u] = g < 0 ? decompress(data, d.raws[i].frame, d.raws[i].out, d.raws[i].bytes)
                        : decodeChunk(data, d.halves, d.groups[static_cast<size_t>(g)], i);
    });
  }
  for (const std::string& e : errors)
    if (!e.empty()) throw py::value_error(e);
}

py::list decodeArrays(const py::buffer& blobs, const py::list& specs, const py::list& differences,
                      const py::object& outputs) {
  // Freed arrays kept for the next item's (glibc returned and re-faulted the ten megabytes of
  // an item's arrays each time: half the read time in the kernel).
  static const bool keep = [] {
    mallopt(M_MMAP_THRESHOLD, 64 << 20);
    return mallopt(M_TRIM_THRESHOLD, 512 << 20) != 0;
  }();
  (void)keep;
  const py::buffer_info info = blobs.request();
  const OutputArrays output(outputs);
  Decoding d;
  readSpecs(d, static_cast<size_t>(info.size * info.itemsize), specs, output);
  groupDifferences(d, differences, output);
  run(d, static_cast<const uint8_t*>(info.ptr));
  return d.arrays;
}

} // namespace

void bindDatasetCodec(py::module_& m) {
  m.def("_decode_arrays", &decodeArrays, py::arg("blobs"), py::arg("specs"),
        py::arg("differences") = py::list(), py::arg("outputs") = py::none(),
        "An item's arrays from its bytes: specs are (offset, frame sizes, kind, shape, k, chunk, "
        "nibbles) of each array (kind f16: per chunk of `chunk` values (0: the whole array) two "
        "zstd frames, the low bytes (nibbles: their high nibbles packed two to a byte) and the "
        "high bytes of float16 bits times 2^k, read as float32; uint32: one frame, read as int32; "
        "float32: one frame), decoded in parallel without the GIL, then for each (a, b) of "
        "differences the array a - b (a derived layer) appended (nxrender.dataset's reader); "
        "outputs, when given, are the arrays to decode into (one per array, then per difference: "
        "a batch's slices). "
        "Keeps freed memory in the process for reuse (glibc's trim threshold raised to 512 MB).");
}

} // namespace nxpy
