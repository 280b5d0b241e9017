#include "batch/mpi_pool.hpp"

#include <mpi.h>
#include <poll.h>
#include <signal.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <functional>
#include <vector>

#include "forward/io/run_json.hpp"
#include "batch/thread_budget.hpp"
#include "forward/simulation.hpp"
#include "inverse/forward_call.hpp"
#include "inverse/model_spread.hpp"

namespace ddafit::batch {
namespace {

constexpr int kTagWork = 1, kTagResult = 2, kTagStop = 3;

SimulationResult failed(const std::string& why) {
  SimulationResult r;
  r.summary.status = RunStatus::Failed;
  r.summary.message = why;
  return r;
}

// One forward run in a child process; the child writes its encoded result to a pipe.
// Returns the encoded result, or an empty string and `why` when the child crashed, hung
// past the timeout (then it is killed) or wrote nothing.
std::string run_in_child(const std::function<SimulationResult()>& run, double timeout, std::string& why) {
  int fds[2];
  if (pipe(fds) != 0) {
    why = "cannot create a pipe for the run";
    return {};
  }
  const auto t0 = std::chrono::steady_clock::now();
  const pid_t pid = fork();
  if (pid == 0) {
    close(fds[0]);
    const SimulationResult r = run();
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const std::string text = io::encode_run(r, seconds);
    for (size_t at = 0; at < text.size();) {
      const ssize_t n = write(fds[1], text.data() + at, text.size() - at);
      if (n <= 0) _exit(3);
      at += static_cast<size_t>(n);
    }
    _exit(0);
  }
  close(fds[1]);
  std::string text;
  char buffer[65536];
  bool timed_out = false;
  while (true) {
    const double left = timeout - std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (left <= 0.0) {
      timed_out = true;
      break;
    }
    pollfd p{fds[0], POLLIN, 0};
    if (poll(&p, 1, static_cast<int>(std::min(left, 1e6) * 1000.0) + 1) <= 0) continue;
    const ssize_t n = read(fds[0], buffer, sizeof buffer);
    if (n <= 0) break;
    text.append(buffer, static_cast<size_t>(n));
  }
  close(fds[0]);
  if (timed_out) kill(pid, SIGKILL);
  int status = 0;
  waitpid(pid, &status, 0);
  if (timed_out) {
    why = "the run hung past " + std::to_string(static_cast<long>(timeout)) + " s and was killed";
    return {};
  }
  if (WIFSIGNALED(status)) {
    why = "the run crashed (signal " + std::to_string(WTERMSIG(status)) + ")";
    return {};
  }
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || text.empty()) {
    why = "the run ended without a result";
    return {};
  }
  return text;
}

}  // namespace

bool mpi_launched() {
  return std::getenv("OMPI_COMM_WORLD_SIZE") || std::getenv("PMI_SIZE") || std::getenv("PMIX_RANK");
}

MpiWorld mpi_start(int* argc, char*** argv) {
  MpiWorld w;
  if (!mpi_launched()) return w;
  MPI_Init(argc, argv);
  MPI_Comm_rank(MPI_COMM_WORLD, &w.rank);
  MPI_Comm_size(MPI_COMM_WORLD, &w.size);
  return w;
}

void mpi_stop() {
  int initialised = 0, finalised = 0;
  MPI_Initialized(&initialised);
  MPI_Finalized(&finalised);
  if (initialised && !finalised) MPI_Finalize();
}

inverse::Objective::BatchRunner mpi_batch_runner(const MpiWorld& world) {
  return [world](const std::vector<std::vector<double>>& points, const inverse::Objective::RunDone& done) {
    size_t next = 0;
    int busy = 0;
    const auto send = [&](int rank) {
      std::vector<double> message{static_cast<double>(next)};
      message.insert(message.end(), points[next].begin(), points[next].end());
      MPI_Send(message.data(), static_cast<int>(message.size()), MPI_DOUBLE, rank, kTagWork, MPI_COMM_WORLD);
      ++next;
      ++busy;
    };
    for (int rank = 1; rank < world.size && next < points.size(); ++rank) send(rank);
    while (busy > 0) {
      MPI_Status status;
      MPI_Probe(MPI_ANY_SOURCE, kTagResult, MPI_COMM_WORLD, &status);
      int length = 0;
      MPI_Get_count(&status, MPI_CHAR, &length);
      std::string text(static_cast<size_t>(length), '\0');
      MPI_Recv(text.data(), length, MPI_CHAR, status.MPI_SOURCE, kTagResult, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
      --busy;
      // The first 20 characters are the point's index; the rest is the encoded run.
      const size_t index = std::stoul(text.substr(0, 20));
      double seconds = 0.0;
      SimulationResult run;
      try {
        run = io::decode_run(text.substr(20), &seconds);
      } catch (const std::exception& e) {  // a garbled reply costs that run, not the job
        run = failed(std::string("worker rank ") + std::to_string(status.MPI_SOURCE) + " sent no readable result (" +
                     e.what() + ")");
      }
      if (next < points.size()) send(status.MPI_SOURCE);
      done(index, std::move(run), seconds);
    }
  };
}

void mpi_release_workers(const MpiWorld& world) {
  for (int rank = 1; rank < world.size; ++rank) MPI_Send(nullptr, 0, MPI_DOUBLE, rank, kTagStop, MPI_COMM_WORLD);
}

namespace {

// Ranks > 0: run what rank 0 sends (each message: the index, then the point's values)
// until it says stop.
void serve(const std::function<SimulationResult(const std::vector<double>&)>& run_point, int threads,
           double timeout) {
  set_worker_threads(threads);
  while (true) {
    MPI_Status status;
    MPI_Probe(0, MPI_ANY_TAG, MPI_COMM_WORLD, &status);
    int count = 0;
    MPI_Get_count(&status, MPI_DOUBLE, &count);
    std::vector<double> message(static_cast<size_t>(count));
    MPI_Recv(message.data(), count, MPI_DOUBLE, 0, status.MPI_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE);
    if (status.MPI_TAG == kTagStop) return;
    const std::vector<double> values(message.begin() + 1, message.end());
    const auto run = [&] { return run_point(values); };
    // A crash or a hang is retried once: a node's hiccup should not count as physics.
    std::string why, text = run_in_child(run, timeout, why);
    if (text.empty()) text = run_in_child(run, timeout, why);
    if (text.empty()) text = io::encode_run(failed(why + ", twice (worker rank " + std::to_string(status.MPI_SOURCE) + ")"), 0.0);
    char index[21];
    std::snprintf(index, sizeof index, "%-20lu", static_cast<unsigned long>(message[0]));
    const std::string reply = std::string(index, 20) + text;
    MPI_Send(reply.data(), static_cast<int>(reply.size()), MPI_CHAR, 0, kTagResult, MPI_COMM_WORLD);
  }
}

}  // namespace

void mpi_worker(const inverse::Study& study, int threads, double timeout) {
  const inverse::StudyScene scene(study);  // read once per worker; each child copies it
  serve(
      [&](const std::vector<double>& point) {
        // A point with one value more is a realisation of the model spread (model_spread.hpp).
        std::vector<double> values;
        int realisation = 0;
        inverse::split_spread_point(study, point, values, realisation);
        return scene.run(values, inverse::run_forward, realisation);
      },
      threads, timeout);
}

void mpi_ensemble_worker(const Scene& scene, int threads, double timeout) {
  serve(
      [&](const std::vector<double>& values) {
        Scene member = scene;
        member.options.realisation = values.empty() ? 0 : static_cast<int>(values.front());
        return simulate(member);
      },
      threads, timeout);
}

}  // namespace ddafit::batch
