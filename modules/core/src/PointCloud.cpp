// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/core/PointCloud.h"

#include <stdexcept>
#include <string>

namespace dynobj::core {
namespace {

template <typename V>
void checkSize(const V& v, std::size_t n, const char* name, bool may_be_empty) {
  if (v.size() == n || (may_be_empty && v.empty())) return;
  throw std::invalid_argument(std::string("PointCloud: '") + name + "' has " +
                              std::to_string(v.size()) + " entries but x has " + std::to_string(n));
}

}  // namespace

void PointCloud::clear() {
  x.clear();
  y.clear();
  z.clear();
  intensity.clear();
  row.clear();
  col.clear();
  ring.clear();
}

void PointCloud::reserve(std::size_t n, bool with_intensity, bool organized) {
  x.reserve(n);
  y.reserve(n);
  z.reserve(n);
  if (with_intensity) intensity.reserve(n);
  if (organized) {
    row.reserve(n);
    col.reserve(n);
  }
}

void PointCloud::push_back(float px, float py, float pz) {
  x.push_back(px);
  y.push_back(py);
  z.push_back(pz);
}

void PointCloud::push_back(float px, float py, float pz, float pi) {
  push_back(px, py, pz);
  intensity.push_back(pi);
}

void PointCloud::push_back(float px, float py, float pz, float pi, std::uint16_t prow,
                           std::uint16_t pcol) {
  push_back(px, py, pz, pi);
  row.push_back(prow);
  col.push_back(pcol);
}

void PointCloud::validate() const {
  const std::size_t n = x.size();
  checkSize(y, n, "y", false);
  checkSize(z, n, "z", false);
  checkSize(intensity, n, "intensity", true);
  checkSize(row, n, "row", true);
  checkSize(col, n, "col", true);
  checkSize(ring, n, "ring", true);
  if (row.empty() != col.empty())
    throw std::invalid_argument("PointCloud: 'row' and 'col' must be both set or both empty");
}

}  // namespace dynobj::core
