#include "dynamic/local_transport.h"

#include <cblas.h>

#include <algorithm>
#include <string>

#include "base/error.h"
#include "transport/blas_int.h"

namespace bounce {

LocalTransport::LocalTransport(std::vector<float> t, std::size_t n, std::vector<bool> active)
    : n_(n), t_(std::move(t)), active_(std::move(active)), u_(n), v_(n), a_(n), b_(n) {
  if (t_.size() != n_ * n_)
    throw Error("local transport", std::to_string(t_.size()) + " matrix entries for " +
                                       std::to_string(n_) + " patches");
  if (active_.size() != n_)
    throw Error("local transport", std::to_string(active_.size()) + " active flags for " +
                                       std::to_string(n_) + " patches");
  for (std::size_t i = 0; i < n_; ++i)
    for (std::size_t j = 0; j < n_; ++j)
      if ((!active_[i] || !active_[j]) && t_[i * n_ + j] != 0.0f)
        throw Error("local transport", "entry (" + std::to_string(i) + ", " + std::to_string(j) +
                                           ") of an inactive patch is not zero");
}

void LocalTransport::check_index(std::size_t k, const char* what) const {
  if (k >= n_)
    throw Error("local transport", std::string(what) + ": patch " + std::to_string(k) +
                                       " out of range (" + std::to_string(n_) + " patches)");
}

double LocalTransport::add_patch(std::size_t k, const std::vector<float>& column,
                                 const std::vector<float>& row) {
  check_index(k, "add");
  if (active_[k]) throw Error("local transport", "add: patch " + std::to_string(k) + " is active");
  if (column.size() != n_ || row.size() != n_)
    throw Error("local transport", "add: column and row need " + std::to_string(n_) + " entries");
  for (std::size_t i = 0; i < n_; ++i) {
    const bool use = active_[i] && i != k;
    u_[i] = use ? column[i] : 0.0f;
    v_[i] = use ? row[i] : 0.0f;
  }
  const int dim = blas_dim(n_, "cblas_sgemv");
  // a = (T + I) u, b = v (T + I): T u and T^T v, then + u and + v.
  a_ = u_;
  b_ = v_;
  cblas_sgemv(CblasRowMajor, CblasNoTrans, dim, dim, 1.0f, t_.data(), dim, u_.data(), 1, 1.0f,
              a_.data(), 1);
  cblas_sgemv(CblasRowMajor, CblasTrans, dim, dim, 1.0f, t_.data(), dim, v_.data(), 1, 1.0f,
              b_.data(), 1);
  double sigma = 0.0;
  for (std::size_t i = 0; i < n_; ++i) sigma += static_cast<double>(v_[i]) * a_[i];
  if (!(sigma < 1.0))
    throw Error("local transport", "add: patch " + std::to_string(k) + " returns a share " +
                                       std::to_string(sigma) +
                                       " >= 1 of its light (no bounded solution)");
  const double scale = 1.0 / (1.0 - sigma);
  // a_k = b_k = 0 (row and column k of T are zero, u_k = v_k = 0): one outer
  // product with a~ = a + e_k, b~ = b + e_k also writes the new row and
  // column, a / (1 - sigma) and b / (1 - sigma).
  a_[k] = 1.0f;
  b_[k] = 1.0f;
  cblas_sger(CblasRowMajor, dim, dim, static_cast<float>(scale), a_.data(), 1, b_.data(), 1,
             t_.data(), dim);
  // The diagonal directly: 1 / (1 - sigma) - 1 would cancel digits.
  t_[k * n_ + k] = static_cast<float>(sigma * scale);
  active_[k] = true;
  return sigma;
}

void LocalTransport::remove_patch(std::size_t k) {
  check_index(k, "remove");
  if (!active_[k])
    throw Error("local transport", "remove: patch " + std::to_string(k) + " is not active");
  for (std::size_t i = 0; i < n_; ++i) {
    a_[i] = t_[i * n_ + k];
    b_[i] = t_[k * n_ + i];
  }
  const double pivot = 1.0 + static_cast<double>(t_[k * n_ + k]);
  const int dim = blas_dim(n_, "cblas_sger");
  cblas_sger(CblasRowMajor, dim, dim, static_cast<float>(-1.0 / pivot), a_.data(), 1, b_.data(), 1,
             t_.data(), dim);
  for (std::size_t i = 0; i < n_; ++i) {
    t_[i * n_ + k] = 0.0f;
    t_[k * n_ + i] = 0.0f;
  }
  active_[k] = false;
}

void transport_column_and_row(const float* f, const std::vector<float>& rho, std::size_t k,
                              std::vector<float>& column, std::vector<float>& row) {
  const std::size_t n = rho.size();
  if (k >= n) throw Error("local transport", "patch " + std::to_string(k) + " out of range");
  column.resize(n);
  row.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    column[i] = rho[i] * f[i * n + k];
    row[i] = rho[k] * f[k * n + i];
  }
}

}  // namespace bounce
