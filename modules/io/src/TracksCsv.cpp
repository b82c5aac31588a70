// SPDX-License-Identifier: BSD-3-Clause
#include "dynobj/io/TracksCsv.h"

namespace dynobj::io {

TracksCsvWriter::TracksCsvWriter(const std::string& path) : file_(path) {
  file_.stream() << "timestamp_ns,sensor_label,id,dynamic,age,points,x,y,z,vx,vy,min_x,min_y,"
                    "min_z,max_x,max_y,max_z\n";
}

void TracksCsvWriter::write(const std::string& sensor_label, const core::DetectionResult& r) {
  auto& o = file_.stream();
  for (const core::TrackedObject& t : r.objects)
    o << r.timestamp_ns << ',' << sensor_label << ',' << t.id << ',' << (t.dynamic ? 1 : 0) << ','
      << t.age << ',' << t.points << ',' << t.centroid.x() << ',' << t.centroid.y() << ','
      << t.centroid.z() << ',' << t.velocity.x() << ',' << t.velocity.y() << ',' << t.box_min.x()
      << ',' << t.box_min.y() << ',' << t.box_min.z() << ',' << t.box_max.x() << ','
      << t.box_max.y() << ',' << t.box_max.z() << '\n';
}

}  // namespace dynobj::io
