// SPDX-License-Identifier: BSD-3-Clause
// Test tool: two rawlogs have the same entries, and every non-LiDAR observation (and every
// action collection) is byte-for-byte the same once serialized; with --all every observation,
// LiDAR ones included (e.g. the pipelined rawlog-dynobj against the single-threaded one).
//   compare_rawlogs [--all] <a.rawlog> <b.rawlog>
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
  const bool all = argc == 4 && std::strcmp(argv[1], "--all") == 0;
  if (argc != 3 && !all) return 2;
  try {
    dynobj::mrptio::RawlogReader a(argv[argc - 2]), b(argv[argc - 1]);
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
      if (all) {
        if (oa.size() != ob.size()) {
          std::printf("entry %zu: %zu vs %zu observations\n", ea.index, oa.size(), ob.size());
          return 1;
        }
        for (std::size_t k = 0; k < oa.size(); k++) {
          if (bytes(*oa[k]) != bytes(*ob[k])) {
            std::printf("entry %zu: observation '%s' differs\n", ea.index,
                        oa[k]->sensorLabel.c_str());
            return 1;
          }
          const bool is_lidar = dynobj::mrptio::ObservationConverter::isLidarObservation(*oa[k]);
          lidar += is_lidar;
          compared += !is_lidar;
        }
        continue;
      }
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
    if (all)
      std::printf("same entries; all %zu observations byte-identical (%zu LiDAR)\n",
                  compared + lidar, lidar);
    else
      std::printf(
          "same entries; %zu non-LiDAR observations byte-identical; %zu LiDAR observations "
          "skipped\n",
          compared, lidar);
    return 0;
  } catch (const std::exception& e) {
    std::printf("compare_rawlogs: error: %s\n", e.what());
    return 1;
  }
}
