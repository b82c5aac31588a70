// SPDX-License-Identifier: BSD-3-Clause
// Reads the first LiDAR observation of a rawlog and prints its frame size.
#include <dynobj/mrpt/LidarObservationStream.h>

#include <iostream>

int main(int argc, char** argv) {
  if (argc != 2) return 2;
  dynobj::mrpt::LidarObservationStream stream(argv[1], dynobj::mrpt::ObservationConverter(), {});
  dynobj::mrpt::LidarObservationStream::Item item;
  if (!stream.next(item)) return 1;
  std::cout << item.frame.rows() << " x " << item.frame.cols() << " frame, "
            << item.frame.sourcePointCount() << " points\n";
  return 0;
}
