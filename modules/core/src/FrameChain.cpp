// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/core/FrameChain.h"

#include <stdexcept>
#include <string>

namespace dynobj::core {

void FrameChain::push(long index, const Eigen::Isometry3d& motion, bool reliable) {
  if (!items_.empty() && index != newest() + 1)
    throw std::invalid_argument("FrameChain: frame " + std::to_string(index) + " after " +
                                std::to_string(newest()));
  items_.push_back({index, motion, reliable});
  while (items_.size() > capacity_) items_.pop_front();
}

Eigen::Isometry3d FrameChain::between(long a, long b) const {
  if (!contains(a) || !contains(b) || a > b)
    throw std::out_of_range("FrameChain::between(" + std::to_string(a) + ", " + std::to_string(b) +
                            ")");
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  for (long i = a + 1; i <= b; i++) T = T * at(i).motion;
  return T;
}

bool FrameChain::reliable(long a, long b) const {
  for (long i = a + 1; i <= b; i++)
    if (!contains(i) || !at(i).reliable) return false;
  return true;
}

}  // namespace dynobj::core
