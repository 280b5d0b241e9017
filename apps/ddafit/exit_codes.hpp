// Exit codes of the ddafit command line (docs/scene-format.md).
#pragma once

namespace ddafit::app {
constexpr int kExitSuccess = 0;
constexpr int kExitFailedCheck = 1;  // `verify` ran and a check failed
constexpr int kExitBadInput = 2;     // bad file, key or argument: one line on stderr
constexpr int kExitRunFailed = 3;    // the simulation stopped with a diagnosis
}  // namespace ddafit::app
