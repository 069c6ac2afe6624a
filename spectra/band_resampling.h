#pragma once
// Turning a render's bands into a capture's: what each capture band would record of the
// spectrum the render's band values sample.

#include <string>
#include <vector>

#include "spectra/sensor.h"

namespace nx {

/// A linear map from a render's band values to a capture's: out_i = sum_j w_ij in_j.
class BandResampling {
public:
  /// The identity on `bands` bands (render and capture share their bands).
  static BandResampling identity(int bands);

  /// The render's band values read as samples at their centroids of a spectrum linear between
  /// them (held at the first and last value beyond), recorded through each channel of
  /// `capture` (Gaussian from centre and FWHM, or a measured response):
  /// w_ij = integral(R_i hat_j) / integral(R_i), hat_j the linear interpolation's basis.
  /// Throws nx::Error naming `where` when a capture channel has more than 1% of its response
  /// outside the render's centroids.
  static BandResampling through(const std::vector<double>& renderCentroidsNm, const Sensor& capture,
                                const std::string& where);

  /// Applies the map to one pixel: `in` has inputs() values, `out` outputs().
  void apply(const float* in, float* out) const;
  /// The same for variances of independent inputs: out_i = sum_j w_ij^2 in_j.
  void applyToVariance(const float* in, float* out) const;

  /// Band counts before and after.
  int inputs() const { return inputs_; }
  int outputs() const { return outputs_; }
  /// w_ij, row-major [output][input].
  const std::vector<double>& weights() const { return w_; }
  /// True for identity().
  bool isIdentity() const { return identity_; }

private:
  void applyWeights(const float* in, float* out, bool squared) const;
  int inputs_ = 0, outputs_ = 0;
  bool identity_ = false;
  std::vector<double> w_;
};

} // namespace nx
