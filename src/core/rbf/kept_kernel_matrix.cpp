#include "core/rbf/kept_kernel_matrix.h"

#include <mutex>
#include <utility>

#include "core/base/huge_pages.h"

namespace hermite {

namespace {

std::mutex& keptMutex() {
  static std::mutex m;
  return m;
}

// Guarded by keptMutex(); empty when nothing is kept.
Eigen::MatrixXd& kept() {
  static Eigen::MatrixXd matrix;
  return matrix;
}

std::size_t bytesOf(const Eigen::MatrixXd& m) { return sizeof(double) * std::size_t(m.size()); }

}  // namespace

Eigen::MatrixXd takeKernelMatrix(Eigen::Index n) {
  Eigen::MatrixXd out;
  {
    std::lock_guard<std::mutex> lock(keptMutex());
    if (kept().rows() == n && kept().cols() == n) return std::move(kept());
    // A kept matrix of another size goes before the new one is allocated (the two never coexist).
    kept() = Eigen::MatrixXd();
  }
  out.resize(n, n);
  adviseHugePages(out.data(), bytesOf(out));
  return out;
}

void keepKernelMatrix(Eigen::MatrixXd&& matrix) {
  const std::size_t bytes = bytesOf(matrix);
  if (matrix.rows() != matrix.cols() || bytes < kMinKeptKernelMatrixBytes || bytes > kMaxKeptKernelMatrixBytes)
    return;  // freed by the caller's moved-from matrix going out of scope
  Eigen::MatrixXd previous;
  std::lock_guard<std::mutex> lock(keptMutex());
  previous.swap(kept());  // freed after the lock is released
  kept() = std::move(matrix);
}

std::size_t releaseKeptKernelMatrix() {
  Eigen::MatrixXd previous;
  {
    std::lock_guard<std::mutex> lock(keptMutex());
    previous.swap(kept());
  }
  return bytesOf(previous);
}

std::size_t keptKernelMatrixBytes() {
  std::lock_guard<std::mutex> lock(keptMutex());
  return bytesOf(kept());
}

}  // namespace hermite
