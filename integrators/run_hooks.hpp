// What a caller hands a run beside its options: an observer of its contact problems and a
// restart. None of them is a scene key, so the options structs (MoreauJeanOptions,
// EventDrivenOptions, ComplianceOptions) hold only what a scene can say, and these are
// passed next to them (integrate, run_method, moreau_jean, event_driven, compliance).
#pragma once

#include <atomic>
#include <string_view>

namespace nsb::integrators {

class ContactObserver;        // contact_stage.hpp
struct MoreauJeanCheckpoint;  // moreau_jean.hpp

struct RunHooks {
  // Shown every contact problem of the run (contact_stage.hpp), e.g. to write it to a file
  // (runs::RunRequest::dump_lcp). Not owned; nullptr: none. Compliance solves no contact
  // problem and shows it nothing.
  ContactObserver* contact_observer = nullptr;
  // A restart, Moreau–Jean only (MoreauJeanCheckpoint; not owned): `resume` starts the run
  // from a saved state instead of the system's initial one; `checkpoint` receives the state
  // at the end of a run that reached end_time.
  const MoreauJeanCheckpoint* resume = nullptr;
  MoreauJeanCheckpoint* checkpoint = nullptr;
  // A stop request (Ctrl-C in `nsbridge run` or in Python): read at every accepted step and
  // after each progress callback; once true, the run ends there with
  // RunStatus::kInterrupted. Not owned; nullptr: never stopped.
  const std::atomic<bool>* stop = nullptr;
};

// Throws std::invalid_argument when hooks ask `method` (one that cannot restart) for a
// restart: a resume or a checkpoint.
void require_no_restart(const RunHooks& hooks, std::string_view method);

}  // namespace nsb::integrators
