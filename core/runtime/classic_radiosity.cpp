#include "runtime/classic_radiosity.h"

#include <cblas.h>

#include <string>

#include "base/error.h"
#include "transport/blas_int.h"

namespace bounce {

ClassicRadiosity::ClassicRadiosity(std::vector<float> form_factors, std::vector<glm::vec3> albedo,
                                   int bounces)
    : n_(albedo.size()),
      f_(std::move(form_factors)),
      albedo_(std::move(albedo)),
      bounces_(bounces),
      v_(n_),
      w_(n_) {
  if (f_.size() != n_ * n_)
    throw Error("classic radiosity", std::to_string(f_.size()) + " form factors for " +
                                         std::to_string(n_) + " patches");
  if (bounces_ < 1) throw Error("classic radiosity", "needs at least one bounce");
}

void ClassicRadiosity::multiply(const std::vector<glm::vec3>& b,
                                std::vector<glm::vec3>& indirect) const {
  if (b.size() != n_)
    throw Error("classic radiosity", "b has " + std::to_string(b.size()) + " entries for " +
                                         std::to_string(n_) + " patches");
  if (indirect.size() != n_) indirect.resize(n_);
  const int dim = blas_dim(n_, "cblas_sgemv");
  for (std::size_t k = 0; k < 3; ++k) {
    for (std::size_t p = 0; p < n_; ++p) {
      v_[p] = b[p][static_cast<glm::length_t>(k)];
      indirect[p][static_cast<glm::length_t>(k)] = 0.0f;
    }
    for (int h = 0; h < bounces_; ++h) {
      // w = diag(rho) F v: one more bounce of the light in v.
      cblas_sgemv(CblasRowMajor, CblasNoTrans, dim, dim, 1.0f, f_.data(), dim, v_.data(), 1, 0.0f,
                  w_.data(), 1);
      for (std::size_t p = 0; p < n_; ++p) {
        w_[p] *= albedo_[p][static_cast<glm::length_t>(k)];
        indirect[p][static_cast<glm::length_t>(k)] += w_[p];
      }
      std::swap(v_, w_);
    }
  }
}

}  // namespace bounce
