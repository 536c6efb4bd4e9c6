// The benchmark bridge (scenes/bridge-exc5.toml and bridge-exc7.toml, an assembly of parts
// built by models/bridge_parts.hpp) against numbers recorded from the bridge model it
// replaced, which had its own class: Moreau–Jean and the event-driven integrator over the
// first 10 s (the strong phase of both records: pounding at both abutments, yielding bents)
// must give the same step counts, event counts and history samples, bit for bit.
//
// The recorded values come from revision 064659b, the Moreau–Jean rows re-recorded when its
// predictor moved the hysteretic springs onto their committed branches (docs/moreau-jean.md,
// "History-dependent forces"), a change of the scheme and not of the bridge:
//   nsbridge run scenes/bridge-exc<N>.toml --out DIR --quiet
//       --set solver.end_time=10 --set solver.method=<moreau|event_driven>
// read from DIR/summary.json (steps, steps_with_lcp), DIR/events.csv (rows, first event
// time) and DIR/history.csv (the largest |theta| and |y| over the samples, and x, theta of
// the last sample); the files print every number in its shortest round-trip form, so the
// literals below are the doubles of that run. The check runs the scene as `nsbridge run`
// does (scene::load_scene, then integrators::integrate with the scene's configuration).
#include "integrators/run.hpp"
#include "scene/scene.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <string>

namespace ni = nsb::integrators;

namespace {

struct Recorded {
  const char* scene;
  const char* method;
  long steps;                  // summary.json steps
  long steps_with_lcp;         // summary.json steps_with_lcp
  std::size_t events;          // rows of events.csv
  double first_event;          // t of the first row of events.csv [s]
  double peak_theta;           // max |theta| over history.csv [rad]
  double peak_y;               // max |y| over history.csv [m]
  double last_x, last_theta;   // x [m], theta [rad] of the last history.csv row
};

// Revision 064659b (Moreau–Jean: re-recorded, above), the command in the header comment.
constexpr Recorded kRecorded[] = {
    {"bridge-exc5.toml", "moreau", 100000, 3061, 144, 3.9666, 0.003026487991340069,
     0.22892116597230525, 0.01735974928648747, -0.0004886907221212568},
    {"bridge-exc5.toml", "event_driven", 1928, 52, 62, 3.9664488948844343, 0.00303283409469583,
     0.228926860169877, 0.01738398867169823, -0.00047505125462645977},
    {"bridge-exc7.toml", "moreau", 100000, 4468, 163, 3.9600000000000004, 0.003835381738247453,
     0.28025507406620176, 0.0170678218760368, -0.0008339339665651532},
    {"bridge-exc7.toml", "event_driven", 1992, 58, 77, 3.9598526300223953,
     0.0038314519191427424, 0.280284022985242, 0.017044418330602978, -0.0008365456781667417},
};

double peak_of(const ni::Recorder& r, const std::string& column) {
  double peak = 0.0;
  for (double v : r.series(column)) peak = std::max(peak, std::abs(v));
  return peak;
}

void check(const Recorded& expected) {
  CAPTURE(expected.scene);
  CAPTURE(expected.method);
  nsb::scene::Scene scene =
      nsb::scene::load_scene(std::string(NSB_SCENES_DIR) + "/" + expected.scene,
                             {"solver.end_time=10", std::string("solver.method=") + expected.method});
  ni::Recorder history(*scene.system, scene.output.sample_dt);
  const ni::RunResult result = ni::integrate(*scene.system, scene.run, history);
  REQUIRE(result.completed);
  CHECK(result.steps == expected.steps);
  CHECK(result.steps_with_lcp == expected.steps_with_lcp);
  REQUIRE(history.events().size() == expected.events);
  CHECK(history.events().front().t == expected.first_event);
  CHECK(peak_of(history, "theta") == expected.peak_theta);
  CHECK(peak_of(history, "y") == expected.peak_y);
  const std::size_t last = history.rows() - 1;
  CHECK(history.at(last, history.column("x")) == expected.last_x);
  CHECK(history.at(last, history.column("theta")) == expected.last_theta);
}

}  // namespace

TEST_CASE("benchmark bridge: histories recorded at 064659b, excitations 5 and 7") {
  for (const Recorded& r : kRecorded) check(r);
}
