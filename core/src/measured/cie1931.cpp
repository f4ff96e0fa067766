#include "bxdf/measured/cie1931.h"

#include <array>

namespace bxdf {

namespace {

// CIE 1931 2° standard colorimetric observer, x̄ ȳ z̄ every 10 nm from 400 to 700 nm: the
// CIE's own tabulation (CIE 15:2004 / ISO 11664-1, 5 nm steps), taken at every second row;
// no interpolation.
constexpr CieSample kCmf[kCieSamples] = {
    {0.014310f, 0.000396f, 0.067850f},  // 400
    {0.043510f, 0.001210f, 0.207400f},  // 410
    {0.134380f, 0.004000f, 0.645600f},  // 420
    {0.283900f, 0.011600f, 1.385600f},  // 430
    {0.348280f, 0.023000f, 1.747060f},  // 440
    {0.336200f, 0.038000f, 1.772110f},  // 450
    {0.290800f, 0.060000f, 1.669200f},  // 460
    {0.195360f, 0.090980f, 1.287640f},  // 470
    {0.095640f, 0.139020f, 0.812950f},  // 480
    {0.032010f, 0.208020f, 0.465180f},  // 490
    {0.004900f, 0.323000f, 0.272000f},  // 500
    {0.009300f, 0.503000f, 0.158200f},  // 510
    {0.063270f, 0.710000f, 0.078250f},  // 520
    {0.165500f, 0.862000f, 0.042160f},  // 530
    {0.290400f, 0.954000f, 0.020300f},  // 540
    {0.433450f, 0.994950f, 0.008750f},  // 550
    {0.594500f, 0.995000f, 0.003900f},  // 560
    {0.762100f, 0.952000f, 0.002100f},  // 570
    {0.916300f, 0.870000f, 0.001650f},  // 580
    {1.026300f, 0.757000f, 0.001100f},  // 590
    {1.062200f, 0.631000f, 0.000800f},  // 600
    {1.002600f, 0.503000f, 0.000340f},  // 610
    {0.854450f, 0.381000f, 0.000190f},  // 620
    {0.642400f, 0.265000f, 0.000050f},  // 630
    {0.447900f, 0.175000f, 0.000020f},  // 640
    {0.283500f, 0.107000f, 0.000000f},  // 650
    {0.164900f, 0.061000f, 0.000000f},  // 660
    {0.087400f, 0.032000f, 0.000000f},  // 670
    {0.046770f, 0.017000f, 0.000000f},  // 680
    {0.022700f, 0.008210f, 0.000000f},  // 690
    {0.011359f, 0.004102f, 0.000000f},  // 700
};

// XYZ → linear Rec.709 (sRGB primaries, D65 white), IEC 61966-2-1.
constexpr double kXyzToRec709[3][3] = {{3.2404542, -1.5371385, -0.4985314},
                                       {-0.9692660, 1.8760108, 0.0415560},
                                       {0.0556434, -0.2040259, 1.0572252}};

// Normalisation. A spectral BRDF value s(λ) is a BRDF per wavelength; its RGB is the BRDF seen
// under an equal-energy illuminant. XYZ = Σ s x̄ etc., then M · XYZ, then each channel is divided
// by the same sum for s ≡ 1. That last step both removes the Σȳ scale and white-balances the
// equal-energy white (E) onto Rec.709 white (a diagonal von Kries step in linear RGB), so a
// spectrally flat value v gives exactly (v, v, v) and grey paints stay grey. The resulting
// per-wavelength weights of each channel sum to 1.
std::array<std::array<float, kCieSamples>, 3> make_weights() {
  std::array<std::array<double, kCieSamples>, 3> w{};
  double sums[3] = {0, 0, 0};
  for (int i = 0; i < kCieSamples; ++i) {
    const double xyz[3] = {kCmf[i].x, kCmf[i].y, kCmf[i].z};
    for (int c = 0; c < 3; ++c) {
      w[c][i] = kXyzToRec709[c][0] * xyz[0] + kXyzToRec709[c][1] * xyz[1] +
                kXyzToRec709[c][2] * xyz[2];
      sums[c] += w[c][i];
    }
  }
  std::array<std::array<float, kCieSamples>, 3> out{};
  for (int c = 0; c < 3; ++c)
    for (int i = 0; i < kCieSamples; ++i) out[c][i] = static_cast<float>(w[c][i] / sums[c]);
  return out;
}

}  // namespace

const CieSample& cie1931_2deg(int i) { return kCmf[i]; }

RGB spectrum_to_rgb(const float* values31) {
  static const auto weights = make_weights();
  double rgb[3] = {0, 0, 0};
  for (int c = 0; c < 3; ++c)
    for (int i = 0; i < kCieSamples; ++i)
      rgb[c] += static_cast<double>(weights[c][i]) * static_cast<double>(values31[i]);
  return RGB(static_cast<float>(rgb[0]), static_cast<float>(rgb[1]), static_cast<float>(rgb[2]));
}

}  // namespace bxdf
