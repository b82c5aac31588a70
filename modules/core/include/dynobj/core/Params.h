// SPDX-License-Identifier: BSD-3-Clause
// Base of every stage's parameter struct: MRPT CLoadableOptions (INI sections; degrees in files,
// radians in memory) plus validate(), which names the bad key.
#pragma once

#include <mrpt/config/CLoadableOptions.h>

namespace dynobj::core {

struct StageParams : public ::mrpt::config::CLoadableOptions {
  /// Throws ParameterError("<key>: <problem>") for the first invalid value.
  virtual void validate() const = 0;
};

}  // namespace dynobj::core
