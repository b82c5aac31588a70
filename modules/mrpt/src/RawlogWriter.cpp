// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/mrptio/RawlogWriter.h"

#include <mrpt/serialization/CArchive.h>

#include <stdexcept>

namespace dynobj::mrptio {

RawlogWriter::RawlogWriter(const std::string& path, int compress_level) : file_(path) {
  if (!out_.open(file_.partial(), compress_level))
    throw std::runtime_error("cannot write '" + file_.partial() + "'");
}

RawlogWriter::~RawlogWriter() {
  out_.close();  // before PartialPath's destructor removes the partial file
}

void RawlogWriter::write(const mrpt::serialization::CSerializable& obj) {
  auto archive = mrpt::serialization::archiveFrom(out_);
  archive << obj;
}

void RawlogWriter::commit() {
  out_.close();
  file_.commit();
}

}  // namespace dynobj::mrptio
