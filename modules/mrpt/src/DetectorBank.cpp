// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/mrptio/DetectorBank.h"

namespace dynobj::mrptio {

DetectorBank::DetectorBank(core::DetectorParams params) : params_(std::move(params)) {
  params_.validate();
}

core::DynamicObjectDetector& DetectorBank::detector(const std::string& sensor_label) {
  auto& d = detectors_[sensor_label];
  if (!d) d = std::make_unique<core::DynamicObjectDetector>(params_);
  return *d;
}

}  // namespace dynobj::mrptio
