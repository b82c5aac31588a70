// SPDX-License-Identifier: BSD-3-Clause
// Test tool: two rawlogs have the same entries, and every non-LiDAR observation (and every
// action collection) is byte-for-byte the same once serialized.
//   compare_rawlogs <a.rawlog> <b.rawlog>
#include <dynobj/mrptio/ObservationConverter.h>
#include <dynobj/mrptio/RawlogReader.h>
#include <mrpt/io/CMemoryStream.h>
#include <mrpt/serialization/CArchive.h>

#include <cstdio>
#include <cstring>

namespace {

std::vector<unsigned char> bytes(const mrpt::serialization::CSerializable& o) {
  mrpt::io::CMemoryStream buf;
  auto arch = mrpt::serialization::archiveFrom(buf);
  arch << o;
  const auto* p = static_cast<const unsigned char*>(buf.getRawBufferData());
  return {p, p + buf.getTotalBytesCount()};
}

}  // namespace

int main(int argc, char** argv) {
  if (argc != 3) return 2;
  try {
    dynobj::mrptio::RawlogReader a(argv[1]), b(argv[2]);
    dynobj::mrptio::RawlogEntry ea, eb;
    std::size_t compared = 0, lidar = 0;
    for (;;) {
      const bool ma = a.next(ea), mb = b.next(eb);
      if (ma != mb) {
        std::printf("different number of entries (%zu vs %zu+)\n", a.entriesRead(),
                    b.entriesRead());
        return 1;
      }
      if (!ma) break;
      if ((ea.actions != nullptr) != (eb.actions != nullptr) ||
          (ea.actions && bytes(*ea.actions) != bytes(*eb.actions))) {
        std::printf("entry %zu: actions differ\n", ea.index);
        return 1;
      }
      const auto oa = ea.observations(), ob = eb.observations();
      std::size_t j = 0;
      for (const auto& o : oa) {
        if (dynobj::mrptio::ObservationConverter::isLidarObservation(*o)) {
          lidar++;
          continue;
        }
        while (j < ob.size() && dynobj::mrptio::ObservationConverter::isLidarObservation(*ob[j]))
          j++;
        if (j >= ob.size() || bytes(*o) != bytes(*ob[j])) {
          std::printf("entry %zu: observation '%s' differs\n", ea.index, o->sensorLabel.c_str());
          return 1;
        }
        j++;
        compared++;
      }
    }
    std::printf(
        "same entries; %zu non-LiDAR observations byte-identical; %zu LiDAR observations skipped\n",
        compared, lidar);
    return 0;
  } catch (const std::exception& e) {
    std::printf("compare_rawlogs: error: %s\n", e.what());
    return 1;
  }
}
