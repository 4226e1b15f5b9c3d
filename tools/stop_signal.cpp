#include "stop_signal.hpp"

#include <atomic>
#include <csignal>

namespace ssrcl::cli {
namespace {

std::atomic<int> received{0};  // lock-free, so safe to touch from a signal handler
struct sigaction previousInt, previousTerm;

void onSignal(int sig) {
  if (received.exchange(sig) != 0) {  // the second one: the default action, now
    std::signal(sig, SIG_DFL);
    std::raise(sig);
  }
}

}  // namespace

StopSignal::StopSignal() {
  received = 0;
  struct sigaction action {};
  action.sa_handler = onSignal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESTART;  // reads and writes in flight carry on
  sigaction(SIGINT, &action, &previousInt);
  sigaction(SIGTERM, &action, &previousTerm);
}

StopSignal::~StopSignal() {
  sigaction(SIGINT, &previousInt, nullptr);
  sigaction(SIGTERM, &previousTerm, nullptr);
}

bool StopSignal::requested() const { return received.load() != 0; }
int StopSignal::signal() const { return received.load(); }

}  // namespace ssrcl::cli
