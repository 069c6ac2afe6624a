#include "spectra/sigmoid_table.h"
#include "core/cell_index.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <stdexcept>

namespace nx {
namespace {

double smoothstep(double t) {
  return t * t * (3.0 - 2.0 * t);
}

// The colour of table entry (l, z, x, y): channel l is z, the next two z * x and z * y.
Rgb entryColour(int l, double z, double x, double y) {
  double c[3];
  c[l] = z;
  c[(l + 1) % 3] = z * x;
  c[(l + 2) % 3] = z * y;
  return {c[0], c[1], c[2]};
}

// A fit counts as converged below this CIEDE2000; otherwise it is redone by continuation.
constexpr double kConvergedDeltaE = 1e-3;

} // namespace

SigmoidTable::SigmoidTable(int resolution, std::vector<float> z, std::vector<float> data)
    : res_(resolution), z_(std::move(z)), data_(std::move(data)) {
  if (res_ < 2 || z_.size() != static_cast<size_t>(res_) ||
      data_.size() != static_cast<size_t>(9) * res_ * res_ * res_)
    throw std::invalid_argument("sigmoid table: sizes do not match its resolution");
}

std::vector<float> SigmoidTable::zPositions(int res) {
  std::vector<float> z(res);
  for (int k = 0; k < res; ++k) z[k] = static_cast<float>(smoothstep(smoothstep(k / (res - 1.0))));
  return z;
}

std::vector<float> SigmoidTable::fit(int res, const ForEach& forEach) {
  if (res < 3) throw std::invalid_argument("sigmoid table: resolution below 3");
  const std::vector<float> zs = zPositions(res);
  const double step = 1.0 / (res - 1);
  const int k0 = res / 2; // the slice nearest z = 1/2: grey there has small coefficients
  std::vector<float> data(static_cast<size_t>(9) * res * res * res);
  auto at = [&](int l, int k, int j, int i) {
    return data.data() + ((static_cast<size_t>(l * res + k) * res + j) * res + i) * 3;
  };
  // Fits the entry (l, k, j, i) starting at the entry (l, sk, sj, si).
  auto fitEntry = [&](int l, int k, int j, int i, int sk, int sj, int si,
                      const SigmoidCoefficients* seedOverride, const Rgb* seedColourOverride) {
    // z = 0 (black) has no finite solution: that slice is fitted at the next z, a colour
    // darker than CIELAB L* = 0.03 at the built-in resolution.
    const double z = std::max<double>(zs[k], zs[1]), sz = std::max<double>(zs[sk], zs[1]);
    const float* s = at(l, sk, sj, si);
    const SigmoidCoefficients seed =
        seedOverride ? *seedOverride : SigmoidCoefficients{s[0], s[1], s[2]};
    const Rgb seedColour =
        seedColourOverride ? *seedColourOverride : entryColour(l, sz, si * step, sj * step);
    const Rgb target = entryColour(l, z, i * step, j * step);
    SigmoidCoefficients c = fitSigmoidCoefficients(target, seed);
    if (sigmoidFitDeltaE(c, target) > kConvergedDeltaE)
      c = fitSigmoidCoefficientsFrom(target, seedColour, seed, 16);
    float* out = at(l, k, j, i);
    for (int a = 0; a < 3; ++a) out[a] = static_cast<float>(c[a]);
  };
  // The middle slices: from grey outward along rows (x) then down the columns (y).
  forEach(3, [&](int l) {
    const SigmoidCoefficients grey = greySigmoidCoefficients(zs[k0]);
    const Rgb greyColour = entryColour(l, zs[k0], 1.0, 1.0);
    for (int i = res - 1; i >= 0; --i)
      for (int j = res - 1; j >= 0; --j) {
        if (i == res - 1 && j == res - 1)
          fitEntry(l, k0, j, i, k0, j, i, &grey, &greyColour);
        else if (j < res - 1)
          fitEntry(l, k0, j, i, k0, j + 1, i, nullptr, nullptr);
        else
          fitEntry(l, k0, j, i, k0, j, i + 1, nullptr, nullptr);
      }
  });
  // Every line of constant chromaticity ratio, from the middle slice toward both ends.
  forEach(3 * res, [&](int line) {
    const int l = line / res, j = line % res;
    for (int i = 0; i < res; ++i) {
      for (int k = k0 + 1; k < res; ++k) fitEntry(l, k, j, i, k - 1, j, i, nullptr, nullptr);
      for (int k = k0 - 1; k >= 0; --k) fitEntry(l, k, j, i, k + 1, j, i, nullptr, nullptr);
    }
  });
  return data;
}

namespace {
constexpr char kMagic[8] = {'N', 'X', 'S', 'I', 'G', 'T', 'A', 'B'};
} // namespace

std::string SigmoidTable::toBytes() const {
  std::string out(kMagic, sizeof kMagic);
  const int32_t res = res_;
  out.append(reinterpret_cast<const char*>(&res), sizeof res);
  out.append(reinterpret_cast<const char*>(z_.data()), z_.size() * sizeof(float));
  out.append(reinterpret_cast<const char*>(data_.data()), data_.size() * sizeof(float));
  return out;
}

SigmoidTable SigmoidTable::fromBytes(const unsigned char* bytes, size_t size) {
  int32_t res = 0;
  if (size < sizeof kMagic + sizeof res || std::memcmp(bytes, kMagic, sizeof kMagic) != 0)
    throw std::invalid_argument("sigmoid table: not a table (no NXSIGTAB header)");
  std::memcpy(&res, bytes + sizeof kMagic, sizeof res);
  if (res < 3 || res > 256) throw std::invalid_argument("sigmoid table: resolution out of range");
  const size_t zCount = static_cast<size_t>(res),
               dataCount = static_cast<size_t>(9) * res * res * res;
  if (size != sizeof kMagic + sizeof res + (zCount + dataCount) * sizeof(float))
    throw std::invalid_argument("sigmoid table: size does not match its resolution");
  std::vector<float> z(zCount), data(dataCount);
  const unsigned char* p = bytes + sizeof kMagic + sizeof res;
  std::memcpy(z.data(), p, zCount * sizeof(float));
  std::memcpy(data.data(), p + zCount * sizeof(float), dataCount * sizeof(float));
  return SigmoidTable(res, std::move(z), std::move(data));
}

SigmoidCoefficients SigmoidTable::lookup(const Rgb& rgb) const {
  const double c[3] = {rgb.r, rgb.g, rgb.b};
  const int l = (c[0] >= c[1] && c[0] >= c[2]) ? 0 : (c[1] >= c[2] ? 1 : 2);
  const double z = c[l];
  const double x = z > 0 ? c[(l + 1) % 3] / z : 1.0, y = z > 0 ? c[(l + 2) % 3] / z : 1.0;
  const double xf = std::clamp(x, 0.0, 1.0) * (res_ - 1), yf = std::clamp(y, 0.0, 1.0) * (res_ - 1);
  const int xi = cellIndex(xf, res_ - 1), yi = cellIndex(yf, res_ - 1);
  const int zi =
      static_cast<int>(std::upper_bound(z_.begin() + 1, z_.end() - 1, static_cast<float>(z)) -
                       z_.begin()) -
      1;
  const double tx = xf - xi, ty = yf - yi;
  const double tz = std::clamp((z - z_[zi]) / (z_[zi + 1] - z_[zi]), 0.0, 1.0);
  SigmoidCoefficients out{0, 0, 0};
  for (int dz = 0; dz < 2; ++dz)
    for (int dy = 0; dy < 2; ++dy)
      for (int dx = 0; dx < 2; ++dx) {
        const double w = (dz ? tz : 1 - tz) * (dy ? ty : 1 - ty) * (dx ? tx : 1 - tx);
        const size_t e =
            ((static_cast<size_t>(l * res_ + zi + dz) * res_ + yi + dy) * res_ + xi + dx) * 3;
        for (int a = 0; a < 3; ++a) out[a] += w * data_[e + a];
      }
  return out;
}

} // namespace nx
