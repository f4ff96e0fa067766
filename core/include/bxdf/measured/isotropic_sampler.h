// Importance sampling for tabulated isotropic BRDFs. For a set of outgoing elevations θo the
// BRDF times cos θi is tabulated over (θi, Δφ) cells and turned into a 2D piecewise-constant
// distribution (marginal over θi rows, conditional over Δφ). A query θo between two nodes uses
// the mixture of the two neighbouring distributions, weighted linearly, so the pdf is
// continuous in wo and exact: pdf() evaluates the same mixture that sample() draws from.
// A fixed fraction of cosine-weighted sampling keeps the pdf positive wherever the BRDF may be.
#pragma once

#include <functional>
#include <vector>

#include "bxdf/math.h"
#include "bxdf/spectrum.h"

namespace bxdf {

class IsotropicSampler {
 public:
  static constexpr int kThetaONodes = 24;   // θo nodes over [0, 90°]
  static constexpr int kThetaICells = 32;   // uniform in θi over [0, 90°]
  static constexpr int kPhiCells = 32;      // uniform in |Δφ| over [0, 180°], mirrored
  static constexpr float kCosineFraction = 0.15f;

  using BRDF = std::function<RGB(const Vec3& wo, const Vec3& wi)>;
  // f is called with unit directions in the upper hemisphere, wo in the xz plane.
  explicit IsotropicSampler(const BRDF& f);

  // wo unit length with wo.z > 0; returns wi in the upper hemisphere.
  Vec3 sample(const Vec3& wo, Point2 u) const;
  // Solid-angle density of sample(); both directions unit length in the upper hemisphere.
  float pdf(const Vec3& wo, const Vec3& wi) const;

 private:
  struct Node {
    bool empty = true;                  // BRDF is zero here: the node samples cosine-weighted
    std::vector<float> marginal_cdf;    // kThetaICells + 1
    std::vector<float> conditional_cdf; // kThetaICells × (kPhiCells + 1)
    std::vector<float> density;         // kThetaICells × kPhiCells, per unit solid angle
  };
  Vec3 sample_node(const Node& n, Point2 u) const;  // wi relative to wo's azimuth
  float node_density(const Node& n, const Vec3& wi_local) const;
  void node_position(float cos_theta_o, int* k, float* t) const;

  std::vector<Node> nodes_;
  float cos_edge_[kThetaICells + 1];
};

}  // namespace bxdf
