// SPDX-License-Identifier: BSD-3-Clause
// A simulated sequence: static scene, moving actors, the sensor platform's motion and the LiDAR
// model. Loaded from share/dynobj/scenarios/*.yaml (format: docs/simulator.md).
#pragma once

#include <dynobj/core/SensorModel.h>

#include <Eigen/Core>
#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "dynobj/sim/PoseTrack.h"
#include "dynobj/sim/Shapes.h"
#include "dynobj/sim/Texture.h"

namespace dynobj::sim {

/// A bad scenario file or override; what() names the file and the key path.
class ScenarioError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

enum class ActorClass { Pedestrian, Cyclist, Car };
const char* toString(ActorClass c);

/// What the intensity channel holds: Ouster signal (photon counts, range-dependent, near-field
/// suppression) or Velodyne calibrated reflectivity (0-255, 0-100 for diffuse surfaces).
enum class IntensityModel { Ouster, Velodyne };
/// How sweeps are written: organized CObservation3DRangeScan, or an unordered
/// CObservationPointCloud (x y z + remission 0-1) laser by laser in firing order, KITTI-style.
enum class OutputFormat { RangeScan, PointCloud };

/// One part of a static object or an actor, in its owner's frame (actors) or the world. Actors
/// are made of boxes and cylinders only; foliage and fences are static clutter.
struct Part {
  enum class Kind { Box, Cylinder, Porous, Fence } kind = Kind::Box;
  Box box;
  Cylinder cylinder;
  Porous porous;
  Fence fence;
  Material material;
  double sway = 0;       ///< [m] amplitude of the horizontal sway of foliage (wind)
  double sway_hz = 0.3;  ///< [Hz] its frequency
  /// [m] a walker's limb swings along the actor's x by this much at walking speed (legs and arms,
  /// the sign giving the side); 0 = rigid.
  double swing = 0;
};

/// Traits of real sensors that make the judge harder (`realism:`, docs/simulator.md gives each
/// default and the real capture or manual it comes from). All off unless asked for;
/// `realism: harsh` turns each on at its default.
struct Realism {
  /// [rad] horizontal width of a beam's footprint; > 0: a footprint straddling a depth edge
  /// returns one mixed echo (surfaces closer than `echo_separation` in range) or the stronger.
  double beam_divergence = 0;
  double echo_separation = 1.0;  ///< [m] two surfaces closer than this give one mixed echo
  /// Share of depth edges (jumps over `echo_separation`) with a point somewhere in between.
  double interstitial = 0;
  /// Spread (sigma of the log) of each beam's intensity gain: a unit's lasers differ.
  double beam_gain_sigma = 0;
  std::vector<double> beam_gain;  ///< drawn per image row from the seed (empty = all 1)
  bool retro_reflectors = false;  ///< licence plates on cars, far brighter than a white wall
  /// No-returns in runs along a row: the share of pixels lost and the mean run [pixels].
  double dropout_runs = 0;
  double dropout_run_length = 4.5;
  double packet_loss = 0;   ///< probability that a lost burst of packets starts at a packet
  double packet_burst = 1;  ///< mean packets lost in one burst (geometric)
  int packet_columns = 16;  ///< columns in one packet (Ouster 16, Velodyne 384 / rows)
  bool gait = false;        ///< walkers swing their legs and arms
  /// [rad] a platform without `bob` rolls and pitches on its suspension: the standard deviation
  /// of the change per sweep at 10 Hz.
  double body_motion = 0;
};

struct Actor {
  int id = 0;
  ActorClass cls = ActorClass::Pedestrian;
  std::vector<Part> parts;  ///< in the actor frame: x forward, origin on the ground
  PoseTrack track;
};

struct Scenario {
  std::string name = "scenario";
  std::uint32_t seed = 1;
  int frames = 300;           ///< sweeps to simulate
  double start_time = 1.7e9;  ///< [s, Unix] timestamp of sweep 0
  core::SensorModel sensor;   ///< from `sensor:` (a preset path under share/dynobj)
  std::string sensor_label = "LIDAR";
  Eigen::Vector3d mount{0, 0, 0.6};   ///< sensor position on the robot [m]
  double range_sigma = 0.02;          ///< [m] Gaussian range noise
  double dropout = 0.003;             ///< random no-return probability
  double grazing_cos = 0.08;          ///< incidence cosine below which most returns drop
  double intensity_gain = 700;        ///< signal of a white (reflectivity 1) wall at 10-50 m
  double intensity_noise = 0.08;      ///< relative signal noise
  double intensity_near_range = 1.5;  ///< [m] signal is suppressed below about this range
  IntensityModel intensity_model = IntensityModel::Ouster;
  OutputFormat output = OutputFormat::RangeScan;
  /// This unit's beams: per image row, the error of its elevation and azimuth from the preset's
  /// nominal table [rad], drawn from the seed (`sensor_unit:`); empty = a perfect unit.
  std::vector<double> beam_elevation_error, beam_azimuth_error;
  Realism realism;
  bool motion_distortion = false;   ///< columns fired over the sweep while everything moves
  double moving_speed = 0.2;        ///< [m/s] an actor faster than this is "dynamic"
  bool odometry = true;             ///< also write CObservationOdometry
  double odometry_sigma_xy = 0.01;  ///< [m per sweep]
  double odometry_sigma_yaw = 0.2 * M_PI / 180;  ///< [rad per sweep]

  Floor floor;
  Material floor_material;
  std::vector<Part> statics;
  std::vector<Actor> actors;

  PoseTrack platform;
  double bob_height = 0.0;  ///< [m] amplitude of the vertical bobbing (legged robot)
  double bob_roll = 0.0;    ///< [rad] amplitudes
  double bob_pitch = 0.0;
  double bob_hz = 2.0;  ///< step frequency

  /// The world a `procedural:` block generated (YAML: floor, static, actors, platform), empty
  /// for hand-written scenes. Writing it out freezes that world into a plain scenario.
  std::string world_yaml;

  double period() const { return 1.0 / sensor.frequency; }
  double duration() const { return frames * period(); }

  /// Loads a scenario. `share_dir` resolves `sensor:` paths; `overrides` are "key.path=value"
  /// pairs applied to the YAML before it is read (e.g. {"seed", "7"}, {"frames", "60"}).
  /// Throws ScenarioError naming the file and key.
  static Scenario fromYamlFile(const std::string& path, const std::string& share_dir,
                               const std::map<std::string, std::string>& overrides = {});
  static Scenario fromYamlText(const std::string& text, const std::string& share_dir,
                               const std::map<std::string, std::string>& overrides = {},
                               const std::string& source = "scenario");
};

/// The body of an actor class, scaled to `height` [m]; `realism` adds swinging limbs (gait) and
/// licence plates (retro-reflectors).
std::vector<Part> actorBody(ActorClass cls, double height, const Material& material,
                            const Realism& realism = {});

}  // namespace dynobj::sim
