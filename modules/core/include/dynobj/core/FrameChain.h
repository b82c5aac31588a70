// SPDX-License-Identifier: BSD-3-Clause
// The frame-to-frame transforms T_{i-1<-i} of the last frames, so that any centroid of a sliding
// window can be expressed in the window's first frame (paper Eq. 14-17). Bounded memory.
#pragma once

#include <Eigen/Geometry>
#include <deque>

namespace dynobj::core {

class FrameChain {
 public:
  explicit FrameChain(std::size_t capacity = 64) : capacity_(capacity) {}

  /// Appends frame `index` (consecutive) with T_{index-1<-index}; `reliable` = ego-motion ok.
  void push(long index, const Eigen::Isometry3d& motion, bool reliable);
  void clear() { items_.clear(); }

  bool contains(long index) const {
    return !items_.empty() && index >= oldest() && index <= newest();
  }
  long oldest() const { return items_.front().index; }
  long newest() const { return items_.back().index; }

  /// Eq. (16): T_{a<-b} = T_{a<-a+1} ... T_{b-1<-b}, for oldest() <= a <= b <= newest().
  Eigen::Isometry3d between(long a, long b) const;
  /// True when every motion in (a, b] was reliable.
  bool reliable(long a, long b) const;

 private:
  struct Item {
    long index;
    Eigen::Isometry3d motion;
    bool reliable;
  };
  const Item& at(long index) const { return items_[static_cast<std::size_t>(index - oldest())]; }
  std::size_t capacity_;
  std::deque<Item> items_;
};

}  // namespace dynobj::core
