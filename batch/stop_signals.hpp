// Ctrl-C (SIGINT) and SIGTERM (what `kill` and SLURM's `scancel` send). The signal number
// lives in the one global of the command line: a signal handler can reach nothing else.
#pragma once

#include <string>

namespace ddafit::batch {

// simulate: the handlers only note the signal; the run stops at its next step, writes its
// history and a summary with status `interrupted`, and the command exits 128 + signal.
void note_stop_signals();
int stop_signal();  // 0, or the signal received

// invert, scan: the handlers print `message` and end the process at once. Every finished
// forward run is already committed to the evaluation cache (as after kill -9), so the
// message says how to resume.
void exit_on_stop_signals(const std::string& message);

// 130 after SIGINT, 143 after SIGTERM (the shell's 128 + signal).
int exit_code_for(int signal);

}  // namespace ddafit::batch
