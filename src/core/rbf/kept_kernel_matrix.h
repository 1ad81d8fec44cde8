#pragma once
// The kernel matrix of the last dense fit, kept for the next fit of the same size in this process
// (a GUI refit after an edit, the bench's repeats). A fresh n × n matrix is a fresh mapping whose
// every page the kernel zeroes on first touch; on this machine (a VM) that costs 15–45 ms for the
// 128 MB of 1 000 samples in 3D with huge pages and about 100 ms without (docs/performance.md,
// Fit speed as users meet it). A kept matrix's pages are already there: the refit only writes them.
//
// One matrix at most, between kMinKeptKernelMatrixBytes and kMaxKeptKernelMatrixBytes; safe to
// call from any thread (small fits running side by side stay below the minimum and bypass it).

#include <cstddef>

#include <Eigen/Core>

namespace hermite {

// Below this a fresh matrix costs little to fault (and partition-of-unity boxes, many at once,
// would only contend for the one kept matrix): 4 MiB, about 180 samples in 3D.
inline constexpr std::size_t kMinKeptKernelMatrixBytes = std::size_t(4) << 20;
// Above this the memory held between fits outweighs the first touches saved (a 2 000-sample 3D
// fit's 512 MiB; larger fits take seconds, of which the first touches are a few per cent).
inline constexpr std::size_t kMaxKeptKernelMatrixBytes = std::size_t(512) << 20;

// An n × n matrix with unspecified contents: the kept one when it has this size, else a fresh one
// whose whole 2 MB pages are advised for huge pages (huge_pages.h). A kept matrix of another size
// is freed first.
Eigen::MatrixXd takeKernelMatrix(Eigen::Index n);

// Keeps a square matrix whose size is within the bounds above for the next takeKernelMatrix
// (replacing one kept before); frees it otherwise.
void keepKernelMatrix(Eigen::MatrixXd&& matrix);

// Frees the kept matrix, if any; returns its bytes (0 when none was kept). Used before a memory
// check fails for want of the memory it holds, and by tests.
std::size_t releaseKeptKernelMatrix();

// Bytes of the kept matrix (0 when none).
std::size_t keptKernelMatrixBytes();

}  // namespace hermite
