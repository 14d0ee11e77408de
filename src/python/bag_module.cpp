// rigid_body_sim._bag: the bag writer of `simulate --bag` (ros/bag_recorder.h) for rigid_body_sim.core, which
// imports this module only for a run with a bag: this one links the ros layer (rosbag, roscpp), the core's
// module does not. Its one function hands over the writer's opener in a capsule; both modules share the
// package's libraries, so the opener is the very one simulate_ros uses.
#include <pybind11/pybind11.h>

#include "rigid_body_sim/ros/bag_recorder.h"

namespace py = pybind11;

PYBIND11_MODULE(_bag, m) {
  m.doc() = "The bag writer of simulate --bag, for rigid_body_sim.core's World.run(bag=...).";
  m.def("opener", [] {
    static const rigid_body_sim::SinkOpener opener = rigid_body_sim::bagOpener();
    return py::capsule(&opener, "rigid_body_sim.SinkOpener");
  });
}
