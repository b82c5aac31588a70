// SPDX-License-Identifier: BSD-3-Clause
// The Python module `dynobj` (docs/python.md): the library's detector, offline sequence loop and
// frame readers on numpy arrays. Glue only: parameters and presets through the library's strict
// readers, sweeps through ArraySweeps (the library's conversions), the offline mode through
// mrptio::SequenceRunner (one step per frame), errors as Python exceptions (std::invalid_argument
// and core::ParameterError: ValueError), faults of the data (core::FrameCheck) as Python warnings
// (dynobj.DataFaultWarning), the GIL released while the library works.
#include <dynobj/core/Config.h>
#include <dynobj/core/DynamicObjectDetector.h>
#include <dynobj/io/IniFile.h>
#include <dynobj/io/SemanticKittiLabel.h>
#include <dynobj/io/SensorFile.h>
#include <dynobj/mrptio/OpenFrameSource.h>
#include <dynobj/mrptio/SequenceRunner.h>
#include <mrpt/config/CConfigFileMemory.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <deque>
#include <limits>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "ArraySweeps.h"

namespace py = pybind11;

namespace dynobj::python {
namespace {

/// A path given as str or os.PathLike.
std::string pathOf(const py::handle& o) {
  return py::str(py::module_::import("os").attr("fspath")(o)).cast<std::string>();
}

bool isPath(const py::handle& o) {
  return py::isinstance<py::str>(o) || py::hasattr(o, "__fspath__");
}

/// An INI value from a Python value: booleans as true/false, sequences space-separated.
std::string iniValue(const std::string& key, const py::handle& v) {
  if (py::isinstance<py::bool_>(v)) return v.cast<bool>() ? "true" : "false";
  if (py::isinstance<py::str>(v)) return v.cast<std::string>();
  if (py::isinstance<py::int_>(v) || py::isinstance<py::float_>(v)) return py::str(v);
  if (py::isinstance<py::list>(v) || py::isinstance<py::tuple>(v)) {
    std::string out;
    for (const py::handle& e : v) out += (out.empty() ? "" : " ") + iniValue(key, e);
    return out;
  }
  throw std::invalid_argument("config: '" + key + "' has a value of type " +
                              py::str(py::type::of(v).attr("__name__")).cast<std::string>() +
                              " (give a number, a bool, a string or a list)");
}

/// {"section.key": value}: each key checked against the detector's sections and keys (the
/// nearest one named), then read by the library's readers as an INI file would be.
core::DetectorParams paramsOfDict(const py::dict& d) {
  core::DetectorParams p;
  std::vector<std::string> sections;
  std::vector<std::vector<std::string>> keys;
  p.forEachStage([&](const char* name, core::StageParams& stage) {
    sections.push_back(name);
    keys.push_back(stage.keys());
  });
  mrpt::config::CConfigFileMemory mem;
  for (const auto& [k, v] : d) {
    if (!py::isinstance<py::str>(k))
      throw std::invalid_argument("config: the key " + py::repr(k).cast<std::string>() +
                                  " is not a string 'section.key'");
    const std::string full = k.cast<std::string>();
    const std::size_t dot = full.find('.');
    if (dot == std::string::npos)
      throw std::invalid_argument("config: key '" + full + "' is not 'section.key'");
    const std::string section = full.substr(0, dot), key = full.substr(dot + 1);
    std::size_t s = 0;
    while (s < sections.size() && sections[s] != section) s++;
    if (s == sections.size()) {
      const std::string near = core::closestName(section, sections);
      throw std::invalid_argument("config: unknown section '" + section + "' in '" + full + "'" +
                                  (near.empty() ? "" : " (did you mean '" + near + "'?)"));
    }
    bool known = false;
    for (const std::string& name : keys[s]) known = known || name == key;
    if (!known) {
      const std::string near = core::closestName(key, keys[s]);
      throw std::invalid_argument(
          "config: unknown key '" + full + "'" +
          (near.empty() ? "" : " (did you mean '" + section + "." + near + "'?)"));
    }
    mem.write(section, key, iniValue(full, v));
  }
  p.load(mem);
  return p;
}

core::DetectorParams paramsOf(const py::object& config) {
  core::DetectorParams p;
  if (config.is_none()) {
  } else if (py::isinstance<py::dict>(config)) {
    p = paramsOfDict(config.cast<py::dict>());
  } else if (isPath(config)) {
    p = io::loadDetectorParams(pathOf(config));
  } else {
    throw std::invalid_argument(
        "config: give None, an INI file path or a dict {'section.key': "
        "value}, not " +
        py::str(py::type::of(config).attr("__name__")).cast<std::string>());
  }
  p.validate();
  return p;
}

std::optional<core::SensorModel> sensorOf(const py::object& sensor) {
  if (sensor.is_none()) return std::nullopt;
  if (!isPath(sensor))
    throw std::invalid_argument("sensor: give None or the path of a sensor preset INI");
  return io::readSensorModel(pathOf(sensor));
}

/// The checked view of a points array (float32/float64, (N, 4) or (rows, cols, 4)); `keep`
/// receives the C-ordered array the view reads (a copy when the input was not C-ordered).
ArrayView viewOf(const py::handle& points, py::array& keep) {
  if (!py::isinstance<py::array>(points))
    throw std::invalid_argument("points: expected a numpy array, got " +
                                py::str(py::type::of(points).attr("__name__")).cast<std::string>());
  py::array a = py::reinterpret_borrow<py::array>(points);
  const bool f32 = a.dtype().is(py::dtype::of<float>());
  const bool f64 = a.dtype().is(py::dtype::of<double>());
  if (!f32 && !f64)
    throw std::invalid_argument("points: dtype " + py::str(a.dtype()).cast<std::string>() +
                                ", expected float32 or float64");
  std::string shape;
  for (py::ssize_t i = 0; i < a.ndim(); i++) shape += (i ? ", " : "") + std::to_string(a.shape(i));
  if (a.ndim() == 1) shape += ",";
  const bool unordered = a.ndim() == 2 && a.shape(1) == 4;
  const bool organized = a.ndim() == 3 && a.shape(2) == 4;
  if (!unordered && !organized)
    throw std::invalid_argument("points: shape (" + shape +
                                "), expected (N, 4) or (rows, cols, 4): x, y, z, intensity");
  keep = f32 ? py::array(py::array_t<float, py::array::c_style>::ensure(a))
             : py::array(py::array_t<double, py::array::c_style>::ensure(a));
  ArrayView v;
  v.data = keep.data();
  v.is_double = f64;
  v.rows = static_cast<std::size_t>(a.shape(0));
  v.cols = organized ? static_cast<std::size_t>(a.shape(1)) : 0;
  return v;
}

/// A timestamp: seconds (a number) or a numpy.datetime64 (exact to the nanosecond).
std::int64_t nanosecondsOf(const py::handle& t) {
  const py::module_ np = py::module_::import("numpy");
  if (py::isinstance(t, np.attr("datetime64"))) {
    if (py::bool_(np.attr("isnat")(t))) throw std::invalid_argument("timestamp: NaT is not a time");
    return t.attr("astype")("datetime64[ns]").attr("astype")("int64").cast<std::int64_t>();
  }
  if (py::isinstance<py::bool_>(t) || !(py::isinstance<py::float_>(t) ||
                                        py::isinstance<py::int_>(t) || py::hasattr(t, "__float__")))
    throw std::invalid_argument(
        "timestamp: expected seconds (a number) or a numpy.datetime64, got " +
        py::str(py::type::of(t).attr("__name__")).cast<std::string>());
  const double s = py::float_(py::reinterpret_borrow<py::object>(t)).cast<double>();
  if (!std::isfinite(s) || std::fabs(s) * 1e9 >= 9.2e18)
    throw std::invalid_argument("timestamp: " + py::repr(t).cast<std::string>() +
                                " s is not a usable time");
  return std::llround(s * 1e9);
}

py::object datetime64(std::int64_t ns) {
  return py::module_::import("numpy").attr("datetime64")(ns, "ns");
}

py::array maskArray(const Mask& m) {
  std::vector<py::ssize_t> shape{static_cast<py::ssize_t>(m.rows)};
  if (m.cols > 0) shape.push_back(static_cast<py::ssize_t>(m.cols));
  py::array_t<bool> out(shape);
  if (!m.values.empty()) std::memcpy(out.mutable_data(), m.values.data(), m.values.size());
  return std::move(out);
}

py::dict timingsDict(const core::StageTimings& t) {
  py::dict d;
  d["foreground"] = t.foreground;
  d["ego_motion"] = t.ego_motion;
  d["ground"] = t.ground;
  d["clustering"] = t.clustering;
  d["association"] = t.association;
  d["movement"] = t.movement;
  d["region_growing"] = t.region_growing;
  d["hindsight"] = t.hindsight;
  d["total"] = t.total;
  return d;
}

/// dynobj.DataFaultWarning (a UserWarning), set when the module is loaded.
PyObject* data_fault_warning = nullptr;

/// The faults of the data FrameCheck found in a sweep, as Python warnings (as the tools print
/// them on stderr): "sweep 12: the same ranges as the sweep before: the sweep is not used".
void warnFaults(const std::vector<std::string>& texts) {
  for (const std::string& t : texts)
    if (PyErr_WarnEx(data_fault_warning, t.c_str(), 1) != 0) throw py::error_already_set();
}

std::vector<std::string> faultTexts(const core::DetectionResult& r) {
  std::vector<std::string> out;
  for (const core::FrameWarning& w : r.warnings) out.push_back(w.text());
  return out;
}

py::list tracksList(const std::vector<core::TrackedObject>& objects) {
  py::list out;
  for (const core::TrackedObject& o : objects) {
    const Eigen::Vector3d centre = 0.5 * (o.box_min + o.box_max), size = o.box_max - o.box_min;
    py::dict d;
    d["id"] = o.id;
    d["box"] = py::dict(py::arg("center") = py::make_tuple(centre.x(), centre.y(), centre.z()),
                        py::arg("size") = py::make_tuple(size.x(), size.y(), size.z()));
    d["centroid"] = py::make_tuple(o.centroid.x(), o.centroid.y(), o.centroid.z());
    d["velocity"] = py::make_tuple(o.velocity.x(), o.velocity.y());
    d["dynamic"] = o.dynamic;
    d["at_rest"] = o.at_rest;
    d["points"] = o.points;
    d["age"] = o.age;
    out.append(std::move(d));
  }
  return out;
}

/// dynobj.Detector: online (causal), one sweep at a time.
class Detector {
 public:
  Detector(const py::object& config, const py::object& sensor)
      : detector_(paramsOf(config)), sweeps_(sensorOf(sensor)) {}

  py::array process(const py::handle& points, const py::handle& timestamp) {
    py::array keep;
    const ArrayView view = viewOf(points, keep);
    const std::int64_t ns = nanosecondsOf(timestamp);
    Mask mask;
    std::vector<std::string> faults;
    {
      py::gil_scoped_release free;
      const std::lock_guard<std::mutex> lock(mutex_);
      const auto start = std::chrono::steady_clock::now();
      sweeps_.convert(view, ns, frame_);
      conversion_ms_ =
          std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
              .count();
      last_ = &detector_.process(frame_.frame);
      mask = ArraySweeps::maskOf(frame_, last_->dynamic);
      faults = faultTexts(*last_);
    }
    warnFaults(faults);
    return maskArray(mask);
  }

  py::list tracks() const { return last_ ? tracksList(last_->objects) : py::list(); }
  py::dict timings() const {
    if (!last_) return py::dict();
    py::dict d = timingsDict(last_->timings);
    d["conversion"] = conversion_ms_;
    return d;
  }

 private:
  core::DynamicObjectDetector detector_;
  ArraySweeps sweeps_;
  mrptio::Frame frame_;
  const core::DetectionResult* last_ = nullptr;
  double conversion_ms_ = 0;  ///< the last sweep's array -> frame conversion (not in 'total')
  std::mutex mutex_;
};

/// The sweeps of a Python iterable, one at a time, as SequenceRunner's source.
class IterableSource final : public mrptio::FrameSource {
 public:
  explicit IterableSource(std::optional<core::SensorModel> sensor) : sweeps_(std::move(sensor)) {}
  /// The next sweep (the array must stay alive until next() took it); none = the end.
  void give(const ArrayView& v, std::int64_t ns) {
    view_ = v;
    ns_ = ns;
    pending_ = true;
  }
  bool next(mrptio::Frame& f) override {
    if (!pending_) return false;
    pending_ = false;
    sweeps_.convert(view_, ns_, f);
    return true;
  }
  void rewind() override { throw std::logic_error("a Python iterable cannot be rewound"); }
  std::string describe() const override { return "the sweeps given to process_sequence"; }

 private:
  ArraySweeps sweeps_;
  ArrayView view_;
  std::int64_t ns_ = 0;
  bool pending_ = false;
};

/// dynobj.process_sequence(...): SequenceRunner over the iterable, stepped as Python asks for
/// masks: each mask comes once its sweep has been held for the hindsight lag.
class Sequence {
 public:
  Sequence(const py::iterable& sweeps, const py::object& config, const py::object& sensor)
      : it_(py::iter(sweeps)), source_(sensorOf(sensor)), runner_(source_, optionsOf(config)) {}

  py::array next() {
    while (ready_.empty()) {
      if (done_) throw py::stop_iteration();
      py::array keep;
      try {
        const py::object item = py::reinterpret_steal<py::object>(PyIter_Next(it_.ptr()));
        if (PyErr_Occurred()) throw py::error_already_set();
        if (item) {
          if (!py::isinstance<py::tuple>(item) && !py::isinstance<py::list>(item))
            throw std::invalid_argument("sweep " + std::to_string(given_) +
                                        ": expected a (points, timestamp) pair");
          const py::sequence pair = item.cast<py::sequence>();
          if (pair.size() != 2)
            throw std::invalid_argument("sweep " + std::to_string(given_) +
                                        ": expected a (points, timestamp) pair, got " +
                                        std::to_string(pair.size()) + " items");
          source_.give(viewOf(pair[0], keep), nanosecondsOf(pair[1]));
          given_++;
        }
        py::gil_scoped_release free;
        done_ = !runner_.step([&](const mrptio::FrameResult& fr) {
          ready_.push_back(Ready{ArraySweeps::maskOf(fr.frame, fr.detection->dynamic),
                                 faultTexts(*fr.detection)});
        });
      } catch (...) {
        done_ = true;  // a sequence that failed gives no further mask
        ready_.clear();
        throw;
      }
    }
    Ready r = std::move(ready_.front());
    ready_.pop_front();
    try {
      warnFaults(r.faults);
    } catch (...) {  // warnings made errors: the sequence ends here, as on any error
      done_ = true;
      ready_.clear();
      throw;
    }
    return maskArray(r.mask);
  }

 private:
  static mrptio::SequenceOptions optionsOf(const py::object& config) {
    mrptio::SequenceOptions o;
    o.detector = paramsOf(config);
    o.single_sensor = true;
    o.require_frames = false;
    return o;
  }

  struct Ready {  ///< a released sweep: its mask and its data's faults
    Mask mask;
    std::vector<std::string> faults;
  };

  py::iterator it_;
  IterableSource source_;
  mrptio::SequenceRunner runner_;
  std::deque<Ready> ready_;
  std::size_t given_ = 0;
  bool done_ = false;
};

/// dynobj.read_sweeps(input): the sweeps of a rawlog or a folder of PCD / .bin files as the
/// tools read them.
class SweepReader {
 public:
  SweepReader(const py::object& input, const py::object& sensor, const std::string& label)
      : opened_(mrptio::openFrameSource(pathOf(input), sensorOf(sensor), label)) {}

  py::tuple next() {
    bool more = false;
    {
      py::gil_scoped_release free;
      more = opened_.source->next(f_);
      if (more) read_++;
    }
    if (!more) {
      if (read_ == 0)
        throw std::runtime_error("no LiDAR observation in " + opened_.source->describe() +
                                 opened_.source->noFramesDetail());
      throw py::stop_iteration();
    }
    const py::object t = datetime64(f_.frame.timestamp_ns);
    if (!f_.points.empty()) {  // a point-cloud file: its points in its order, sensor frame
      const core::PointCloud& c = f_.points;
      py::array_t<float> a({static_cast<py::ssize_t>(c.size()), py::ssize_t{4}});
      float* p = a.mutable_data();
      for (std::size_t i = 0; i < c.size(); i++, p += 4) {
        p[0] = c.x[i];
        p[1] = c.y[i];
        p[2] = c.z[i];
        p[3] = c.hasIntensity() ? c.intensity[i] : 0.0f;
      }
      return py::make_tuple(std::move(a), t);
    }
    const core::LidarFrame& fr = f_.frame;  // an image: one point per pixel, NaN where none
    py::array_t<float> a(
        {static_cast<py::ssize_t>(fr.rows()), static_cast<py::ssize_t>(fr.cols()), py::ssize_t{4}});
    float* p = a.mutable_data();
    const float nan = std::numeric_limits<float>::quiet_NaN();
    for (int r = 0; r < fr.rows(); r++)
      for (int c = 0; c < fr.cols(); c++, p += 4) {
        const bool v = fr.isValid(r, c);
        const cv::Vec3f& q = fr.xyz(r, c);
        p[0] = v ? q[0] : nan;
        p[1] = v ? q[1] : nan;
        p[2] = v ? q[2] : nan;
        p[3] = v ? fr.intensity(r, c) : nan;
      }
    return py::make_tuple(std::move(a), t);
  }

 private:
  mrptio::OpenedFrameSource opened_;
  mrptio::Frame f_;
  std::size_t read_ = 0;
};

}  // namespace
}  // namespace dynobj::python

PYBIND11_MODULE(dynobj, m) {
  using namespace dynobj::python;
  m.doc() =
      "Moving-object detection in 3D LiDAR sweeps (mrpt-dynobj, Du & Beltrame). See "
      "docs/python.md.";
  m.attr("__version__") = DYNOBJ_VERSION;
  m.attr("SEMANTIC_KITTI_STATIC") = dynobj::io::semantic_kitti::kStatic;
  m.attr("SEMANTIC_KITTI_MOVING") = dynobj::io::semantic_kitti::kMoving;
  // The module's attribute holds the class (the pointer stays valid while the module lives).
  const py::object fault_warning = py::reinterpret_steal<py::object>(PyErr_NewExceptionWithDoc(
      "dynobj.DataFaultWarning",
      "A fault of the data (docs/usage.md, 'Faults of the data'): a duplicate sweep (the same "
      "ranges as the sweep before: not used, its mask is the sweep before's), a time jump (the "
      "tracks start anew), missing sweeps, lost columns, ... The message names the sweep "
      "(0-based, every sweep given). Timestamps that do not increase are a ValueError.",
      PyExc_UserWarning, nullptr));
  if (!fault_warning) throw py::error_already_set();
  m.attr("DataFaultWarning") = fault_warning;
  data_fault_warning = fault_warning.ptr();

  py::class_<Detector>(m, "Detector",
                       "The detector, online (causal): one sweep at a time, in time order.")
      .def(py::init<const py::object&, const py::object&>(), py::arg("config") = py::none(),
           py::arg("sensor") = py::none(),
           "config: None (defaults), the path of an INI file (share/dynobj/config/dynobj.ini) or "
           "a dict {'section.key': value}; sensor: None (rows recovered from the data) or the "
           "path of a sensor preset INI (share/dynobj/sensors/*.ini).")
      .def("process", &Detector::process, py::arg("points"), py::arg("timestamp"),
           "points: (N, 4) or (rows, cols, 4) float32/float64 array of x, y, z [m] (sensor "
           "frame) and intensity; timestamp: seconds or a numpy.datetime64, after the previous "
           "sweep's. Returns the moving "
           "points: a bool mask (N,) in input order, or (rows, cols).")
      .def("tracks", &Detector::tracks,
           "The objects tracked in the last sweep: dicts with id, box (center, size) [m], "
           "centroid [m], velocity (vx, vy) [m/s], dynamic, at_rest, points, age.")
      .def("timings", &Detector::timings,
           "The last sweep's time per stage [ms]: the detector's stages and their 'total' (as "
           "dynobj-detect -v reports it), and 'conversion', the array's conversion into the "
           "detector's frame before it (rows recovered, projected; not in 'total').");

  py::class_<Sequence>(m, "Sequence")
      .def("__iter__", [](py::object self) { return self; })
      .def("__next__", &Sequence::next);
  m.def(
      "process_sequence",
      [](const py::iterable& sweeps, const py::object& config, const py::object& sensor) {
        return std::make_unique<Sequence>(sweeps, config, sensor);
      },
      py::arg("sweeps"), py::arg("config") = py::none(), py::arg("sensor") = py::none(),
      "Offline, as dynobj-detect: each sweep of the iterable of (points, timestamp) is held for "
      "the hindsight lag ([hindsight] lag, 1 s; 0 = online) so that tracks confirmed later flag "
      "it too. Yields one mask per sweep, in order.");

  py::class_<SweepReader>(m, "SweepReader")
      .def("__iter__", [](py::object self) { return self; })
      .def("__next__", &SweepReader::next);
  m.def(
      "read_sweeps",
      [](const py::object& input, const py::object& sensor, const std::string& sensor_label) {
        return std::make_unique<SweepReader>(input, sensor, sensor_label);
      },
      py::arg("input"), py::arg("sensor") = py::none(), py::arg("sensor_label") = "",
      "The sweeps of a rawlog or a folder of .pcd / .bin files, as the tools read them: yields "
      "(points, timestamp) with the timestamp a numpy.datetime64 [ns]; a folder's sweeps as (N, 4) "
      "float32 (the file's points in its "
      "order, sensor frame, intensity on the tools' scale), a rawlog's as (rows, cols, 4) "
      "float32 images (NaN where no return).");
}
